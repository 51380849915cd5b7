// SPDX-License-Identifier: MIT
// Writing a file so that it is either complete or absent. Internal.
#pragma once

#include "supermodal/result.h"

#include <cstdint>
#include <string>
#include <vector>

namespace supermodal::render
{

/// Writes `bytes` to `path`.part and renames it to `path`; on any error removes the part file. Unlike
/// io/atomic_file.h it does not fsync: frames are written tens a second, and a reader only has to
/// never see half a file.
[[nodiscard]] Status write_complete_file(const std::string& path, const std::vector<uint8_t>& bytes);

} // namespace supermodal::render
