// SPDX-License-Identifier: MIT
#include "script.h"

#include "render_hook.h"
#include "script_support.h"
#include "supermodal/body.h"

#include <array>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <map>
#include <sstream>
#include <vector>

namespace supermodal::editor
{
namespace
{
using namespace script;

void run_load(const ActionContext& c)
{
    const std::filesystem::path file = c.base_dir / text(c.action, c.where, "file");
    check(c.session.load(file.string()), c.where + "/file");
    c.ui.select_body("");
    c.log << " " << file.string() << ": " << c.session.scene().bodies.size() << " bodies";
}

void run_set(const ActionContext& c)
{
    const std::string path = text(c.action, c.where, "path");
    check(c.session.set(path, required(c.action, c.where, "value")), c.where);
    c.log << " " << path << " = " << c.action["value"].dump()
          << (c.session.last_set_effect() == SetEffect::Live ? " (live)" : " (rebuilt)");
}

void run_step(const ActionContext& c)
{
    const int n = count(c.action, c.where, "count", 1);
    c.session.step(n);
    c.log << " " << n << ": t = " << c.session.world().time() << " s, " << c.session.ms_per_step()
          << " ms/step";
}

void run_frames(const ActionContext& c)
{
    const int n = count(c.action, c.where, "count", 1);
    const double seconds = number(c.action, c.where, "seconds", 1.0 / 60.0);
    if (!(seconds > 0.0 && seconds <= 1.0))
        fail(c.where + "/seconds", "expected seconds per frame in (0, 1]");
    for (int i = 0; i < n; ++i)
        c.ui.host_frame(seconds);
    c.log << " " << n << ": t = " << c.session.world().time() << " s";
}

void run_play(const ActionContext& c)
{
    c.session.play();
}

void run_pause(const ActionContext& c)
{
    c.session.pause();
}

void run_reset(const ActionContext& c)
{
    check(c.session.reset(), c.where);
}

void run_undo(const ActionContext& c)
{
    check(c.session.undo(), c.where);
    c.log << " (" << c.session.history_position() << " of " << c.session.history().size()
          << " edits applied)";
}

void run_redo(const ActionContext& c)
{
    check(c.session.redo(), c.where);
    c.log << " (" << c.session.history_position() << " of " << c.session.history().size()
          << " edits applied)";
}

void run_press(const ActionContext& c)
{
    const std::string widget = text(c.action, c.where, "widget");
    check(c.ui.press(widget), c.where + "/widget");
    c.log << " \"" << widget << "\"";
    if (!c.ui.last_error().empty())
        fail(c.where, "the widget's action failed: " + c.ui.last_error());
}

void run_select(const ActionContext& c)
{
    const std::string body = text(c.action, c.where, "body");
    if (find_body(c.session.world(), body).is_null())
        fail(c.where + "/body", "no body named \"" + body + "\"");
    c.ui.select_body(body);
}

/// Pick along `r`, select what it hits, and check "expect" when given.
void pick_along(const ActionContext& c, const Ray& r)
{
    const std::optional<PickHit> hit = c.session.pick(r);
    const std::string name = hit ? hit->name : std::string();
    if (hit)
        c.ui.select_body(name);
    c.log << " " << (hit ? name + " at " + vec_text(hit->point) : std::string("nothing"));
    if (c.action.contains("expect") && text(c.action, c.where, "expect") != name)
        fail(c.where + "/expect",
             "expected the ray to hit \"" + c.action["expect"].get<std::string>() + "\", it hit " +
                 (hit ? "\"" + name + "\"" : std::string("nothing")),
             ScriptFailure::CheckFailed);
}

void run_pick(const ActionContext& c)
{
    pick_along(c, ray(c.action, c.where));
}

void run_click(const ActionContext& c)
{
    pick_along(c, pixel_ray(c.action, c.where, c.session, c.ui, "x", "y"));
}

void run_drag(const ActionContext& c)
{
    const Ray grab = ray_or_pixel(c.action, c.where, c.session, c.ui, "x0", "y0");
    const std::optional<PickHit> hit = c.session.pick(grab);
    check(c.session.drag_begin(grab), c.where);
    if (c.action.contains("ray")) {
        c.session.drag_to(vec3(required(c.action, c.where, "to"), c.where + "/to"));
    } else {
        // The mouse moves the grabbed point in the plane through it that faces the grab ray.
        const Ray to = pixel_ray(c.action, c.where, c.session, c.ui, "x1", "y1");
        const Vec3 n = normalized(grab.direction), d = normalized(to.direction);
        const double facing = dot(d, n);
        if (!(facing > 1e-6))
            fail(c.where + "/x1", "the pixel's ray does not meet the drag plane");
        c.session.drag_to(to.origin + (dot(hit->point - to.origin, n) / facing) * d);
    }
    const int n = count(c.action, c.where, "steps", 1);
    c.session.step(n);
    c.log << " " << body_name(c.session.world(), c.session.drag()->body) << " for " << n << " steps";
    c.session.drag_end();
}

void run_push(const ActionContext& c)
{
    const Ray r = ray_or_pixel(c.action, c.where, c.session, c.ui, "x", "y");
    const int n = count(c.action, c.where, "steps", 1);
    if (c.action.contains("depth") == c.action.contains("force"))
        fail(c.where, "expected either \"force\" [N] or \"depth\" [m]");
    if (c.action.contains("depth")) {
        const double depth = number(c.action, c.where, "depth", 0.0);
        check(c.session.mould(r, depth, n), c.where);
        c.session.step(n);
        c.log << " " << depth << " m deep for " << n << " steps: reached " << c.session.mould_depth_reached()
              << " m";
    } else {
        const double force = number(c.action, c.where, "force", 0.0);
        check(c.session.push(r, force, n), c.where);
        c.session.step(n);
        c.log << " " << force << " N for " << n << " steps";
    }
}

/// "x", "y" or "z" at `key` as an axis index.
int axis_of(const ActionContext& c, const char* key)
{
    const std::string name = text(c.action, c.where, key);
    if (name != "x" && name != "y" && name != "z")
        fail(c.where + "/" + key, R"(expected "x", "y" or "z", found ")" + name + "\"");
    return name[0] - 'x';
}

/// The display pixel of a mouse action: "x" and "y", "body" (where its centre is drawn), or "gizmo" (a
/// handle of the selected body's gizmo: "x", "y" or "z").
std::array<double, 2> mouse_pixel(const ActionContext& c)
{
    if (c.action.contains("gizmo")) {
        if (c.action.contains("body") || c.action.contains("x"))
            fail(c.where + "/gizmo", "expected \"gizmo\" alone, without \"x\", \"y\" or \"body\"");
        const int axis = axis_of(c, "gizmo");
        const std::optional<std::array<double, 2>> p = gizmo_handle_pixel(c.session, c.ui, axis);
        if (!p)
            fail(c.where + "/gizmo", "no gizmo handle is drawn (select a body and a gizmo mode first)");
        return *p;
    }
    if (c.action.contains("body") == c.action.contains("x"))
        fail(c.where, "expected either \"x\", \"y\", \"body\" or \"gizmo\"");
    if (!c.action.contains("body"))
        return {number(c.action, c.where, "x", NAN), number(c.action, c.where, "y", NAN)};
    const std::string name = text(c.action, c.where, "body");
    const Entity e = find_body(c.session.world(), name);
    if (e.is_null())
        fail(c.where + "/body", "no body named \"" + name + "\"");
    const std::optional<std::array<double, 2>> p =
        screen_pixel(c.session, c.ui, body_position(c.session.world(), e));
    if (!p)
        fail(c.where + "/body", "\"" + name + "\" is behind the camera");
    return *p;
}

/// "mods": a list of "shift", "ctrl", "alt" held with a button or key.
uint8_t mods(const ActionContext& c)
{
    if (!c.action.contains("mods"))
        return k_mod_none;
    const Json& v = c.action.at("mods");
    if (!v.is_array())
        fail(c.where + "/mods", "expected a list of \"shift\", \"ctrl\", \"alt\", found " + kind_of(v));
    uint8_t out = k_mod_none;
    for (size_t i = 0; i < v.size(); ++i) {
        const std::string name = v[i].is_string() ? v[i].get<std::string>() : std::string();
        if (name == "shift")
            out |= k_mod_shift;
        else if (name == "ctrl")
            out |= k_mod_ctrl;
        else if (name == "alt")
            out |= k_mod_alt;
        else
            fail(c.where + "/mods/" + std::to_string(i),
                 "expected \"shift\", \"ctrl\" or \"alt\", found " + kind_of(v[i]));
    }
    return out;
}

/// Mouse events as the host delivers them (a window: through its GLFW callbacks), then frames.
void run_mouse(const ActionContext& c)
{
    const auto [x, y] = mouse_pixel(c);
    if (!(x >= 0.0 && x <= c.ui.width()))
        fail(c.where + "/x", "expected a pixel in [0, " + std::to_string(c.ui.width()) + "], found " +
                                 kind_of(c.action.value("x", Json())));
    if (!(y >= 0.0 && y <= c.ui.height()))
        fail(c.where + "/y", "expected a pixel in [0, " + std::to_string(c.ui.height()) + "], found " +
                                 kind_of(c.action.value("y", Json())));
    c.ui.input.cursor(x, y);
    c.log << " at (" << x << ", " << y << ")";
    const uint8_t held = mods(c);
    if (c.action.contains("button")) {
        const std::string name = text(c.action, c.where, "button");
        if (name != "left" && name != "right" && name != "middle")
            fail(c.where + "/button", R"(expected "left", "right" or "middle", found ")" + name + "\"");
        const Json& down = required(c.action, c.where, "down");
        if (!down.is_boolean())
            fail(c.where + "/down", "expected true or false, found " + kind_of(down));
        const MouseButton b = name == "left"    ? MouseButton::Left
                              : name == "right" ? MouseButton::Right
                                                : MouseButton::Middle;
        c.ui.input.button(b, down.get<bool>(), held);
        c.log << " " << name << (down.get<bool>() ? " down" : " up");
    }
    if (c.action.contains("wheel")) {
        const double notches = number(c.action, c.where, "wheel", 0.0);
        if (!(notches != 0.0 && std::abs(notches) <= 100.0))
            fail(c.where + "/wheel",
                 "expected wheel notches in [-100, 100], not 0, found " + kind_of(c.action["wheel"]));
        c.ui.input.scroll(notches);
        c.log << " wheel " << notches;
    }
    const int n = count(c.action, c.where, "frames", 1);
    for (int i = 0; i < n; ++i)
        c.ui.host_frame(1.0 / 60.0);
    if (c.action.contains("expect") && text(c.action, c.where, "expect") != c.ui.selected_body())
        fail(c.where + "/expect",
             "expected \"" + c.action["expect"].get<std::string>() +
                 "\" to be selected, the selection is \"" + c.ui.selected_body() + "\"",
             ScriptFailure::CheckFailed);
}

