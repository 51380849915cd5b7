// SPDX-License-Identifier: MIT
#include "scene/json_text.h"

#include "scene/json_reader.h"

#include <cstdint>
#include <exception>
#include <new>
#include <utility>
#include <vector>

namespace supermodal::scene_io
{
namespace
{

// Longest excerpt of a parser message or literal quoted back to the user [bytes].
constexpr size_t k_max_quoted_bytes = 200;

/// Cheap pass over the raw text, before nlohmann builds anything: nesting depth and object sizes.
/// It skips string contents (brackets inside strings do not count) and validates nothing else.
Status scan_structure(std::string_view text, const std::string& file)
{
    struct Open {
        bool is_object;
        size_t members;
    };
    std::vector<Open> open;
    bool in_string = false, escaped = false;
    for (size_t i = 0; i < text.size(); ++i) {
        const char c = text[i];
        if (in_string) {
            if (escaped)
                escaped = false;
            else if (c == '\\')
                escaped = true;
            else if (c == '"')
                in_string = false;
            continue;
        }
        if (c == '"') {
            in_string = true;
        } else if (c == '{' || c == '[') {
            if (open.size() >= static_cast<size_t>(k_max_json_depth))
                return Error{file, line_column(text, i),
                             "JSON nested deeper than " + std::to_string(k_max_json_depth) + " levels"};
            open.push_back({c == '{', 1});
        } else if (c == '}' || c == ']') {
            if (!open.empty())
                open.pop_back();
        } else if (c == ',' && !open.empty() && open.back().is_object) {
            if (++open.back().members > k_max_object_keys)
                return Error{file, line_column(text, i),
                             "JSON object has more than " + std::to_string(k_max_object_keys) + " keys"};
        }
    }
    return {};
}

/// Printable, bounded copy of parser text: control bytes and invalid UTF-8 would garble a terminal.
std::string printable(std::string_view s)
{
    std::string out;
    for (char c : s.substr(0, k_max_quoted_bytes)) {
        const auto u = static_cast<unsigned char>(c);
        out += (u < 0x20 || u == 0x7f || u >= 0x80) ? '?' : c;
    }
    if (s.size() > k_max_quoted_bytes)
        out += "...";
    return out;
}

/// nlohmann's what() without its "[json.exception.parse_error.101] parse error at line 1, column 5: "
/// prefix, since we compute and report the location ourselves.
std::string parser_detail(const char* what)
{
    const std::string_view text(what);
    size_t start = text.find("column ");
    start = start == std::string_view::npos ? text.find("] ") : text.find(": ", start);
    if (start == std::string_view::npos)
        return printable(text);
    return printable(text.substr(start + 2));
}

/// Builds the DOM from nlohmann's SAX events (as its own json_sax_dom_parser does) while knowing the
/// JSON pointer of the value being read, so that errors raised inside the parser, such as a number
/// literal beyond double range, can name it; it also refuses duplicate keys. Errors come back through
/// parse_error(), not exceptions, and returning false stops the parser at once.
class DomBuilder
{
  public:
    DomBuilder(Json& root, std::string_view text, const std::string& file)
        : m_root(root), m_text(text), m_file(file)
    {
    }

    [[nodiscard]] bool failed() const { return m_failed; }
    [[nodiscard]] const Error& error() const { return m_error; }

    bool null() { return add(nullptr); }
    bool boolean(bool value) { return add(value); }
    bool number_integer(Json::number_integer_t value) { return add(value); }
    bool number_unsigned(Json::number_unsigned_t value) { return add(value); }
    bool number_float(Json::number_float_t value, const std::string&) { return add(value); }
    bool string(std::string& value) { return add(std::move(value)); }
    bool binary(Json::binary_t&) { return fail(pointer(), "binary values are not JSON"); }
    bool start_object(std::size_t) { return open(Json::value_t::object); }
    bool start_array(std::size_t) { return open(Json::value_t::array); }
    bool end_object() { return close(); }
    bool end_array() { return close(); }

