// SPDX-License-Identifier: MIT
// JSON text → DOM for scene files, with the guards a file from the outside world needs: a size
// cap; a nesting cap and a cap on keys per object, both checked by a plain scan before nlohmann's
// parser runs (ordered_json inserts in O(n), so one huge object would cost O(n²)); duplicate keys
// refused (nlohmann would silently keep the last one). The DOM is built from nlohmann's SAX events,
// so parse errors arrive as calls with a position rather than as exceptions.
#pragma once

#include "supermodal/result.h"

#include <cstddef>
#include <nlohmann/json.hpp>
#include <string>
#include <string_view>

namespace supermodal::scene_io
{

/// The DOM type of scene files; ordered so materials keep file order and messages list keys as written.
using Json = nlohmann::ordered_json;

/// Largest scene text accepted [bytes]; real scenes are kilobytes, so this only stops accidents.
constexpr size_t k_max_scene_bytes = size_t{64} << 20;
/// Deepest nesting of arrays and objects accepted [-]; format v1 needs 4.
constexpr int k_max_json_depth = 64;
/// Most members one JSON object may have [-].
constexpr size_t k_max_object_keys = 10000;

/// "line 3, column 7" for a 0-based byte offset in `text`; columns count UTF-8 code points from 1.
[[nodiscard]] std::string line_column(std::string_view text, size_t offset);

/// Parses JSON text into a DOM. Errors carry `file` and either "line L, column C" (syntax, limits)
/// or the JSON pointer of the offending value (number overflow, duplicate key). Never throws
/// (out of memory aside, which is fatal anyway).
[[nodiscard]] Result<Json> parse_json_text(std::string_view text, const std::string& file);

} // namespace supermodal::scene_io