/// A key pressed and released, a frame after each.
void run_key(const ActionContext& c)
{
    const std::string name = text(c.action, c.where, "key");
    const std::optional<EditorKey> key = key_from_name(name);
    if (!key)
        fail(c.where + "/key", "unknown key "
                               " + name + "
                               "; keys are: " +
                                   key_names());
    const uint8_t held = mods(c);
    c.ui.input.key(*key, true, held);
    c.ui.host_frame(0.0);
    c.ui.input.key(*key, false, held);
    c.ui.host_frame(0.0);
    c.log << " " << name;
}

/// Resizes the display (a window: through GLFW, as a user dragging its corner), then runs a frame.
void run_resize(const ActionContext& c)
{
    int size[2] = {0, 0};
    for (int i = 0; i < 2; ++i) {
        const char* key = i == 0 ? "width" : "height";
        const Json& v = required(c.action, c.where, key);
        if (!v.is_number_integer() || v.get<int64_t>() < 16 || v.get<int64_t>() > 16384)
            fail(c.where + "/" + key, "expected an integer in [16, 16384] px, found " + kind_of(v));
        size[i] = static_cast<int>(v.get<int64_t>());
    }
    if (!c.ui.input.resize)
        fail(c.where, "this host cannot be resized");
    c.ui.input.resize(size[0], size[1]);
    c.ui.host_frame(0.0);
    c.log << " " << c.ui.width() << "x" << c.ui.height();
}

