// SPDX-License-Identifier: MIT
#include "script.h"

#include "render_hook.h"

#include <cmath>
#include <fstream>
#include <map>
#include <sstream>
#include <vector>

namespace supermodal::editor
{
namespace
{

/// Keys each action takes besides "action" (and "comment", which any action may carry).
const std::map<std::string, std::vector<std::string>, std::less<>> k_actions = {
    {"load", {"file"}},
    {"set", {"path", "value"}},
    {"step", {"count"}},
    {"frames", {"count", "seconds"}},
    {"play", {}},
    {"pause", {}},
    {"reset", {}},
    {"press", {"widget"}},
    {"select", {"body"}},
    {"pick", {"ray", "expect"}},
    {"click", {"x", "y", "expect"}},
    {"drag", {"ray", "to", "steps", "x0", "y0", "x1", "y1"}},
    {"push", {"ray", "force", "steps", "x", "y", "depth"}},
    {"windows", {"show"}},
    {"save", {"file", "state"}},
};
/// Most steps or frames one action may ask for: a typo (1e9) should not hang CI.
constexpr double k_max_count = 1e7;

/// Thrown inside the runner only; becomes a ScriptOutcome at its top.
struct ScriptError {
    ScriptFailure failure;
    std::string where;
    std::string what;
};

[[noreturn]] void fail(std::string where, std::string what, ScriptFailure f = ScriptFailure::BadScript)
{
    throw ScriptError{f, std::move(where), std::move(what)};
}

std::string kind_of(const Json& v)
{
    return v.is_null() ? "null" : std::string(v.type_name()) + " " + v.dump();
}

const Json& required(const Json& action, const std::string& where, const char* key)
{
    if (!action.contains(key))
        fail(where, std::string("missing required key \"") + key + "\"");
    return action.at(key);
}

std::string text(const Json& action, const std::string& where, const char* key)
{
    const Json& v = required(action, where, key);
    if (!v.is_string())
        fail(where + "/" + key, "expected a string, found " + kind_of(v));
    return v.get<std::string>();
}

int count(const Json& action, const std::string& where, const char* key, int fallback)
{
    if (!action.contains(key))
        return fallback;
    const Json& v = action.at(key);
    if (!v.is_number() || v.get<double>() != std::floor(v.get<double>()) || v.get<double>() < 1.0 ||
        v.get<double>() > k_max_count)
        fail(where + "/" + key, "expected an integer in [1, 1e7], found " + kind_of(v));
    return static_cast<int>(v.get<double>());
}

double number(const Json& action, const std::string& where, const char* key, double fallback)
{
    if (!action.contains(key))
        return fallback;
    const Json& v = action.at(key);
    if (!v.is_number() || !std::isfinite(v.get<double>()))
        fail(where + "/" + key, "expected a finite number, found " + kind_of(v));
    return v.get<double>();
}

Vec3 vec3(const Json& v, const std::string& where)
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

Ray ray(const Json& action, const std::string& where)
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
Ray pixel_ray(const Json& action, const std::string& where, const EditorSession& session, EditorUi& ui,
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
Ray ray_or_pixel(const Json& action, const std::string& where, const EditorSession& session, EditorUi& ui,
                 const char* kx, const char* ky)
{
    if (action.contains("ray") == action.contains(kx))
        fail(where, std::string("expected either \"ray\" or the pixel \"") + kx + "\", \"" + ky + "\"");
    return action.contains("ray") ? ray(action, where) : pixel_ray(action, where, session, ui, kx, ky);
}

void check(const Status& status, const std::string& where)
{
    if (!status)
        fail(where, status.error().message());
}

std::string vec_text(const Vec3& v)
{
    std::ostringstream out;
    out << "[" << v.x << ", " << v.y << ", " << v.z << "]";
    return out.str();
}

void run_action(const Json& action, const std::string& where, const std::filesystem::path& base_dir,
                EditorSession& session, EditorUi& ui, std::ostream& log)
{
    if (!action.is_object())
        fail(where, "expected an object {\"action\": ...}, found " + kind_of(action));
    const std::string verb = text(action, where, "action");
    const auto known = k_actions.find(verb);
    if (known == k_actions.end()) {
        std::string names;
        for (const auto& [name, keys] : k_actions)
            names += (names.empty() ? "" : ", ") + name;
        fail(where + "/action", "unknown action \"" + verb + "\"; actions are: " + names);
    }
    for (const auto& item : action.items())
        if (item.key() != "action" && item.key() != "comment" &&
            std::find(known->second.begin(), known->second.end(), item.key()) == known->second.end())
            fail(where + "/" + item.key(), "unknown key \"" + item.key() + "\" for action \"" + verb + "\"");
    if (verb != "load" && !session.has_world())
        fail(where, "no scene is loaded: start the script with {\"action\": \"load\", \"file\": ...}");

    log << where << " " << verb;
    if (verb == "load") {
        const std::filesystem::path file = base_dir / text(action, where, "file");
        check(session.load(file.string()), where + "/file");
        ui.select_body("");
        log << " " << file.string() << ": " << session.scene().bodies.size() << " bodies";
    } else if (verb == "set") {
        const std::string path = text(action, where, "path");
        check(session.set(path, required(action, where, "value")), where);
        log << " " << path << " = " << action["value"].dump()
            << (session.last_set_effect() == SetEffect::Live ? " (live)" : " (rebuilt)");
    } else if (verb == "step") {
        const int n = count(action, where, "count", 1);
        session.step(n);
        log << " " << n << ": t = " << session.world().time() << " s, " << session.ms_per_step()
            << " ms/step";
    } else if (verb == "frames") {
        const int n = count(action, where, "count", 1);
        const double seconds = number(action, where, "seconds", 1.0 / 60.0);
        if (!(seconds > 0.0 && seconds <= 1.0))
            fail(where + "/seconds", "expected seconds per frame in (0, 1]");
        for (int i = 0; i < n; ++i)
            ui.frame(seconds);
        log << " " << n << ": t = " << session.world().time() << " s";
    } else if (verb == "play") {
        session.play();
    } else if (verb == "pause") {
        session.pause();
    } else if (verb == "reset") {
        check(session.reset(), where);
    } else if (verb == "press") {
        const std::string widget = text(action, where, "widget");
        check(ui.press(widget), where + "/widget");
        log << " \"" << widget << "\"";
        if (!ui.last_error().empty())
            fail(where, "the widget's action failed: " + ui.last_error());
    } else if (verb == "select") {
        const std::string body = text(action, where, "body");
        if (find_body(session.world(), body).is_null())
            fail(where + "/body", "no body named \"" + body + "\"");
        ui.select_body(body);
    } else if (verb == "pick" || verb == "click") {
        const std::optional<PickHit> hit = session.pick(
            verb == "pick" ? ray(action, where) : pixel_ray(action, where, session, ui, "x", "y"));
        const std::string name = hit ? hit->name : std::string();
        if (hit)
            ui.select_body(name);
        log << " " << (hit ? name + " at " + vec_text(hit->point) : std::string("nothing"));
        if (action.contains("expect") && text(action, where, "expect") != name)
            fail(where + "/expect",
                 "expected the ray to hit \"" + action["expect"].get<std::string>() + "\", it hit " +
                     (hit ? "\"" + name + "\"" : std::string("nothing")),
                 ScriptFailure::CheckFailed);
    } else if (verb == "drag") {
        const Ray grab = ray_or_pixel(action, where, session, ui, "x0", "y0");
        const std::optional<PickHit> hit = session.pick(grab);
        check(session.drag_begin(grab), where);
        if (action.contains("ray")) {
            session.drag_to(vec3(required(action, where, "to"), where + "/to"));
        } else {
            // The mouse moves the grabbed point in the plane through it that faces the grab ray.
            const Ray to = pixel_ray(action, where, session, ui, "x1", "y1");
            const Vec3 n = normalized(grab.direction), d = normalized(to.direction);
            const double facing = dot(d, n);
            if (!(facing > 1e-6))
                fail(where + "/x1", "the pixel's ray does not meet the drag plane");
            session.drag_to(to.origin + (dot(hit->point - to.origin, n) / facing) * d);
        }
        const int n = count(action, where, "steps", 1);
        session.step(n);
        log << " " << body_name(session.world(), session.drag()->body) << " for " << n << " steps";
        session.drag_end();
    } else if (verb == "push") {
        const Ray r = ray_or_pixel(action, where, session, ui, "x", "y");
        const int n = count(action, where, "steps", 1);
        if (action.contains("depth") == action.contains("force"))
            fail(where, "expected either \"force\" [N] or \"depth\" [m]");
        if (action.contains("depth")) {
            const double depth = number(action, where, "depth", 0.0);
            check(session.mould(r, depth, n), where);
            session.step(n);
            log << " " << depth << " m deep for " << n << " steps: reached " << session.mould_depth_reached()
                << " m";
        } else {
            const double force = number(action, where, "force", 0.0);
            check(session.push(r, force, n), where);
            session.step(n);
            log << " " << force << " N for " << n << " steps";
        }
    } else if (verb == "windows") {
        const Json& show = required(action, where, "show");
        if (!show.is_boolean())
            fail(where + "/show", "expected true or false, found " + kind_of(show));
        ui.show_windows = show.get<bool>();
    } else if (verb == "save") {
        const std::filesystem::path file = base_dir / text(action, where, "file");
        std::string state = "current";
        if (action.contains("state"))
            state = text(action, where, "state");
        if (state != "current" && state != "initial")
            fail(where + "/state", "expected \"current\" or \"initial\", found \"" + state + "\"");
        check(session.save(file.string(), state == "current"), where + "/file");
        log << " " << file.string();
    }
    log << "\n";
}

} // namespace

ScriptOutcome run_script_text(std::string_view script, const std::string& source,
                              const std::filesystem::path& base_dir, EditorSession& session, EditorUi& ui,
                              std::ostream& log)
{
    ScriptOutcome outcome;
    Json root;
    try {
        root = Json::parse(script.begin(), script.end());
    } catch (const Json::exception& e) {
        outcome.failure = ScriptFailure::BadScript;
        outcome.error = Error{source, "", std::string("invalid JSON: ") + e.what()};
        return outcome;
    }
    try {
        if (!root.is_object() || !root.contains("actions") || !root["actions"].is_array())
            fail("", "expected an object {\"actions\": [ ... ]}");
        for (const auto& item : root.items())
            if (item.key() != "actions" && item.key() != "comment")
                fail("/" + item.key(), "unknown key \"" + item.key() + "\"; a script has \"actions\"");
        const Json& actions = root["actions"];
        for (size_t i = 0; i < actions.size(); ++i) {
            run_action(actions[i], "/actions/" + std::to_string(i), base_dir, session, ui, log);
            ++outcome.actions_run;
        }
    } catch (const ScriptError& e) {
        log << "\n";
        outcome.failure = e.failure;
        outcome.error = Error{source, e.where, e.what};
    }
    return outcome;
}

ScriptOutcome run_script_file(const std::string& path, EditorSession& session, EditorUi& ui,
                              std::ostream& log)
{
    std::ifstream in(path, std::ios::binary);
    if (!in) {
        ScriptOutcome outcome;
        outcome.failure = ScriptFailure::BadScript;
        outcome.error = Error{path, "", "cannot open the script"};
        return outcome;
    }
    std::ostringstream text;
    text << in.rdbuf();
    return run_script_text(text.str(), path, std::filesystem::path(path).parent_path(), session, ui, log);
}

} // namespace supermodal::editor
