// SPDX-License-Identifier: MIT
// Atomic file output: the scene writer and the exporters.
#pragma once

#include "supermodal/result.h"

#include <cstddef>
#include <string>

namespace supermodal
{

/// Writes `size` bytes to `path` through a temporary file in the same folder, flushed and synced, then
/// renamed over `path`: a reader never sees half a file and a failure leaves nothing behind.
[[nodiscard]] Status write_file_atomically(const std::string& path, const void* data, size_t size);

} // namespace supermodal