/// Logs the 3-D view's rectangle in the last frame; with "min_fraction", checks its share of the display.
void run_viewport(const ActionContext& c)
{
    const ScreenRect& v = c.ui.viewport();
    const double fraction = v.area() / (static_cast<double>(c.ui.width()) * c.ui.height());
    c.log << " " << v.width() << "x" << v.height() << " at (" << v.x0 << ", " << v.y0
          << "): " << 100.0 * fraction << "% of the display";
    if (c.action.contains("min_fraction")) {
        const double min = number(c.action, c.where, "min_fraction", 0.0);
        if (!(min >= 0.0 && min <= 1.0))
            fail(c.where + "/min_fraction", "expected a fraction in [0, 1]");
        if (fraction < min)
            fail(c.where + "/min_fraction",
                 "the 3-D view keeps " + std::to_string(fraction) + " of the display, expected at least " +
                     std::to_string(min),
                 ScriptFailure::CheckFailed);
    }
}

/// Logs the view's camera; with "yaw_deg", "pitch_deg", "distance" checks them to "tolerance"; with
/// "framed" checks that every corner of the named bodies' boxes ("all": every body) is drawn inside
/// the 3-D view's rectangle.
void run_camera(const ActionContext& c)
{
    const CameraDef& cam = editor_camera(c.session, c.ui);
    const Vec3 t = cam.target.value_or(Vec3{});
    c.log << std::setprecision(10) << " target " << vec_text(t) << " distance " << cam.distance << " yaw "
          << cam.yaw_deg << " pitch " << cam.pitch_deg << std::setprecision(6);
    const double tolerance = number(c.action, c.where, "tolerance", 1e-9);
    for (const auto& [key, value] : {std::pair{"yaw_deg", cam.yaw_deg}, std::pair{"pitch_deg", cam.pitch_deg},
                                     std::pair{"distance", cam.distance}})
        if (c.action.contains(key) && !(std::abs(number(c.action, c.where, key, 0.0) - value) <= tolerance))
            fail(c.where + "/" + key,
                 "expected " + c.action[key].dump() + " to " + std::to_string(tolerance) +
                     ", the camera has " + std::to_string(value),
                 ScriptFailure::CheckFailed);
    if (!c.action.contains("framed"))
        return;
    const Json& framed = c.action["framed"];
    std::vector<Entity> bodies;
    if (framed == "all") {
        bodies = world_bodies(c.session.world());
    } else {
        if (!framed.is_array())
            fail(c.where + "/framed", "expected \"all\" or a list of body names, found " + kind_of(framed));
        for (size_t i = 0; i < framed.size(); ++i) {
            const Entity e =
                framed[i].is_string() ? find_body(c.session.world(), framed[i].get<std::string>()) : Entity{};
            if (e.is_null())
                fail(c.where + "/framed/" + std::to_string(i), "no body named " + kind_of(framed[i]));
            bodies.push_back(e);
        }
    }
    const ScreenRect& v = c.ui.viewport();
    int checked = 0;
    for (Entity e : bodies) {
        const std::optional<Aabb> box = body_box(c.session.world(), e);
        if (!box)
            continue; // a plane has no bounds to frame
        for (int k = 0; k < 8; ++k) {
            const Vec3 corner{(k & 1) ? box->max.x : box->min.x, (k & 2) ? box->max.y : box->min.y,
                              (k & 4) ? box->max.z : box->min.z};
            const std::optional<ViewPixel> p = view_pixel(cam, v.width(), v.height(), corner);
            if (!p || p->x < 0.0 || p->x > v.width() || p->y < 0.0 || p->y > v.height())
                fail(c.where + "/framed",
                     "a corner of \"" + body_name(c.session.world(), e) + "\"'s box, " + vec_text(corner) +
                         ", is outside the 3-D view",
                     ScriptFailure::CheckFailed);
        }
        ++checked;
    }
    c.log << ", " << checked << " bodies framed";
}

