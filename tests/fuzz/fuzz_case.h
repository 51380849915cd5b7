// SPDX-License-Identifier: MIT
// One fuzz input through the scene loader and a few steps: shared by the libFuzzer target and the
// ctest replay of kept inputs (tests/fuzz/regressions, tests/fuzz/corpus).
#pragma once

#include <string_view>

namespace supermodal::fuzz
{

/// What became of one input.
enum class Verdict {
    Rejected, ///< the loader refused it with an error that names where
    Skipped,  ///< valid but too large to step inside the fuzzer's time (see fuzz_case.cpp)
    Unbuilt,  ///< valid, but build_world refused it (with an error)
    Stepped,  ///< built and stepped to a finite state hash
    BadError, ///< refused with an error that names no place: a finding
};

/// Loads `text` as a scene and, when accepted and cheap enough, steps it a few times.
[[nodiscard]] Verdict run_scene_case(std::string_view text);

} // namespace supermodal::fuzz
