// SPDX-License-Identifier: MIT
#include "scene/overrides.h"

#include "scene/json_reader.h"

#include <cstddef>
#include <limits>
#include <string_view>
#include <vector>

namespace supermodal::scene_io
{
namespace
{

constexpr size_t k_no_index = std::numeric_limits<size_t>::max();

// The pointer's reference tokens, unescaped (RFC 6901); an error message when it is not a pointer.
std::string split_pointer(std::string_view pointer, std::vector<std::string>& tokens)
{
    if (pointer.empty() || pointer[0] != '/')
        return "a JSON pointer starts with '/', as in \"/settings/dt\"";
    std::string token;
    for (size_t i = 1; i <= pointer.size(); ++i) {
        if (i == pointer.size() || pointer[i] == '/') {
            tokens.push_back(std::move(token));
            token.clear();
        } else if (pointer[i] != '~') {
            token += pointer[i];
        } else if (i + 1 < pointer.size() && (pointer[i + 1] == '0' || pointer[i + 1] == '1')) {
            token += pointer[++i] == '0' ? '~' : '/';
        } else {
            return "'~' in a JSON pointer must be followed by 0 ('~') or 1 ('/')";
        }
    }
    return {};
}

// An array index token: decimal digits without a leading zero (RFC 6901); k_no_index otherwise.
size_t array_index(const std::string& token)
{
    // Nine digits are far past any array a scene can hold (k_max_scene_bytes) and cannot overflow.
    if (token.empty() || token.size() > 9 || (token.size() > 1 && token[0] == '0'))
        return k_no_index;
    size_t index = 0;
    for (char c : token) {
        if (c < '0' || c > '9')
            return k_no_index;
        index = index * 10 + static_cast<size_t>(c - '0');
    }
    return index;
}

std::string name_of(const std::string& pointer)
{
    return pointer.empty() ? "the top level" : pointer;
}

// Where the pointer leads: the existing value, or a new null member of an existing object when only
// the last token is missing. An error message otherwise.
std::string locate(Json& root, const std::vector<std::string>& tokens, Json*& out)
{
    Json* node = &root;
    std::string at; // the pointer of *node
    for (size_t i = 0; i < tokens.size(); ++i) {
        const std::string& token = tokens[i];
        const std::string next = pointer_join(at, token);
        if (node->is_object()) {
            auto it = node->find(token);
            if (it == node->end() && i + 1 < tokens.size())
                return next + " does not exist";
            node = it == node->end() ? &(*node)[token] : &*it;
        } else if (node->is_array()) {
            const size_t index = array_index(token);
            if (index == k_no_index)
                return name_of(at) + " is an array: expected an index, found " + quote_text(token);
            if (index >= node->size())
                return next + " does not exist: " + name_of(at) + " has " + std::to_string(node->size()) +
                       (node->size() == 1 ? " element" : " elements");
            node = &(*node)[index];
        } else {
            return name_of(at) + " is " + describe_value(*node) + ", not an object or an array";
        }
        at = next;
    }
    out = node;
    return {};
}

Status apply_override(Json& root, const SceneOverride& o, const std::string& source)
{
    std::vector<std::string> tokens;
    if (std::string error = split_pointer(o.pointer, tokens); !error.empty())
        return Error{source, o.pointer, error};
    // The value first, so that nothing is added to the DOM for a value that is refused.
    Result<Json> value = parse_json_text(o.value, source);
    if (!value) {
        const Error& e = value.error();
        return Error{source, o.pointer,
                     "the value is not JSON: " + (e.where.empty() ? "" : e.where + ": ") + e.what};
    }
    Json* target = nullptr;
    if (std::string error = locate(root, tokens, target); !error.empty())
        return Error{source, o.pointer, "cannot set: " + error};
    *target = std::move(*value);
    return {};
}

} // namespace

Status apply_overrides(Json& root, std::span<const SceneOverride> overrides, const std::string& source)
{
    for (const SceneOverride& o : overrides)
        if (Status s = apply_override(root, o, source); !s)
            return s;
    return {};
}

} // namespace supermodal::scene_io