/// Logs a body's modes as the Body window lists them, frequencies to the last bit (17 digits).
void run_modes(const ActionContext& c)
{
    const std::string name = body_or_selected(c);
    const ModesReadout r = modes_readout(c.session, name);
    if (!r.modal) {
        c.log << " " << name << ": rigid, no modes";
        return;
    }
    c.log << " " << name << ": " << r.frequencies_hz.size() << " modes [Hz]" << std::setprecision(17);
    for (double f : r.frequencies_hz)
        c.log << " " << f;
    c.log << std::setprecision(6) << "; residual " << r.residual << ", truncated energy "
          << r.truncated_energy << " J";
    if (r.plastic_dent > 0.0)
        c.log << "; plastic dent " << r.plastic_dent << " m";
    if (r.animating >= 0)
        c.log << "; mode " << r.animating + 1 << " animated";
}

/// Runs the Speed / accuracy plot's sweep ("seconds" simulated per run) and waits for it; logs every
/// point and which one the current dt and substeps are.
void run_trade(const ActionContext& c)
{
    const double seconds = number(c.action, c.where, "seconds", c.ui.trade_seconds);
    if (!(seconds > 0.0) || seconds > 3600.0)
        fail(c.where + "/seconds", "expected seconds in (0, 3600], found " + std::to_string(seconds));
    c.ui.trade_seconds = seconds;
    check(c.ui.start_trade(), c.where);
    c.ui.trade.wait();
    const TradeResult r = c.ui.trade.result();
    if (!r.error.empty())
        fail(c.where, r.error);
    const WorldDef& w = c.session.scene().world;
    const int marked = find_trade_point(r.points, w.dt, w.substep_count);
    c.log << " " << r.points.size() << " points (knob value: ms per simulated s, error m):";
    for (const TradePoint& p : r.points)
        c.log << " " << p.knob << " " << p.value << ": " << p.ms_per_sim_s << ", " << p.error_m << ";";
    if (marked >= 0)
        c.log << " current " << r.points[static_cast<size_t>(marked)].knob << " "
              << r.points[static_cast<size_t>(marked)].value;
}

