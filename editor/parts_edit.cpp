// SPDX-License-Identifier: MIT
// Building scenes from part files: adding a part, attaching two parts at a picked surface point, and
// detaching a part. Each is made of set() edits of whole scene sections joined in the history, so undo,
// redo, refusals and the world's rebuild behave exactly as for any other edit.
#include "session.h"
#include "supermodal/body.h"

#include <cmath>
#include <filesystem>
#include <map>
#include <set>

namespace supermodal::editor
{
namespace
{

Json written(const Scene& scene)
{
    return Json::parse(scene_to_json(scene)); // the writer's output is valid JSON by construction
}

Json vec_json(const Vec3& v)
{
    return Json::array({v.x, v.y, v.z});
}

/// `name`, or `name_2`, `name_3`, ... whichever is not in `taken`; the result is then taken.
std::string unique_name(const std::string& name, std::set<std::string>& taken)
{
    std::string out = name;
    for (int n = 2; taken.count(out) != 0; ++n)
        out = name + "_" + std::to_string(n);
    taken.insert(out);
    return out;
}

/// The part file read through an include, so that its prefix, pose and mesh paths follow the include
/// rules (docs/scene_format.md "include").
Result<Scene> read_part(const PartDef& def, const std::string& source)
{
    if (!is_finite(def.position) || !is_finite(def.orientation))
        return Error{"", "position", "expected finite numbers"};
    const Json include = {{"file", std::filesystem::absolute(def.file).string()},
                          {"prefix", def.prefix},
                          {"position", vec_json(def.position)},
                          {"orientation", Json::array({def.orientation.w, def.orientation.x,
                                                       def.orientation.y, def.orientation.z})}};
    Result<Scene> part = parse_scene(Json{{"include", Json::array({include})}}.dump(), source);
    if (!part)
        return Error{"", "file", def.file + ": " + part.error().what};
    if (part->bodies.empty())
        return Error{"", "file", def.file + ": the part has no bodies"};
    return part;
}

/// Renames the part's bodies and constraints so that no name is taken in `scene`: the root body gets
/// `root_name` when given. Fails when that name is taken.
Status rename_part(Json& part, const Scene& scene, const std::string& root_name)
{
    std::set<std::string> bodies, constraints;
    for (const SceneBody& b : scene.bodies)
        bodies.insert(b.def.name);
    for (const SceneConstraint& c : scene.constraints)
        constraints.insert(c.def.name);
    if (!root_name.empty() && bodies.count(root_name) != 0)
        return Error{"", "name", "a body named \"" + root_name + "\" is already in the scene"};
    std::map<std::string, std::string> renamed;
    for (Json& b : part["bodies"]) {
        const std::string old = b.value("name", "");
        const bool root = renamed.empty() && !b.contains("parent") && !root_name.empty();
        renamed[old] = root ? unique_name(root_name, bodies) : unique_name(old, bodies);
        b["name"] = renamed[old];
        if (b.contains("parent"))
            b["parent"] = renamed[b["parent"].get<std::string>()];
    }
    for (Json& c : part["constraints"]) {
        for (const char* side : {"a", "b"})
            if (c.contains(side) && renamed.count(c[side].get<std::string>()) != 0)
                c[side] = renamed[c[side].get<std::string>()];
        if (c.contains("name") && !c["name"].get<std::string>().empty())
            c["name"] = unique_name(c["name"].get<std::string>(), constraints);
    }
    return {};
}

/// The scene's materials with the part's added; a name defined differently is an error.
Result<Json> merged_materials(const Json& scene, const Json& part)
{
    Json out = scene.contains("materials") ? scene["materials"] : Json::object();
    if (!part.contains("materials"))
        return out;
    for (const auto& [name, def] : part["materials"].items()) {
        if (out.contains(name) && out[name] != def)
            return Error{"", "file", "the part's material \"" + name + "\" differs from the scene's"};
        out[name] = def;
    }
    return out;
}

const char* constraint_type_name(ConstraintType t)
{
    return t == ConstraintType::Weld ? "weld" : t == ConstraintType::Distance ? "distance" : "point";
}

std::optional<size_t> body_index(const Scene& scene, const std::string& name)
{
    for (size_t i = 0; i < scene.bodies.size(); ++i)
        if (scene.bodies[i].def.name == name)
            return i;
    return std::nullopt;
}

/// The body `key` names: in the scene, not a plane.
Result<size_t> attachable(const Scene& scene, const std::string& name, const char* key)
{
    const std::optional<size_t> i = body_index(scene, name);
    if (!i)
        return Error{"", key, "no body named \"" + name + "\""};
    if (scene.bodies[*i].def.shape.type == ShapeType::Plane)
        return Error{"", key, "\"" + name + "\" is a plane: it has no surface point to attach at"};
    return *i;
}

Status check_attach(const AttachDef& def)
{
    if (!is_finite(def.point))
        return Error{"", "point", "expected a finite point"};
    if (!(def.frequency > 0.0 && std::isfinite(def.frequency)))
        return Error{"", "frequency", "expected a frequency > 0 [Hz]"};
    if (!(def.damping_ratio >= 0.0 && std::isfinite(def.damping_ratio)))
        return Error{"", "damping_ratio", "expected a damping ratio >= 0"};
    if (def.body == def.to)
        return Error{"", "to", "a part cannot be attached to itself"};
    return {};
}

/// The direction from a body's shape origin through a world point, in its shape frame.
Result<Vec3> anchor_direction(const World& w, Entity e, const Vec3& point, const std::string& name)
{
    const Vec3 d = inv_rotate(body_orientation(w, e), point - body_position(w, e));
    if (!(length(d) > 1e-9))
        return Error{"", "point", "the point is at the origin of \"" + name + "\": no surface direction"};
    return d;
}

/// def.name when free, else "<body>_joint" made unique.
Result<std::string> constraint_name(const Scene& scene, const AttachDef& def)
{
    std::set<std::string> names;
    for (const SceneConstraint& c : scene.constraints)
        names.insert(c.def.name);
    if (!def.name.empty() && names.count(def.name) != 0)
        return Error{"", "name", "a constraint named \"" + def.name + "\" is already in the scene"};
    return def.name.empty() ? unique_name(def.body + "_joint", names) : def.name;
}

/// The constraint's JSON: from def.to (a) to def.body (b), direction anchors through the point.
Result<Json> attach_constraint(const World& w, const AttachDef& def, const std::string& name)
{
    Result<Vec3> da = anchor_direction(w, find_body(w, def.to), def.point, def.to);
    Result<Vec3> db = anchor_direction(w, find_body(w, def.body), def.point, def.body);
    if (!da || !db)
        return da ? db.error() : da.error();
    return Json{{"name", name},
                {"type", constraint_type_name(def.type)},
                {"a", def.to},
                {"b", def.body},
                {"anchor_a", {{"direction", vec_json(*da)}}},
                {"anchor_b", {{"direction", vec_json(*db)}}},
                {"frequency", def.frequency},
                {"damping_ratio", def.damping_ratio}};
}

/// The written body as a part of def.to: moved with it, its pose (where the world has it) kept in
/// that part's frame.
Json as_part_of(const World& w, Json body, const AttachDef& def)
{
    const Entity eb = find_body(w, def.body), et = find_body(w, def.to);
    const Quat qt = body_orientation(w, et);
    body["parent"] = def.to;
    body["position"] = vec_json(inv_rotate(qt, body_position(w, eb) - body_position(w, et)));
    const Quat q = normalized(conjugate(qt) * body_orientation(w, eb));
    body["orientation"] = Json::array({q.w, q.x, q.y, q.z});
    return body;
}

} // namespace

Result<std::string> EditorSession::attach(const AttachDef& def)
{
    if (!m_world)
        return Error{"", "", "no scene is loaded"};
    Result<size_t> ib = attachable(m_scene, def.body, "body");
    Result<size_t> it = attachable(m_scene, def.to, "to");
    if (!ib || !it)
        return ib ? it.error() : ib.error();
    if (Status ok = check_attach(def); !ok)
        return ok.error();
    Result<std::string> name = constraint_name(m_scene, def);
    Result<Json> constraint = attach_constraint(*m_world, def, name ? *name : std::string());
    if (!name || !constraint)
        return name ? constraint.error() : name.error();
    const Json scene = written(m_scene);
    Json constraints = scene["constraints"];
    constraints.push_back(*constraint);
    std::vector<std::pair<std::string, Json>> edits;
    if (m_scene.bodies[*ib].parent.empty() && *it < *ib)
        edits.emplace_back("/bodies/" + std::to_string(*ib), as_part_of(*m_world, scene["bodies"][*ib], def));
    edits.emplace_back("/constraints", constraints);
    if (Status status = set_joined(edits); !status)
        return status.error();
    return *name;
}

Status EditorSession::detach(std::string_view body)
{
    if (!m_world)
        return Error{"", "", "no scene is loaded"};
    const std::string name(body);
    const std::optional<size_t> i = body_index(m_scene, name);
    if (!i)
        return Error{"", "body", "no body named \"" + name + "\""};
    const Json scene = written(m_scene);
    Json constraints = Json::array();
    for (const Json& c : scene["constraints"])
        if (c.value("a", "") != name && c.value("b", "") != name)
            constraints.push_back(c);
    std::vector<std::pair<std::string, Json>> edits;
    if (constraints != scene["constraints"])
        edits.emplace_back("/constraints", constraints);
    if (!m_scene.bodies[*i].parent.empty()) {
        // On its own again: its pose in the world frame, where the world has it now.
        Json b = scene["bodies"][*i];
        const Entity e = find_body(*m_world, name);
        const Quat q = body_orientation(*m_world, e);
        b.erase("parent");
        b["position"] = vec_json(body_position(*m_world, e));
        b["orientation"] = Json::array({q.w, q.x, q.y, q.z});
        edits.emplace_back("/bodies/" + std::to_string(*i), b);
    }
    if (edits.empty())
        return Error{"", "body", "\"" + name + "\" has no constraint and no parent to detach from"};
    return set_joined(edits);
}

Result<std::string> EditorSession::add_part(const PartDef& def)
{
    if (!m_world)
        return Error{"", "", "no scene is loaded"};
    Result<Scene> read = read_part(def, m_scene.source);
    if (!read)
        return read.error();
    Json part = written(*read);
    if (Status status = rename_part(part, m_scene, def.name); !status)
        return status.error();
    const Json scene = written(m_scene);
    Result<Json> materials = merged_materials(scene, part);
    if (!materials)
        return materials.error();
    Json bodies = scene["bodies"], constraints = scene["constraints"];
    for (const Json& b : part["bodies"])
        bodies.push_back(b);
    for (const Json& c : part["constraints"])
        constraints.push_back(c);
    // Materials first, constraints last: every scene on the way is valid.
    std::vector<std::pair<std::string, Json>> edits;
    if (*materials != scene["materials"])
        edits.emplace_back("/materials", *materials);
    edits.emplace_back("/bodies", bodies);
    if (constraints != scene["constraints"])
        edits.emplace_back("/constraints", constraints);
    if (Status status = set_joined(edits); !status)
        return status.error();
    return part["bodies"][0]["name"].get<std::string>();
}

} // namespace supermodal::editor