    bool key(std::string& key)
    {
        Json& object = *m_open.back();
        m_keys.back() = key;
        // Linear in the object's size, like ordered_json's own insert; the structure scan capped it.
        if (object.contains(key))
            return fail(pointer(), "duplicate key " + quote_text(key) + " in the same object");
        m_member = &object[std::move(key)];
        return true;
    }

    bool parse_error(std::size_t position, const std::string& last_token, const Json::exception& ex)
    {
        // 406: a number literal beyond double range ("1e999"); the token is the literal.
        if (ex.id == 406)
            return fail(pointer(), "expected a finite number, found " + printable(last_token));
        // position counts characters read, so the offending byte sits at position − 1.
        return fail(line_column(m_text, position > 0 ? position - 1 : 0),
                    "invalid JSON: " + parser_detail(ex.what()));
    }

  private:
    template <class Value> bool add(Value&& value)
    {
        if (m_open.empty())
            m_root = Json(std::forward<Value>(value));
        else if (m_open.back()->is_array())
            m_open.back()->emplace_back(std::forward<Value>(value));
        else
            *m_member = Json(std::forward<Value>(value));
        return true;
    }
    bool open(Json::value_t type)
    {
        Json* container = &m_root;
        if (!m_open.empty() && m_open.back()->is_array())
            container = &m_open.back()->emplace_back(type);
        else if (!m_open.empty())
            container = &(*m_member = Json(type));
        else
            m_root = Json(type);
        m_open.push_back(container);
        m_keys.emplace_back();
        return true;
    }
    bool close()
    {
        m_open.pop_back();
        m_keys.pop_back();
        return true;
    }
    bool fail(std::string where, std::string what)
    {
        m_failed = true;
        m_error = Error{m_file, std::move(where), std::move(what)};
        return false;
    }
    /// JSON pointer of the value being read: an array's element being read is the last one when it
    /// is an open container, else the next one.
    [[nodiscard]] std::string pointer() const
    {
        std::string out;
        for (size_t i = 0; i < m_open.size(); ++i) {
            const Json& c = *m_open[i];
            if (c.is_array())
                out = pointer_join(out, i + 1 < m_open.size() ? c.size() - 1 : c.size());
            else
                out = pointer_join(out, m_keys[i]);
        }
        return out;
    }

    Json& m_root;
    std::string_view m_text;
    const std::string& m_file;
    std::vector<Json*> m_open;       ///< Open containers, outermost first.
    std::vector<std::string> m_keys; ///< Per open container: the object key being read.
    Json* m_member = nullptr;        ///< Slot of the object member being read.
    Error m_error;
    bool m_failed = false;
};

} // namespace

std::string line_column(std::string_view text, size_t offset)
{
    offset = std::min(offset, text.size());
    size_t line = 1, column = 1;
    for (size_t i = 0; i < offset; ++i) {
        const auto u = static_cast<unsigned char>(text[i]);
        if (u == '\n') {
            ++line;
            column = 1;
        } else if ((u & 0xC0) != 0x80) { // UTF-8 continuation bytes do not start a new column
            ++column;
        }
    }
    return "line " + std::to_string(line) + ", column " + std::to_string(column);
}

Result<Json> parse_json_text(std::string_view text, const std::string& file)
{
    if (text.size() > k_max_scene_bytes)
        return Error{file, "",
                     "scene is " + std::to_string(text.size()) + " bytes; the limit is " +
                         std::to_string(k_max_scene_bytes) + " bytes"};
    if (Status s = scan_structure(text, file); !s)
        return s.error();
    Json root;
    DomBuilder builder(root, text, file);
    // sax_parse reports through the builder and does not throw for JSON input; the catch keeps the
    // no-exception promise of the public API should that change.
    try {
        const bool parsed = Json::sax_parse(text.begin(), text.end(), &builder);
        if (builder.failed())
            return builder.error();
        if (!parsed)
            return Error{file, "", "invalid JSON"};
        return root;
    } catch (const std::bad_alloc&) {
        return Error{file, "", "out of memory while parsing the scene"};
    } catch (const std::exception& e) {
        return Error{file, "", std::string("cannot parse the scene: ") + printable(e.what())};
    }
}

} // namespace supermodal::scene_io