/// Starts a mode animation ("mode", 1 = lowest) or ends it ("restore": true).
void run_animate(const ActionContext& c)
{
    if (c.action.contains("restore") == c.action.contains("mode"))
        fail(c.where, "expected either \"mode\" (1 = the lowest) or \"restore\": true");
    if (c.action.contains("restore")) {
        if (c.action["restore"] != true || c.action.contains("body"))
            fail(c.where + "/restore",
                 "expected \"restore\": true alone, found " + kind_of(c.action["restore"]));
        const bool was = c.session.mode_animation().has_value();
        c.session.end_mode_animation();
        c.log << (was ? " ended: the world is restored" : " (no animation ran)");
        return;
    }
    const std::string name = body_or_selected(c);
    const int mode = count(c.action, c.where, "mode", 1);
    ModeAnimationDef def;
    def.mode = mode - 1;
    check(c.session.animate_mode(name, def), c.where + "/mode");
    const ModeAnimation& a = *c.session.mode_animation();
    c.log << " " << name << " mode " << mode << " (" << a.frequency_hz << " Hz): swing " << a.amplitude
          << " sqrt(kg) m, peak " << a.peak_displacement << " m, one swing per " << a.period << " s";
}

/// A vector at `key`, or `fallback` when absent; a number gives all three components when `uniform`.
Vec3 vec3_or(const ActionContext& c, const char* key, const Vec3& fallback, bool uniform = false)
{
    if (!c.action.contains(key))
        return fallback;
    const Json& v = c.action.at(key);
    if (uniform && v.is_number()) {
        const double s = number(c.action, c.where, key, 1.0);
        return {s, s, s};
    }
    return vec3(v, c.where + "/" + key);
}

