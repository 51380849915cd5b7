// SPDX-License-Identifier: MIT
// Typed reading of scene JSON with errors that name the JSON pointer, what was expected and what was
// found. The Reader keeps the first error and turns every later read into a no-op, so readers are
// written as straight-line code and checked once at the end: the first problem in reading order is
// the one reported, and a failed read leaves its output at the default.
#pragma once

#include "scene/json_text.h"
#include "supermodal/math.h"
#include "supermodal/result.h"

#include <cstddef>
#include <limits>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace supermodal::scene_io
{

/// `base` + "/" + `key`, escaping "~" and "/" in the key as RFC 6901 says.
[[nodiscard]] std::string pointer_join(std::string_view base, std::string_view key);
/// `base` + "/" + `index`.
[[nodiscard]] std::string pointer_join(std::string_view base, size_t index);

/// Shortest text that reads back to the same double ("0.1", "1e-05", "inf").
[[nodiscard]] std::string format_number(double value);
/// `text` in double quotes for a message: control bytes become '?', long text is cut at 40 bytes.
[[nodiscard]] std::string quote_text(std::string_view text);
/// How a JSON value reads after "found": "-1", "a string \"abc\"", "an array of 2 values", "null".
[[nodiscard]] std::string describe_value(const Json& value);

/// Allowed values of a number; infinite ends are unbounded. Non-finite numbers are always refused.
struct Range {
    double min = -std::numeric_limits<double>::infinity();
    double max = std::numeric_limits<double>::infinity();
    bool min_open = false; ///< True: min itself is excluded.
    bool max_open = false; ///< True: max itself is excluded.

    [[nodiscard]] bool contains(double value) const;
    /// "> 0", ">= 1", "in (0, 4]", or "" when unbounded.
    [[nodiscard]] std::string text() const;
};

/// Any finite number.
[[nodiscard]] inline Range any_number()
{
    return {};
}
/// Numbers > min.
[[nodiscard]] inline Range above(double min)
{
    return {.min = min, .min_open = true};
}
/// Numbers >= min.
[[nodiscard]] inline Range at_least(double min)
{
    return {.min = min};
}
/// Numbers in [min, max].
[[nodiscard]] inline Range closed(double min, double max)
{
    return {.min = min, .max = max};
}

/// Reads typed values out of a JSON DOM, keeping the first error.
class Reader
{
  public:
    explicit Reader(std::string file) : m_file(std::move(file)) {}

    [[nodiscard]] bool ok() const { return !m_failed; }
    /// The first error recorded; meaningful only when !ok().
    [[nodiscard]] const Error& error() const { return m_error; }
    /// Records an error unless one is already recorded.
    void fail(std::string where, std::string what);

    /// Checks that `value` is an object whose keys are all in `allowed` ("$schema" and "comment"
    /// always pass); records the first stranger with a did-you-mean. False if not ok afterwards.
    bool check_object(const Json& value, const std::string& where,
                      const std::vector<std::string_view>& allowed);
    /// The member `key` of an object, or null when absent (or when not ok: reading stops).
    [[nodiscard]] const Json* member(const Json& object, std::string_view key) const;
    /// The member `key`, recording `missing required key "key"` at `where` when absent.
    const Json* require(const Json& object, const std::string& where, std::string_view key);

    /// A finite number in `range`.
    void read_number(const Json& value, const std::string& where, const Range& range, double& out_value);
    /// An integral number in `range` (2 and 2.0 pass, 2.5 does not) that fits an int.
    void read_int(const Json& value, const std::string& where, const Range& range, int& out_value);
    /// An array of exactly out_values.size() finite numbers, each in `range`.
    void read_numbers(const Json& value, const std::string& where, const Range& range,
                      std::span<double> out_values);
    /// An array of 3 finite numbers in `range`.
    void read_vec3(const Json& value, const std::string& where, const Range& range, Vec3& out_value);
    /// true or false.
    void read_bool(const Json& value, const std::string& where, bool& out_value);
    /// A string.
    void read_string(const Json& value, const std::string& where, std::string& out_value);
    /// One of `choices` (a string); out_index is its position in `choices`.
    void read_choice(const Json& value, const std::string& where,
                     const std::vector<std::string_view>& choices, size_t& out_index);

    /// The read_* above for an optional member `key` of `object`: nothing happens when it is absent.
    void field_number(const Json& object, const std::string& where, std::string_view key, const Range& range,
                      double& out_value);
    void field_int(const Json& object, const std::string& where, std::string_view key, const Range& range,
                   int& out_value);
    void field_vec3(const Json& object, const std::string& where, std::string_view key, const Range& range,
                    Vec3& out_value);
    void field_bool(const Json& object, const std::string& where, std::string_view key, bool& out_value);

  private:
    std::string m_file;
    Error m_error;
    bool m_failed = false;
};

} // namespace supermodal::scene_io
