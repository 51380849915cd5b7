// Fuzz target for engine/src/scene (libFuzzer): any bytes in, never a crash, hang or sanitizer report.
// A rejected input must carry an error that says where (a JSON pointer, "" for the document root, or
// "line L, column C" for syntax); an accepted one must build a world that steps to finite state.
#include "fuzz/fuzz_case.h"

#include <cstdint>
#include <cstdlib>
#include <string_view>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
    const std::string_view text(reinterpret_cast<const char*>(data), size);
    if (supermodal::fuzz::run_scene_case(text) == supermodal::fuzz::Verdict::BadError)
        std::abort();
    return 0;
}