std::string pose_text(const ActionContext& c, const std::string& name)
{
    const World& w = c.session.world();
    const Entity e = find_body(w, name);
    const Vec3 p = body_position(w, e);
    const Quat q = body_orientation(w, e);
    const Vec3 r = body_shape(w, e).radii;
    std::ostringstream out;
    out << std::setprecision(17) << "position [" << p.x << ", " << p.y << ", " << p.z << "] orientation ["
        << q.w << ", " << q.x << ", " << q.y << ", " << q.z << "] radii [" << r.x << ", " << r.y << ", "
        << r.z << "]";
    return out.str();
}

/// Moves, turns and scales a body as one undoable edit (what a gizmo drag applies).
void run_transform(const ActionContext& c)
{
    const std::string name = body_or_selected(c);
    TransformDef def;
    def.translate = vec3_or(c, "translate", def.translate);
    def.rotate_deg = vec3_or(c, "rotate_deg", def.rotate_deg);
    def.scale = vec3_or(c, "scale", def.scale, /*uniform=*/true);
    for (int i = 0; i < 3; ++i)
        if (!(def.scale[i] > 0.0))
            fail(c.where + "/scale" + (c.action.at("scale").is_array() ? "/" + std::to_string(i) : ""),
                 "expected a factor > 0, found " + std::to_string(def.scale[i]));
    if (c.action.contains("snap")) {
        if (!c.action["snap"].is_boolean())
            fail(c.where + "/snap", "expected true or false, found " + kind_of(c.action["snap"]));
        def.snap = c.action["snap"].get<bool>();
    }
    // The session names the key at fault ("body", "scale", "translate"): the message points at it.
    if (const Status status = c.session.transform(name, def, c.ui.gizmo.steps); !status) {
        const std::string& key = status.error().where;
        fail(c.action.contains(key) ? c.where + "/" + key : c.where, status.error().what);
    }
    c.log << " " << name << ": " << pose_text(c, name);
}

/// Logs a body's pose and radii to 17 digits (read back to the same doubles).
void run_pose(const ActionContext& c)
{
    const std::string name = body_or_selected(c);
    c.log << " " << name << ": " << pose_text(c, name);
}

/// The gizmo's mode, snapping and steps, as the Body window sets them.
void run_gizmo(const ActionContext& c)
{
    GizmoDef g = c.ui.gizmo;
    if (c.action.contains("mode")) {
        const std::string mode = text(c.action, c.where, "mode");
        const GizmoMode modes[] = {GizmoMode::Off, GizmoMode::Move, GizmoMode::Rotate, GizmoMode::Scale};
        bool known = false;
        for (GizmoMode m : modes)
            if (mode == gizmo_mode_name(m)) {
                g.mode = m;
                known = true;
            }
        if (!known)
            fail(c.where + "/mode", R"(expected "off", "move", "rotate" or "scale", found ")" + mode + "\"");
    }
    if (c.action.contains("snap")) {
        if (!c.action["snap"].is_boolean())
            fail(c.where + "/snap", "expected true or false, found " + kind_of(c.action["snap"]));
        g.snap = c.action["snap"].get<bool>();
    }
    const std::pair<const char*, double*> steps[] = {{"move_step", &g.steps.move_step},
                                                     {"rotate_step_deg", &g.steps.rotate_step_deg},
                                                     {"scale_step", &g.steps.scale_step}};
    for (const auto& [key, value] : steps) {
        *value = number(c.action, c.where, key, *value);
        if (!(*value > 0.0))
            fail(c.where + "/" + key, "expected a step > 0, found " + kind_of(c.action[key]));
    }
    c.ui.gizmo = g;
    c.ui.gizmo_drag.reset();
    c.ui.host_frame(0.0); // drawn, so a "mouse" action can find its handles
    c.log << " " << gizmo_mode_name(g.mode) << (g.snap ? ", snapping" : ", free");
}

void run_windows(const ActionContext& c)
{
    const Json& show = required(c.action, c.where, "show");
    if (!show.is_boolean())
        fail(c.where + "/show", "expected true or false, found " + kind_of(show));
    c.ui.show_windows = show.get<bool>();
}

