// SPDX-License-Identifier: MIT
// Setting scene values by JSON pointer. The scene is written (scene_to_json), the value put in at the
// pointer, and the text read back by the scene loader: every check and message of the loader applies,
// and any field the format has can be edited without a line of code per field.
#include "session.h"
#include "supermodal/hierarchy.h"

#include <algorithm>
#include <charconv>
#include <vector>

namespace supermodal::editor
{
namespace
{

/// RFC 6901 tokens of a pointer, unescaped; an error for text that does not start with '/'.
Result<std::vector<std::string>> split_pointer(std::string_view path)
{
    if (path.empty() || path.front() != '/')
        return Error{"", std::string(path), "expected a JSON pointer starting with '/', like /settings/dt"};
    std::vector<std::string> tokens;
    size_t start = 1;
    for (;;) {
        const size_t end = path.find('/', start);
        std::string token(
            path.substr(start, end == std::string_view::npos ? std::string_view::npos : end - start));
        std::string unescaped;
        for (size_t i = 0; i < token.size(); ++i) {
            if (token[i] == '~' && i + 1 < token.size() && (token[i + 1] == '0' || token[i + 1] == '1')) {
                unescaped += token[i + 1] == '0' ? '~' : '/';
                ++i;
            } else {
                unescaped += token[i];
            }
        }
        tokens.push_back(std::move(unescaped));
        if (end == std::string_view::npos)
            return tokens;
        start = end + 1;
    }
}

std::string escape_token(const std::string& token)
{
    std::string out;
    for (char c : token)
        out += c == '~' ? std::string("~0") : c == '/' ? std::string("~1") : std::string(1, c);
    return out;
}

std::optional<size_t> as_index(const std::string& token)
{
    size_t value = 0;
    const auto [end, ec] = std::from_chars(token.data(), token.data() + token.size(), value);
    if (ec != std::errc{} || end != token.data() + token.size() || token.empty())
        return std::nullopt;
    return value;
}

Result<Json> written_scene(const Scene& scene)
{
    // The writer's output is valid JSON by construction; parse it back into a DOM to edit.
    Json json = Json::parse(scene_to_json(scene), nullptr, /*allow_exceptions=*/false);
    if (json.is_discarded())
        return Error{scene.source, "", "internal error: the written scene is not valid JSON"};
    return json;
}

/// The value at tokens in json; with `create`, missing object keys on the way are made (the loader
/// then refuses the ones the format does not know, with a did-you-mean).
Result<Json*> locate(Json& json, const std::vector<std::string>& tokens, const std::string& path, bool create)
{
    Json* node = &json;
    std::string where;
    for (const std::string& token : tokens) {
        where += "/" + escape_token(token);
        if (node->is_object()) {
            if (!node->contains(token) && !create)
                return Error{"", where, "no such key in the scene"};
            node = &(*node)[token];
        } else if (node->is_array()) {
            const std::optional<size_t> index = as_index(token);
            if (!index || *index >= node->size())
                return Error{"", where,
                             "expected an index below " + std::to_string(node->size()) + " in " + path +
                                 ", found \"" + token + "\""};
            node = &(*node)[*index];
        } else if (node->is_null() && create) {
            *node = Json::object();
            node = &(*node)[token];
        } else {
            return Error{"", where, "cannot go into a " + std::string(node->type_name()) + " in " + path};
        }
    }
    return node;
}

/// Names of bodies or constraints in the order of the scene, for resolving "/bodies/NAME".
template <class Item, class NameOf>
std::optional<size_t> find_named(const std::vector<Item>& items, const std::string& name, NameOf name_of)
{
    for (size_t i = 0; i < items.size(); ++i)
        if (name_of(items[i]) == name)
            return i;
    return std::nullopt;
}

/// Indices of the bodies whose position or orientation differs between two written scenes.
std::vector<size_t> moved_bodies(const Json& before, const Json& after)
{
    std::vector<size_t> out;
    const Json& a = before["bodies"];
    const Json& b = after["bodies"];
    for (size_t i = 0; i < std::min(a.size(), b.size()); ++i)
        if (a[i].value("name", "") == b[i].value("name", "") &&
            (a[i].value("position", Json()) != b[i].value("position", Json()) ||
             a[i].value("orientation", Json()) != b[i].value("orientation", Json())))
            out.push_back(i);
    return out;
}

} // namespace

Result<std::string> resolve_scene_path(const Scene& scene, std::string_view path)
{
    Result<std::vector<std::string>> tokens = split_pointer(path);
    if (!tokens)
        return tokens.error();
    std::vector<std::string>& t = *tokens;
    if (t.size() >= 2 && !as_index(t[1])) {
        std::optional<size_t> index;
        if (t[0] == "bodies") {
            index = find_named(scene.bodies, t[1], [](const SceneBody& b) { return b.def.name; });
            if (!index)
                return Error{"", std::string(path), "no body named \"" + t[1] + "\""};
        } else if (t[0] == "constraints") {
            index = find_named(scene.constraints, t[1], [](const SceneConstraint& c) { return c.def.name; });
            if (!index)
                return Error{"", std::string(path), "no constraint named \"" + t[1] + "\""};
        }
        if (index)
            t[1] = std::to_string(*index);
    }
    std::string out;
    for (const std::string& token : t)
        out += "/" + escape_token(token);
    return out;
}

Result<Json> EditorSession::get(std::string_view path) const
{
    Result<std::string> resolved = resolve_scene_path(m_scene, path);
    if (!resolved)
        return resolved.error();
    Result<Json> json = written_scene(m_scene);
    if (!json)
        return json.error();
    Result<std::vector<std::string>> tokens = split_pointer(*resolved);
    Result<Json*> node = locate(*json, *tokens, *resolved, /*create=*/false);
    if (!node)
        return node.error();
    return **node;
}

Status EditorSession::set(std::string_view path, const Json& value)
{
    if (!m_world)
        return Error{"", std::string(path), "no scene is loaded"};
    Result<std::string> resolved = resolve_scene_path(m_scene, path);
    if (!resolved)
        return resolved.error();
    std::optional<Json> before;
    if (Result<Json> old = get(*resolved))
        before = *old;
    if (Status status = apply_edit(std::string(path), *resolved, value); !status)
        return status;
    // Recorded after it applied: a refused value leaves no history.
    m_history.resize(m_history_position);
    m_history.push_back({std::string(path), *resolved, std::move(before), value});
    if (m_history.size() > k_max_history) {
        m_history.erase(m_history.begin());
        m_history.front().joined = false; // the rest of a cut-off transform stands alone
    }
    m_history_position = m_history.size();
    return {};
}

Status EditorSession::undo()
{
    if (m_history_position == 0)
        return Error{"", "", "nothing to undo"};
    // Joined edits (one transform) go back together, the last first.
    for (;;) {
        const SceneEdit& e = m_history[m_history_position - 1];
        if (Status status = apply_edit(e.path, e.resolved, e.before); !status)
            return status;
        --m_history_position;
        if (!e.joined || m_history_position == 0)
            return {};
    }
}

Status EditorSession::redo()
{
    if (m_history_position == m_history.size())
        return Error{"", "", "nothing to redo"};
    for (;;) {
        const SceneEdit& e = m_history[m_history_position];
        if (Status status = apply_edit(e.path, e.resolved, e.after); !status)
            return status;
        ++m_history_position;
        if (m_history_position == m_history.size() || !m_history[m_history_position].joined)
            return {};
    }
}

Status EditorSession::apply_edit(const std::string& path, const std::string& resolved,
                                 const std::optional<Json>& value)
{
    end_mode_animation();
    Result<Json> json = written_scene(m_scene);
    if (!json)
        return json.error();
    Result<std::vector<std::string>> tokens = split_pointer(resolved);
    if (tokens->empty() || (tokens->size() == 1 && (*tokens)[0].empty()))
        return Error{"", path, "give the path of one value, not the whole scene"};
    if (value) {
        Result<Json*> node = locate(*json, *tokens, resolved, /*create=*/true);
        if (!node)
            return node.error();
        **node = *value;
    } else {
        // Undoing an edit that added a key: remove it again.
        const std::vector<std::string> parent_tokens(tokens->begin(), tokens->end() - 1);
        Result<Json*> parent = locate(*json, parent_tokens, resolved, /*create=*/false);
        if (!parent || !(*parent)->is_object())
            return Error{"", path, "cannot remove the value again"};
        (*parent)->erase(tokens->back());
    }
    Result<Scene> edited = parse_scene(json->dump(), m_scene.source);
    if (!edited)
        return edited.error();

    // Live when only shapes of rigid, non-plane bodies changed: compare the written sections.
    Result<Json> after = written_scene(*edited);
    Result<Json> before = written_scene(m_scene);
    if (!after || !before)
        return after ? before.error() : after.error();
    bool live = (*before)["settings"] == (*after)["settings"] &&
                (*before)["materials"] == (*after)["materials"] &&
                (*before)["constraints"] == (*after)["constraints"] &&
                (*before)["bodies"].size() == (*after)["bodies"].size();
    std::vector<size_t> reshaped;
    for (size_t i = 0; live && i < edited->bodies.size(); ++i) {
        Json a = (*before)["bodies"][i], b = (*after)["bodies"][i];
        const bool shape_changed = a["shape"] != b["shape"];
        a.erase("shape");
        b.erase("shape");
        live = a == b;
        if (shape_changed) {
            const SceneBody& body = edited->bodies[i];
            live = live && body.dynamics == DynamicsType::Rigid && body.def.shape.type != ShapeType::Plane &&
                   m_scene.bodies[i].def.shape.type == body.def.shape.type;
            reshaped.push_back(i);
        }
    }
    if (live) {
        for (size_t i : reshaped) {
            const Entity e = find_body(*m_world, edited->bodies[i].def.name);
            if (e.is_null() || !set_body_shape(*m_world, e, edited->bodies[i].def.shape)) {
                live = false;
                break;
            }
        }
    }
    if (!live)
        if (Status status = rebuild_keeping_state(*edited, moved_bodies(*before, *after)); !status)
            return status;
    m_scene = std::move(*edited);
    m_last_effect = live ? SetEffect::Live : SetEffect::Rebuilt;
    return {};
}

} // namespace supermodal::editor
