// SPDX-License-Identifier: MIT
// Scene → JSON text (format v1), the inverse of the loader: parse_scene(scene_to_json(s)) == s field by
// field. The Scene is already flat (includes were merged when it was read), so the text is too. Keys
// whose value means "not set" (an unbounded yield stress, an automatic lattice, no joint limit) are
// left out so that they read back as "not set"; every other field is written, so an editor can reach
// it by its JSON pointer.
#include "io/atomic_file.h"
#include "scene/json_text.h"
#include "supermodal/body.h"
#include "supermodal/scene.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>

namespace supermodal
{
namespace
{

using scene_io::Json;

// Names in enum order (the loader's lists, which it static_asserts against the enums).
const char* const k_motion_names[] = {"static", "kinematic", "dynamic"};
const char* const k_dynamics_names[] = {"rigid", "modal", "auto", "full"};
const char* const k_integrator_names[] = {"exact", "central_difference"};
const char* const k_contact_paths[] = {"auto", "sampling", "support_map"};
const char* const k_contact_stiffness[] = {"frequency", "material"};
const char* const k_contact_solvers[] = {"soft", "penalty"};
const char* const k_constraint_types[] = {"point", "distance", "weld"};

/// Lines at most this long stay on one line in the output [characters].
constexpr size_t k_inline_width = 100;

Json vec3(const Vec3& v)
{
    return Json::array({v.x, v.y, v.z});
}

Json settings_json(const Scene& scene)
{
    const WorldDef& w = scene.world;
    Json s = Json::object();
    s["dt"] = w.dt;
    s["substeps"] = w.substep_count;
    s["gravity"] = vec3(w.gravity);
    s["duration"] = scene.duration;
    s["max_steps_per_advance"] = w.max_steps_per_advance;
    s["constraint_iterations"] = w.constraint_iterations;
    const SoftContactDef& soft = w.contact.soft;
    s["contact"] = {{"solver", k_contact_solvers[static_cast<size_t>(w.contact.solver)]},
                    {"soft",
                     {{"frequency", soft.frequency_hz},
                      {"damping_ratio", soft.damping_ratio},
                      {"push_out_speed", soft.push_out_speed},
                      {"restitution_speed", soft.restitution_speed},
                      {"iterations", soft.iterations},
                      {"relax_iterations", soft.relax_iterations},
                      {"substeps", soft.substeps}}},
                    {"path", k_contact_paths[static_cast<size_t>(w.contact.path)]},
                    {"stiffness", k_contact_stiffness[static_cast<size_t>(w.contact.stiffness)]},
                    {"sample_spacing", w.contact.sample_spacing},
                    {"max_samples_per_body", w.contact.max_samples_per_body},
                    {"deformed_inside_test", w.contact.deformed_inside_test}};
    s["threads"] = w.thread_count;
    s["split_islands"] = w.split_islands;
    s["sleep"] = {{"enabled", w.sleep.enabled},
                  {"linear_speed", w.sleep.linear_speed},
                  {"angular_speed", w.sleep.angular_speed},
                  {"time", w.sleep.time}};
    s["accuracy"] = {{"displacement", scene.accuracy.displacement}};
    return s;
}

Json material_json(const MaterialDef& m)
{
    Json j = {{"density", m.density},         {"young", m.young},
              {"poisson", m.poisson},         {"friction", m.friction},
              {"restitution", m.restitution}, {"damping_ratio", m.damping_ratio}};
    if (m.rolling_resistance != 0.0)
        j["rolling_resistance"] = m.rolling_resistance;
    if (std::isfinite(m.yield_stress))
        j["yield_stress"] = m.yield_stress;
    if (m.hardening != 0.0)
        j["hardening"] = m.hardening;
    if (std::isfinite(m.max_plastic_strain))
        j["max_plastic_strain"] = m.max_plastic_strain;
    if (m.remould_threshold != MaterialDef{}.remould_threshold)
        j["remould_threshold"] = m.remould_threshold;
    return j;
}

Json camera_json(const CameraDef& c)
{
    Json j = {{"distance", c.distance}, {"yaw", c.yaw_deg}, {"pitch", c.pitch_deg}, {"fov", c.fov_deg}};
    if (c.target)
        j["target"] = {c.target->x, c.target->y, c.target->z};
    return j;
}

Json shape_json(const ShapeDef& shape)
{
    Json j = Json::object();
    switch (shape.type) {
    case ShapeType::Superquadric:
        j["type"] = "superquadric";
        j["radii"] = vec3(shape.radii);
        j["exponents"] = Json::array({shape.epsilon1, shape.epsilon2});
        j["taper"] = Json::array({shape.taper.kx, shape.taper.ky});
        j["bend"] = {{"curvature", shape.bend.curvature}, {"angle", shape.bend.angle}};
        break;
    case ShapeType::Plane:
        j["type"] = "plane";
        j["normal"] = vec3(shape.plane_normal);
        j["offset"] = shape.plane_offset;
        break;
    case ShapeType::Hyperquadric:
        j["type"] = "hyperquadric";
        j["terms"] = Json::array();
        for (const HyperquadricTerm& t : shape.terms)
            j["terms"].push_back(
                {{"normal", vec3(t.normal)}, {"offset", t.offset}, {"exponent", t.exponent}});
        break;
    }
    return j;
}

/// The scene's material of this name, or the default material (a body without one uses it).
MaterialDef material_of(const Scene& scene, const std::string& name)
{
    for (const MaterialDef& m : scene.materials)
        if (m.name == name)
            return m;
    return MaterialDef{};
}

Json body_json(const Scene& scene, const SceneBody& body)
{
    const BodyDef& d = body.def;
    const MaterialDef material = material_of(scene, body.material);
    Json j = Json::object();
    j["name"] = d.name;
    if (!body.parent.empty())
        j["parent"] = body.parent;
    if (!body.material.empty())
        j["material"] = body.material;
    // Only when it differs: a body that takes its material's density follows later material edits.
    if (d.density != material.density)
        j["density"] = d.density;
    j["shape"] = shape_json(d.shape);
    j["position"] = vec3(d.position);
    j["orientation"] = Json::array({d.orientation.w, d.orientation.x, d.orientation.y, d.orientation.z});
    j["velocity"] = vec3(d.linear_velocity);
    j["angular_velocity"] = vec3(d.angular_velocity);
    j["motion"] = k_motion_names[static_cast<size_t>(d.motion)];
    j["gravity_scale"] = d.gravity_scale;
    if (!d.allow_sleep)
        j["sleep"] = false;
    if (!body.mesh.empty())
        j["mesh"] = body.mesh;
    // A body read without "dynamics" keeps the default ModalBodyDef (not its material's constants), and
    // only leaving the key out reads back that way.
    const ModalBodyDef no_dynamics{};
    const ModalBodyDef& m = d.modal;
    if (body.dynamics == DynamicsType::Rigid && !m.enabled && m.mode_count == no_dynamics.mode_count &&
        m.lattice == no_dynamics.lattice && m.integrator == no_dynamics.integrator &&
        m.damping_ratio == no_dynamics.damping_ratio && m.static_correction == no_dynamics.static_correction)
        return j;
    Json dyn = Json::object();
    dyn["type"] = k_dynamics_names[static_cast<size_t>(body.dynamics)];
    if (body.dynamics != DynamicsType::Full) // full: every mode, which "modes" cannot say
        dyn["modes"] = d.modal.mode_count;
    // All zero is the automatic lattice, which the format spells by leaving the key out.
    if (d.modal.lattice != std::array<int, 3>{})
        dyn["lattice"] = Json::array({d.modal.lattice[0], d.modal.lattice[1], d.modal.lattice[2]});
    dyn["integrator"] = k_integrator_names[static_cast<size_t>(d.modal.integrator)];
    if (d.modal.damping_ratio != material.damping_ratio)
        dyn["damping_ratio"] = d.modal.damping_ratio;
    if (d.modal.static_correction)
        dyn["static_correction"] = true;
    j["dynamics"] = dyn;
    return j;
}

Json anchor_json(const AnchorDef& a)
{
    switch (a.kind) {
    case AnchorKind::Direction:
        return {{"direction", vec3(a.direction)}};
    case AnchorKind::Surface:
        return {{"surface", Json::array({a.eta, a.omega})}};
    case AnchorKind::Point:
        break;
    }
    return vec3(a.point);
}

Json constraint_json(const SceneConstraint& c)
{
    const ConstraintDef& d = c.def;
    Json j = Json::object();
    if (!d.name.empty())
        j["name"] = d.name;
    j["type"] = k_constraint_types[static_cast<size_t>(d.type)];
    j["a"] = c.body_a;
    j["b"] = c.body_b.empty() ? std::string("world") : c.body_b;
    j["anchor_a"] = anchor_json(d.anchor_a);
    j["anchor_b"] = anchor_json(d.anchor_b);
    j["frequency"] = d.frequency_hz;
    j["damping_ratio"] = d.damping_ratio;
    // Negative values mean "not set" (from the creation pose, or no limit): the format leaves them out.
    if (d.rest_length >= 0.0)
        j["rest_length"] = d.rest_length;
    if (d.swing_limit >= 0.0)
        j["swing_limit"] = d.swing_limit;
    if (d.twist_limit >= 0.0)
        j["twist_limit"] = d.twist_limit;
    if (d.axis_a != Vec3{})
        j["axis_a"] = vec3(d.axis_a);
    j["angular_damping"] = d.angular_damping;
    if (std::isfinite(d.break_force))
        j["break_force"] = d.break_force;
    j["collide_connected"] = d.collide_connected;
    return j;
}

/// Pretty text: a value whose one-line form fits k_inline_width (after the indent) stays on one line;
/// larger objects and arrays open one member per line. Numbers print through nlohmann, which writes
/// the shortest digits that read back to the same double.
// One-line JSON text. Names set through the API may be any bytes: invalid UTF-8 becomes U+FFFD rather
// than nlohmann's throw.
std::string flat_text(const Json& value)
{
    return value.dump(-1, ' ', false, Json::error_handler_t::replace);
}

void write_value(const Json& value, int indent, std::string& out)
{
    const std::string flat = flat_text(value);
    if (!value.is_structured() || value.empty() ||
        flat.size() + static_cast<size_t>(indent) <= k_inline_width) {
        // dump() packs separators; one space after ':' and ',' reads better and still parses the same.
        if (!value.is_structured()) {
            out += flat;
            return;
        }
        bool in_string = false, escaped = false;
        for (char ch : flat) {
            out += ch;
            if (in_string) {
                if (escaped)
                    escaped = false;
                else if (ch == '\\')
                    escaped = true;
                else if (ch == '"')
                    in_string = false;
                continue;
            }
            if (ch == '"')
                in_string = true;
            else if (ch == ',' || ch == ':')
                out += ' ';
        }
        return;
    }
    const std::string pad(static_cast<size_t>(indent) + 2, ' ');
    const bool is_object = value.is_object();
    out += is_object ? "{\n" : "[\n";
    size_t i = 0;
    for (auto it = value.begin(); it != value.end(); ++it, ++i) {
        out += pad;
        if (is_object)
            out += flat_text(Json(it.key())) + ": ";
        write_value(*it, indent + 2, out);
        out += i + 1 < value.size() ? ",\n" : "\n";
    }
    out += std::string(static_cast<size_t>(indent), ' ') + (is_object ? "}" : "]");
}

} // namespace

std::string scene_to_json(const Scene& scene)
{
    Json root = Json::object();
    root["settings"] = settings_json(scene);
    Json materials = Json::object();
    for (const MaterialDef& m : scene.materials)
        materials[m.name] = material_json(m);
    root["materials"] = materials;
    root["bodies"] = Json::array();
    for (const SceneBody& b : scene.bodies)
        root["bodies"].push_back(body_json(scene, b));
    root["constraints"] = Json::array();
    for (const SceneConstraint& c : scene.constraints)
        root["constraints"].push_back(constraint_json(c));
    root["camera"] = camera_json(scene.camera);
    std::string out;
    write_value(root, 0, out);
    out += '\n';
    return out;
}

Status save_scene(const Scene& scene, const std::string& path)
{
    const std::string text = scene_to_json(scene);
    if (Status s = write_file_atomically(path, text.data(), text.size()); !s)
        return Error{path, "", "cannot write the scene: " + s.error().what};
    return {};
}

Status refresh_scene_from_world(Scene& scene, const World& world, bool include_shapes)
{
    std::vector<Entity> entities(scene.bodies.size());
    for (size_t i = 0; i < scene.bodies.size(); ++i) {
        entities[i] = find_body(world, scene.bodies[i].def.name);
        if (entities[i].is_null())
            return Error{scene.source, "/bodies/" + std::to_string(i),
                         "the world has no body named \"" + scene.bodies[i].def.name + "\""};
        if (!scene.bodies[i].parent.empty() && find_body(world, scene.bodies[i].parent).is_null())
            return Error{scene.source, "/bodies/" + std::to_string(i) + "/parent",
                         "the world has no body named \"" + scene.bodies[i].parent + "\""};
    }
    for (size_t i = 0; i < scene.bodies.size(); ++i) {
        SceneBody& body = scene.bodies[i];
        const Entity e = entities[i];
        Vec3 position = body_position(world, e);
        Quat orientation = body_orientation(world, e);
        Vec3 velocity = body_linear_velocity(world, e);
        Vec3 spin = body_angular_velocity(world, e);
        if (!body.parent.empty()) {
            // The inverse of the loader's placement: a part's pose and velocities relative to its parent,
            // whose velocity field v_p + ω_p × (x − c_p) the part shares.
            const Entity p = find_body(world, body.parent);
            const Quat qp = body_orientation(world, p);
            const Vec3 wp = body_angular_velocity(world, p);
            velocity = inv_rotate(qp, velocity - body_linear_velocity(world, p) -
                                          cross(wp, position - body_center_of_mass(world, p)));
            spin = inv_rotate(qp, spin - wp);
            position = inv_rotate(qp, position - body_position(world, p));
            orientation = normalized(conjugate(qp) * orientation);
        }
        body.def.position = position;
        body.def.orientation = orientation;
        body.def.linear_velocity = velocity;
        body.def.angular_velocity = spin;
        if (include_shapes)
            body.def.shape = body_shape(world, e);
    }
    return {};
}

} // namespace supermodal