void run_save(const ActionContext& c)
{
    const std::filesystem::path file = c.base_dir / text(c.action, c.where, "file");
    std::string state = "current";
    if (c.action.contains("state"))
        state = text(c.action, c.where, "state");
    if (state != "current" && state != "initial")
        fail(c.where + "/state", "expected \"current\" or \"initial\", found \"" + state + "\"");
    check(c.session.save(file.string(), state == "current"), c.where + "/file");
    c.log << " " << file.string();
}

struct ActionSpec {
    std::vector<std::string> keys; ///< Keys besides "action" (and "comment", which any action may carry).
    void (*run)(const ActionContext&);
};

/// The actions by name (listed in this order when a script names an unknown one).
const std::map<std::string, ActionSpec, std::less<>> k_actions = {
    {"load", {{"file"}, run_load}},
    {"set", {{"path", "value"}, run_set}},
    {"step", {{"count"}, run_step}},
    {"frames", {{"count", "seconds"}, run_frames}},
    {"play", {{}, run_play}},
    {"pause", {{}, run_pause}},
    {"reset", {{}, run_reset}},
    {"undo", {{}, run_undo}},
    {"redo", {{}, run_redo}},
    {"press", {{"widget"}, run_press}},
    {"select", {{"body"}, run_select}},
    {"pick", {{"ray", "expect"}, run_pick}},
    {"click", {{"x", "y", "expect"}, run_click}},
    {"drag", {{"ray", "to", "steps", "x0", "y0", "x1", "y1"}, run_drag}},
    {"push", {{"ray", "force", "steps", "x", "y", "depth"}, run_push}},
    {"windows", {{"show"}, run_windows}},
    {"mouse",
     {{"x", "y", "body", "gizmo", "button", "down", "mods", "wheel", "frames", "expect"}, run_mouse}},
    {"transform", {{"body", "translate", "rotate_deg", "scale", "snap"}, run_transform}},
    {"pose", {{"body"}, run_pose}},
    {"gizmo", {{"mode", "snap", "move_step", "rotate_step_deg", "scale_step"}, run_gizmo}},
    {"key", {{"key", "mods"}, run_key}},
    {"camera", {{"yaw_deg", "pitch_deg", "distance", "tolerance", "framed"}, run_camera}},
    {"viewport", {{"min_fraction"}, run_viewport}},
    {"resize", {{"width", "height"}, run_resize}},
    {"save", {{"file", "state"}, run_save}},
    {"modes", {{"body"}, run_modes}},
    {"trade", {{"seconds"}, run_trade}},
    {"animate", {{"body", "mode", "restore"}, run_animate}},
    {"parts", {{"folder", "size", "cache"}, run_parts}},
    {"add_part", {{"file", "at", "ray", "x", "y", "orientation", "name", "prefix"}, run_add_part}},
    {"attach",
     {{"body", "to", "at", "ray", "x", "y", "type", "frequency", "damping_ratio", "name"}, run_attach}},
    {"detach", {{"body"}, run_detach}},
};

void run_action(const Json& action, const std::string& where, const std::filesystem::path& base_dir,
                EditorSession& session, EditorUi& ui, std::ostream& log)
{
    if (!action.is_object())
        fail(where, "expected an object {\"action\": ...}, found " + kind_of(action));
    const std::string verb = text(action, where, "action");
    const auto known = k_actions.find(verb);
    if (known == k_actions.end()) {
        std::string names;
        for (const auto& [name, spec] : k_actions)
            names += (names.empty() ? "" : ", ") + name;
        fail(where + "/action", "unknown action \"" + verb + "\"; actions are: " + names);
    }
    const std::vector<std::string>& keys = known->second.keys;
    for (const auto& item : action.items())
        if (item.key() != "action" && item.key() != "comment" &&
            std::find(keys.begin(), keys.end(), item.key()) == keys.end())
            fail(where + "/" + item.key(), "unknown key \"" + item.key() + "\" for action \"" + verb + "\"");
    if (verb != "load" && verb != "parts" && !session.has_world())
        fail(where, "no scene is loaded: start the script with {\"action\": \"load\", \"file\": ...}");

    log << where << " " << verb;
    known->second.run(ActionContext{action, where, base_dir, session, ui, log});
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
