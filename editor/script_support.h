// SPDX-License-Identifier: MIT
// What the script actions share (editor/script.cpp, script_parts.cpp): the action's context, reading its
// keys with errors that name their JSON pointer, and the one way a run fails.
#pragma once

#include "render_hook.h"
#include "script.h"
#include "supermodal/body.h"

#include <cmath>
#include <sstream>
#include <string>

namespace supermodal::editor::script
{

/// Most steps or frames one action may ask for: a typo (1e9) should not hang CI.
constexpr double k_max_count = 1e7;

/// Thrown inside the runner only; becomes a ScriptOutcome at its top.
struct ScriptError {
    ScriptFailure failure;
    std::string where;
    std::string what;
};

[[noreturn]] inline void fail(std::string where, std::string what, ScriptFailure f = ScriptFailure::BadScript)
{
    throw ScriptError{f, std::move(where), std::move(what)};
}

inline std::string kind_of(const Json& v)
{
    return v.is_null() ? "null" : std::string(v.type_name()) + " " + v.dump();
}

inline const Json& required(const Json& action, const std::string& where, const char* key)
{
    if (!action.contains(key))
        fail(where, std::string("missing required key \"") + key + "\"");
    return action.at(key);
}

inline std::string text(const Json& action, const std::string& where, const char* key)
{
    const Json& v = required(action, where, key);
    if (!v.is_string())
        fail(where + "/" + key, "expected a string, found " + kind_of(v));
    return v.get<std::string>();
}

inline int count(const Json& action, const std::string& where, const char* key, int fallback)
{
    if (!action.contains(key))
        return fallback;
    const Json& v = action.at(key);
    if (!v.is_number() || v.get<double>() != std::floor(v.get<double>()) || v.get<double>() < 1.0 ||
        v.get<double>() > k_max_count)
        fail(where + "/" + key, "expected an integer in [1, 1e7], found " + kind_of(v));
    return static_cast<int>(v.get<double>());
}

inline double number(const Json& action, const std::string& where, const char* key, double fallback)
{
    if (!action.contains(key))
        return fallback;
    const Json& v = action.at(key);
    if (!v.is_number() || !std::isfinite(v.get<double>()))
        fail(where + "/" + key, "expected a finite number, found " + kind_of(v));
    return v.get<double>();
}

inline Vec3 vec3(const Json& v, const std::string& where)
{
    if (!v.is_array() || v.size() != 3)
        fail(where, "expected an array of 3 numbers, found " + kind_of(v));
    Vec3 out;
    for (int i = 0; i < 3; ++i) {
        if (!v[i].is_number() || !std::isfinite(v[i].get<double>()))
            fail(where + "/" + std::to_string(i), "expected a finite number, found " + kind_of(v[i]));
        out[i] = v[i].get<double>();
    }
    return out;
}

inline Ray ray(const Json& action, const std::string& where)
{
    const Json& r = required(action, where, "ray");
    const std::string rw = where + "/ray";
    if (!r.is_object() || !r.contains("origin") || !r.contains("direction") || r.size() != 2)
        fail(rw, "expected {\"origin\": [x, y, z], \"direction\": [x, y, z]}, found " + kind_of(r));
    Ray out{vec3(r["origin"], rw + "/origin"), vec3(r["direction"], rw + "/direction")};
    if (!(length(out.direction) > 0.0))
        fail(rw + "/direction", "expected a non-zero direction");
    return out;
}

/// The ray through the pixel at keys (kx, ky) of the UI's display, through the scene camera.
inline Ray pixel_ray(const Json& action, const std::string& where, const EditorSession& session, EditorUi& ui,
                     const char* kx, const char* ky)
{
    const double x = number(action, where, kx, NAN), y = number(action, where, ky, NAN);
    if (!(x >= 0.0 && x <= ui.width()))
        fail(where + "/" + kx, "expected a pixel in [0, " + std::to_string(ui.width()) + "], found " +
                                   kind_of(action.value(kx, Json())));
    if (!(y >= 0.0 && y <= ui.height()))
        fail(where + "/" + ky, "expected a pixel in [0, " + std::to_string(ui.height()) + "], found " +
                                   kind_of(action.value(ky, Json())));
    Result<Ray> r = screen_ray(session, ui, x, y);
    if (!r)
        fail(where, r.error().what);
    return *r;
}

/// A ray given as "ray" or as pixel keys; exactly one of the two.
inline Ray ray_or_pixel(const Json& action, const std::string& where, const EditorSession& session,
                        EditorUi& ui, const char* kx, const char* ky)
{
    if (action.contains("ray") == action.contains(kx))
        fail(where, std::string("expected either \"ray\" or the pixel \"") + kx + "\", \"" + ky + "\"");
    return action.contains("ray") ? ray(action, where) : pixel_ray(action, where, session, ui, kx, ky);
}

inline void check(const Status& status, const std::string& where)
{
    if (!status)
        fail(where, status.error().message());
}

inline std::string vec_text(const Vec3& v)
{
    std::ostringstream out;
    out << "[" << v.x << ", " << v.y << ", " << v.z << "]";
    return out.str();
}

/// What an action runs against; `where` is the action's JSON pointer.
struct ActionContext {
    const Json& action;
    const std::string& where;
    const std::filesystem::path& base_dir;
    EditorSession& session;
    EditorUi& ui;
    std::ostream& log;
};

/// "body", or the selected body when it is absent; an error naming the key when there is neither.
inline std::string body_or_selected(const ActionContext& c)
{
    const std::string name =
        c.action.contains("body") ? text(c.action, c.where, "body") : c.ui.selected_body();
    if (name.empty())
        fail(c.where, "expected \"body\" (no body is selected)");
    if (find_body(c.session.world(), name).is_null())
        fail(c.where + (c.action.contains("body") ? "/body" : ""), "no body named \"" + name + "\"");
    return name;
}

/// A failed session call: the message points at the key it names when the action has it.
inline void check_keyed(const ActionContext& c, const Error& e)
{
    fail(!e.where.empty() && c.action.contains(e.where) ? c.where + "/" + e.where : c.where, e.what);
}

/// Exactly one of "at" (a world point) and a ray ("ray" or the pixel "x", "y").
inline bool at_or_ray(const ActionContext& c)
{
    const int given =
        int(c.action.contains("at")) + int(c.action.contains("ray")) + int(c.action.contains("x"));
    if (given != 1)
        fail(c.where, R"(expected one of "at" [x, y, z], "ray" or the pixel "x", "y")");
    return c.action.contains("at");
}

inline std::string optional_text(const ActionContext& c, const char* key)
{
    return c.action.contains(key) ? text(c.action, c.where, key) : std::string();
}

// The Parts library's actions (script_parts.cpp).
void run_parts(const ActionContext& c);
void run_add_part(const ActionContext& c);
void run_attach(const ActionContext& c);
void run_detach(const ActionContext& c);

} // namespace supermodal::editor::script
