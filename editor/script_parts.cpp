// SPDX-License-Identifier: MIT
// The script actions of the Parts library: parts, add_part, attach, detach.
#include "script_support.h"

#include <algorithm>
#include <filesystem>

namespace supermodal::editor::script
{
namespace
{

ConstraintType constraint_type(const ActionContext& c)
{
    const std::string type = c.action.contains("type") ? text(c.action, c.where, "type") : "weld";
    if (type == "weld")
        return ConstraintType::Weld;
    if (type == "point")
        return ConstraintType::Point;
    if (type == "distance")
        return ConstraintType::Distance;
    fail(c.where + "/type", R"(expected "weld", "point" or "distance", found ")" + type + "\"");
}

} // namespace

/// Lists a folder's part files and draws their thumbnails (the Parts panel's library).
void run_parts(const ActionContext& c)
{
    ThumbnailDef def = c.ui.parts_library.settings(); // the command line's cache unless "cache" is given
    def.size = count(c.action, c.where, "size", ThumbnailDef{}.size);
    if (c.action.contains("cache"))
        def.cache_dir = (c.base_dir / text(c.action, c.where, "cache")).string();
    const std::filesystem::path folder = c.base_dir / text(c.action, c.where, "folder");
    if (const Status status = c.ui.parts_library.scan(folder.string(), def); !status)
        check_keyed(c,
                    Error{"", status.error().where == "size" ? "size" : "folder", status.error().message()});
    const int drawn = c.ui.parts_library.render_pending();
    c.log << " " << folder.string() << ": " << c.ui.parts_library.entries().size() << " parts, " << drawn
          << " drawn";
    for (const PartEntry& e : c.ui.parts_library.entries())
        c.log << ", " << e.label << (e.width > 0 ? (e.from_cache ? " (cached)" : "") : " (" + e.error + ")");
}

/// Adds a part file at a point (its origin there) or where a ray meets the scene (set on the surface,
/// as a drop from the Parts panel).
void run_add_part(const ActionContext& c)
{
    PartDef def;
    def.file = (c.base_dir / text(c.action, c.where, "file")).string();
    def.name = optional_text(c, "name");
    def.prefix = optional_text(c, "prefix");
    if (c.action.contains("orientation")) {
        const Json& q = c.action["orientation"];
        if (!q.is_array() || q.size() != 4 || !std::all_of(q.begin(), q.end(), [](const Json& v) {
                return v.is_number() && std::isfinite(v.get<double>());
            }))
            fail(c.where + "/orientation",
                 "expected a quaternion [w, x, y, z] of finite numbers, found " + kind_of(q));
        const Quat raw{q[0].get<double>(), q[1].get<double>(), q[2].get<double>(), q[3].get<double>()};
        if (!(raw.w * raw.w + raw.x * raw.x + raw.y * raw.y + raw.z * raw.z > 0.0))
            fail(c.where + "/orientation", "expected a quaternion that is not all zero");
        def.orientation = normalized(raw);
    }
    Result<std::string> added = Error{};
    if (at_or_ray(c)) {
        def.position = vec3(c.action["at"], c.where + "/at");
        added = c.session.add_part(def);
    } else {
        added = drop_part(c.session, ray_or_pixel(c.action, c.where, c.session, c.ui, "x", "y"), def);
    }
    if (!added)
        check_keyed(c, added.error());
    c.ui.select_body(*added);
    c.log << " " << *added << " at "
          << vec_text(body_position(c.session.world(), find_body(c.session.world(), *added)));
}

/// Attaches a part to another at a surface point: a world point on `to`, or where a ray meets it.
void run_attach(const ActionContext& c)
{
    AttachDef def;
    def.body = body_or_selected(c);
    def.type = constraint_type(c);
    def.frequency = number(c.action, c.where, "frequency", def.frequency);
    def.damping_ratio = number(c.action, c.where, "damping_ratio", def.damping_ratio);
    def.name = optional_text(c, "name");
    def.to = optional_text(c, "to");
    if (at_or_ray(c)) {
        if (def.to.empty())
            fail(c.where, R"(expected "to" (the part the point is on) with "at")");
        def.point = vec3(c.action["at"], c.where + "/at");
    } else {
        const std::optional<PickHit> hit =
            c.session.pick(ray_or_pixel(c.action, c.where, c.session, c.ui, "x", "y"));
        if (!hit)
            fail(c.where, "the ray hits no part", ScriptFailure::CheckFailed);
        if (!def.to.empty() && hit->name != def.to)
            fail(c.where + "/to", "the ray hits \"" + hit->name + "\", not \"" + def.to + "\"",
                 ScriptFailure::CheckFailed);
        def.to = hit->name;
        def.point = hit->point;
    }
    Result<std::string> made = c.session.attach(def);
    if (!made)
        check_keyed(c, made.error());
    c.log << " " << def.body << " to " << def.to << " at " << vec_text(def.point) << ": " << *made;
}

void run_detach(const ActionContext& c)
{
    const std::string name = body_or_selected(c);
    if (const Status status = c.session.detach(name); !status)
        check_keyed(c, status.error());
    c.log << " " << name;
}

} // namespace supermodal::editor::script
