// SPDX-License-Identifier: MIT
#include "scene/json_reader.h"

#include "scene/did_you_mean.h"

#include <algorithm>
#include <charconv>
#include <climits>
#include <cmath>

namespace supermodal::scene_io
{
namespace
{

// Longest part of a string value quoted back in a message [bytes].
constexpr size_t k_max_quoted_bytes = 40;

std::string number_phrase(const Range& range)
{
    const std::string text = range.text();
    return text.empty() ? "a finite number" : "a number " + text;
}

/// "\"static\", \"kinematic\" or \"dynamic\"".
std::string choice_list(const std::vector<std::string_view>& choices)
{
    std::string out;
    for (size_t i = 0; i < choices.size(); ++i) {
        if (i > 0)
            out += i + 1 == choices.size() ? " or " : ", ";
        out += quote_text(choices[i]);
    }
    return out;
}

} // namespace

std::string pointer_join(std::string_view base, std::string_view key)
{
    std::string out(base);
    out += '/';
    for (char c : key) {
        if (c == '~')
            out += "~0";
        else if (c == '/')
            out += "~1";
        else
            out += c;
    }
    return out;
}

std::string pointer_join(std::string_view base, size_t index)
{
    return std::string(base) + '/' + std::to_string(index);
}

std::string format_number(double value)
{
    char buffer[64];
    const auto [end, ec] = std::to_chars(buffer, buffer + sizeof(buffer), value);
    return ec == std::errc{} ? std::string(buffer, end) : std::string("?");
}

std::string quote_text(std::string_view text)
{
    size_t cut = std::min(text.size(), k_max_quoted_bytes);
    // Back off to a UTF-8 character boundary so the quote stays valid UTF-8.
    while (cut < text.size() && cut > 0 && (static_cast<unsigned char>(text[cut]) & 0xC0) == 0x80)
        --cut;
    std::string out = "\"";
    for (char c : text.substr(0, cut)) {
        const auto u = static_cast<unsigned char>(c);
        out += (u < 0x20 || u == 0x7f) ? '?' : c;
    }
    if (cut < text.size())
        out += "...";
    return out + "\"";
}

std::string describe_value(const Json& value)
{
    switch (value.type()) {
    case Json::value_t::null:
        return "null";
    case Json::value_t::boolean:
        return value.get<bool>() ? "true" : "false";
    case Json::value_t::number_integer:
    case Json::value_t::number_unsigned:
        return value.dump();
    case Json::value_t::number_float:
        return format_number(value.get<double>());
    case Json::value_t::string:
        return "a string " + quote_text(value.get_ref<const std::string&>());
    case Json::value_t::array:
        if (value.empty())
            return "an empty array";
        return "an array of " + std::to_string(value.size()) + (value.size() == 1 ? " value" : " values");
    case Json::value_t::object:
        return "an object";
    default:
        return "an unexpected value";
    }
}

bool Range::contains(double value) const
{
    const bool above_min = min_open ? value > min : value >= min;
    const bool below_max = max_open ? value < max : value <= max;
    return above_min && below_max;
}

std::string Range::text() const
{
    const bool has_min = std::isfinite(min), has_max = std::isfinite(max);
    if (has_min && has_max)
        return "in " + std::string(min_open ? "(" : "[") + format_number(min) + ", " + format_number(max) +
               (max_open ? ")" : "]");
    if (has_min)
        return (min_open ? "> " : ">= ") + format_number(min);
    if (has_max)
        return (max_open ? "< " : "<= ") + format_number(max);
    return {};
}

void Reader::fail(std::string where, std::string what)
{
    if (m_failed)
        return;
    m_failed = true;
    m_error = Error{m_file, std::move(where), std::move(what)};
}

bool Reader::check_object(const Json& value, const std::string& where,
                          const std::vector<std::string_view>& allowed)
{
    if (!ok())
        return false;
    if (!value.is_object()) {
        fail(where, "expected an object, found " + describe_value(value));
        return false;
    }
    for (const auto& item : value.items()) {
        const std::string& key = item.key();
        // Annotations a scene may carry anywhere (editor schemas, notes); never read.
        if (key == "$schema" || key == "comment")
            continue;
        if (std::find(allowed.begin(), allowed.end(), key) != allowed.end())
            continue;
        std::string hint = did_you_mean(key, allowed);
        if (hint.empty())
            hint = "; known keys: " + join_names(allowed);
        fail(pointer_join(where, key), "unknown key " + quote_text(key) + hint);
        return false;
    }
    return true;
}

const Json* Reader::member(const Json& object, std::string_view key) const
{
    if (!ok() || !object.is_object())
        return nullptr;
    const auto it = object.find(std::string(key));
    return it == object.end() ? nullptr : &*it;
}

const Json* Reader::require(const Json& object, const std::string& where, std::string_view key)
{
    const Json* found = member(object, key);
    if (found == nullptr)
        fail(where, "missing required key " + quote_text(key));
    return found;
}

void Reader::read_number(const Json& value, const std::string& where, const Range& range, double& out_value)
{
    if (!ok())
        return;
    if (!value.is_number())
        return fail(where, "expected " + number_phrase(range) + ", found " + describe_value(value));
    const double v = value.get<double>();
    if (!std::isfinite(v))
        return fail(where, "expected a finite number, found " + describe_value(value));
    if (!range.contains(v))
        return fail(where, "expected " + number_phrase(range) + ", found " + describe_value(value));
    out_value = v;
}

void Reader::read_int(const Json& value, const std::string& where, const Range& range, int& out_value)
{
    if (!ok())
        return;
    // The field is an int, so the accepted range can never be wider than an int's.
    Range limited = range;
    limited.min = std::max(range.min, static_cast<double>(INT_MIN));
    limited.max = std::min(range.max, static_cast<double>(INT_MAX));
    const std::string expected = "expected an integer " + limited.text() + ", found ";
    if (!value.is_number())
        return fail(where, expected + describe_value(value));
    const double v = value.get<double>();
    if (!std::isfinite(v) || std::floor(v) != v || !limited.contains(v))
        return fail(where, expected + describe_value(value));
    out_value = static_cast<int>(v);
}

void Reader::read_numbers(const Json& value, const std::string& where, const Range& range,
                          std::span<double> out_values)
{
    if (!ok())
        return;
    const std::string range_text = range.text();
    if (!value.is_array() || value.size() != out_values.size())
        return fail(where, "expected an array of " + std::to_string(out_values.size()) + " numbers" +
                               (range_text.empty() ? "" : " " + range_text) + ", found " +
                               describe_value(value));
    std::vector<double> values(out_values.size());
    for (size_t i = 0; i < values.size(); ++i)
        read_number(value[i], pointer_join(where, i), range, values[i]);
    if (ok())
        std::copy(values.begin(), values.end(), out_values.begin());
}

void Reader::read_vec3(const Json& value, const std::string& where, const Range& range, Vec3& out_value)
{
    double v[3] = {out_value.x, out_value.y, out_value.z};
    read_numbers(value, where, range, v);
    out_value = {v[0], v[1], v[2]};
}

void Reader::read_bool(const Json& value, const std::string& where, bool& out_value)
{
    if (!ok())
        return;
    if (!value.is_boolean())
        return fail(where, "expected true or false, found " + describe_value(value));
    out_value = value.get<bool>();
}

void Reader::field_bool(const Json& object, const std::string& where, std::string_view key, bool& out_value)
{
    if (const Json* value = member(object, key))
        read_bool(*value, pointer_join(where, key), out_value);
}

void Reader::read_string(const Json& value, const std::string& where, std::string& out_value)
{
    if (!ok())
        return;
    if (!value.is_string())
        return fail(where, "expected a string, found " + describe_value(value));
    out_value = value.get<std::string>();
}

void Reader::read_choice(const Json& value, const std::string& where,
                         const std::vector<std::string_view>& choices, size_t& out_index)
{
    if (!ok())
        return;
    const std::string expected = "expected " + choice_list(choices) + ", found ";
    if (!value.is_string())
        return fail(where, expected + describe_value(value));
    const std::string& text = value.get_ref<const std::string&>();
    const auto it = std::find(choices.begin(), choices.end(), text);
    if (it == choices.end())
        return fail(where, expected + quote_text(text) + did_you_mean(text, choices));
    out_index = static_cast<size_t>(it - choices.begin());
}

void Reader::field_number(const Json& object, const std::string& where, std::string_view key,
                          const Range& range, double& out_value)
{
    if (const Json* value = member(object, key))
        read_number(*value, pointer_join(where, key), range, out_value);
}

void Reader::field_int(const Json& object, const std::string& where, std::string_view key, const Range& range,
                       int& out_value)
{
    if (const Json* value = member(object, key))
        read_int(*value, pointer_join(where, key), range, out_value);
}

void Reader::field_vec3(const Json& object, const std::string& where, std::string_view key,
                        const Range& range, Vec3& out_value)
{
    if (const Json* value = member(object, key))
        read_vec3(*value, pointer_join(where, key), range, out_value);
}

} // namespace supermodal::scene_io
