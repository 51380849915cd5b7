// SPDX-License-Identifier: MIT
// Scene format v1: file → text → JSON DOM → Scene → World. All checking happens while reading the
// DOM, so every problem is reported with the JSON pointer of the value at fault; validate() on the
// resulting Defs runs too, but only as a guard against the loader and the Defs drifting apart.
#include "scene/body_reader.h"
#include "scene/constraint_reader.h"
#include "scene/json_reader.h"
#include "scene/json_text.h"
#include "scene/overrides.h"
#include "supermodal/hierarchy.h"
#include "supermodal/mesh_io.h"
#include "supermodal/modal.h"
#include "supermodal/scene.h"

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <exception>
#include <filesystem>
#include <memory>
#include <vector>

namespace supermodal
{
namespace
{

using scene_io::Json;
using scene_io::pointer_join;
using scene_io::Reader;

const std::vector<std::string_view> k_top_keys = {"settings", "materials",   "include",
                                                  "bodies",   "constraints", "camera"};
const std::vector<std::string_view> k_include_keys = {"file", "prefix", "position", "orientation"};
constexpr size_t k_max_include_depth = 16;
const std::vector<std::string_view> k_settings_keys = {
    "dt",      "substeps", "gravity",  "duration", "max_steps_per_advance", "constraint_iterations",
    "contact", "threads",  "accuracy", "sleep", "split_islands"};
const std::vector<std::string_view> k_sleep_keys = {"enabled", "linear_speed", "angular_speed", "time"};
const std::vector<std::string_view> k_accuracy_keys = {"displacement"};
const std::vector<std::string_view> k_contact_keys = {
    "solver", "soft", "path", "stiffness", "sample_spacing", "max_samples_per_body", "deformed_inside_test"};
const std::vector<std::string_view> k_contact_stiffness = {"frequency", "material"};
// In ContactSolver order.
const std::vector<std::string_view> k_contact_solvers = {"soft", "penalty"};
static_assert(static_cast<int>(ContactSolver::Penalty) == 1);
const std::vector<std::string_view> k_soft_keys = {"frequency",         "damping_ratio", "push_out_speed",
                                                   "restitution_speed", "iterations",    "relax_iterations",
                                                   "substeps"};
// In ContactPath order.
const std::vector<std::string_view> k_contact_paths = {"auto", "sampling", "support_map"};
static_assert(static_cast<int>(ContactPath::Sampling) == 1 && static_cast<int>(ContactPath::SupportMap) == 2);
const std::vector<std::string_view> k_material_keys = {"density",          "young",
                                                       "poisson",          "friction",
                                                       "restitution",      "rolling_resistance",
                                                       "damping_ratio",    "yield_stress",
                                                       "hardening",        "max_plastic_strain",
                                                       "remould_threshold"};
// Same bound as validate(const WorldDef&): more substeps than this is a mistake, not a setting.
constexpr double k_max_substeps = 1000.0;
// Same bound as validate(const WorldDef&) on thread_count.
constexpr double k_max_threads = 64.0;
// Read size for scene files [bytes].
constexpr size_t k_read_chunk = size_t{1} << 16;

// One of `names` at key `key` of an object into an enum (by index).
template <class E>
void field_choice(Reader& r, const Json& object, const std::string& where, const char* key,
                  const std::vector<std::string_view>& names, E& out)
{
    if (!r.ok())
        return;
    if (const Json* value = r.member(object, key)) {
        size_t index = 0;
        r.read_choice(*value, where + "/" + key, names, index);
        out = static_cast<E>(index);
    }
}

void read_soft_contact(Reader& r, const Json& soft, const std::string& where, SoftContactDef& out)
{
    if (!r.check_object(soft, where, k_soft_keys))
        return;
    // 0 Hz is the automatic frequency; up to 1 MHz, past which a spring is a unit mistake.
    r.field_number(soft, where, "frequency", scene_io::closed(0.0, 1e6), out.frequency_hz);
    r.field_number(soft, where, "damping_ratio", scene_io::closed(0.0, 1e3), out.damping_ratio);
    r.field_number(soft, where, "push_out_speed", scene_io::above(0.0), out.push_out_speed);
    r.field_number(soft, where, "restitution_speed", scene_io::at_least(0.0), out.restitution_speed);
    r.field_int(soft, where, "iterations", scene_io::closed(1.0, 100.0), out.iterations);
    r.field_int(soft, where, "relax_iterations", scene_io::closed(0.0, 100.0), out.relax_iterations);
    r.field_int(soft, where, "substeps", scene_io::closed(0.0, 64.0), out.substeps);
}

void read_contact(Reader& r, const Json& contact, const std::string& where, ContactDef& out)
{
    if (!r.check_object(contact, where, k_contact_keys))
        return;
    field_choice(r, contact, where, "solver", k_contact_solvers, out.solver);
    field_choice(r, contact, where, "path", k_contact_paths, out.path);
    field_choice(r, contact, where, "stiffness", k_contact_stiffness, out.stiffness);
    if (const Json* soft = r.member(contact, "soft"))
        read_soft_contact(r, *soft, where + "/soft", out.soft);
    r.field_number(contact, where, "sample_spacing", scene_io::at_least(0.0), out.sample_spacing);
    r.field_int(contact, where, "max_samples_per_body", scene_io::closed(1.0, 1e6), out.max_samples_per_body);
    r.field_bool(contact, where, "deformed_inside_test", out.deformed_inside_test);
}

// true/false, or an object of SleepDef's fields.
void read_sleep(Reader& r, const Json& sleep, const std::string& where, SleepDef& out)
{
    if (sleep.is_boolean())
        return r.read_bool(sleep, where, out.enabled);
    if (!r.check_object(sleep, where, k_sleep_keys))
        return;
    r.field_bool(sleep, where, "enabled", out.enabled);
    r.field_number(sleep, where, "linear_speed", scene_io::at_least(0.0), out.linear_speed);
    r.field_number(sleep, where, "angular_speed", scene_io::at_least(0.0), out.angular_speed);
    r.field_number(sleep, where, "time", scene_io::above(0.0), out.time);
}

void read_settings(Reader& r, const Json& root, Scene& out_scene)
{
    const Json* settings = r.member(root, "settings");
    if (settings == nullptr || !r.check_object(*settings, "/settings", k_settings_keys))
        return;
    const std::string where = "/settings";
    WorldDef& world = out_scene.world;
    // dt ≤ 1 s: longer steps are a unit mistake (ms for s), not a simulation.
    r.field_number(*settings, where, "dt", {.min = 0.0, .max = 1.0, .min_open = true}, world.dt);
    r.field_int(*settings, where, "substeps", scene_io::closed(1.0, k_max_substeps), world.substep_count);
    r.field_vec3(*settings, where, "gravity", scene_io::any_number(), world.gravity);
    r.field_number(*settings, where, "duration", scene_io::above(0.0), out_scene.duration);
    r.field_int(*settings, where, "constraint_iterations", scene_io::closed(1.0, 100.0),
                world.constraint_iterations);
    r.field_int(*settings, where, "max_steps_per_advance", scene_io::at_least(1.0),
                world.max_steps_per_advance);
    if (const Json* contact = r.member(*settings, "contact"))
        read_contact(r, *contact, where + "/contact", world.contact);
    r.field_int(*settings, where, "threads", scene_io::closed(1.0, k_max_threads), world.thread_count);
    r.field_bool(*settings, where, "split_islands", world.split_islands);
    if (const Json* sleep = r.member(*settings, "sleep"))
        read_sleep(r, *sleep, where + "/sleep", world.sleep);
    if (const Json* accuracy = r.member(*settings, "accuracy"))
        if (r.check_object(*accuracy, where + "/accuracy", k_accuracy_keys))
            r.field_number(*accuracy, where + "/accuracy", "displacement", scene_io::above(0.0),
                           out_scene.accuracy.displacement);
    if (!r.ok())
        return;
    if (Status status = validate(world); !status)
        r.fail(where, "invalid settings: " + status.error().message());
}

const std::vector<std::string_view> k_camera_keys = {"target", "distance", "yaw", "pitch", "fov"};

void read_camera(Reader& r, const Json& root, Scene& out_scene)
{
    const Json* camera = r.member(root, "camera");
    if (camera == nullptr || !r.check_object(*camera, "/camera", k_camera_keys))
        return;
    const std::string where = "/camera";
    CameraDef& out = out_scene.camera;
    if (const Json* target = r.member(*camera, "target")) {
        Vec3 t{};
        r.read_vec3(*target, where + "/target", scene_io::any_number(), t);
        out.target = t;
    }
    r.field_number(*camera, where, "distance", scene_io::at_least(0.0), out.distance);
    r.field_number(*camera, where, "yaw", scene_io::any_number(), out.yaw_deg);
    // ±89°: at ±90° the view direction is parallel to the up axis and the orbit's frame degenerates.
    r.field_number(*camera, where, "pitch", scene_io::closed(-89.0, 89.0), out.pitch_deg);
    r.field_number(*camera, where, "fov", scene_io::closed(1.0, 150.0), out.fov_deg);
}

void read_material(Reader& r, const Json& value, const std::string& where, MaterialDef& out_material)
{
    if (!r.check_object(value, where, k_material_keys))
        return;
    using scene_io::above;
    using scene_io::at_least;
    r.field_number(value, where, "density", above(0.0), out_material.density);
    r.field_number(value, where, "young", above(0.0), out_material.young);
    // (−1, 0.5): the bounds where an isotropic solid's bulk and shear moduli stay positive.
    r.field_number(value, where, "poisson", {.min = -1.0, .max = 0.5, .min_open = true, .max_open = true},
                   out_material.poisson);
    r.field_number(value, where, "friction", at_least(0.0), out_material.friction);
    r.field_number(value, where, "restitution", scene_io::closed(0.0, 1.0), out_material.restitution);
    r.field_number(value, where, "rolling_resistance", at_least(0.0), out_material.rolling_resistance);
    r.field_number(value, where, "damping_ratio", at_least(0.0), out_material.damping_ratio);
    r.field_number(value, where, "yield_stress", above(0.0), out_material.yield_stress);
    r.field_number(value, where, "hardening", at_least(0.0), out_material.hardening);
    r.field_number(value, where, "max_plastic_strain", above(0.0), out_material.max_plastic_strain);
    r.field_number(value, where, "remould_threshold", at_least(0.0), out_material.remould_threshold);
}

void read_materials(Reader& r, const Json& root, Scene& out_scene)
{
    const Json* materials = r.member(root, "materials");
    if (materials == nullptr)
        return;
    if (!materials->is_object())
        return r.fail("/materials", "expected an object, found " + scene_io::describe_value(*materials));
    for (const auto& item : materials->items()) {
        const std::string& name = item.key();
        if (name == "$schema" || name == "comment")
            continue;
        const std::string where = scene_io::pointer_join("/materials", name);
        if (name.empty())
            return r.fail(where, "a material name must not be empty");
        MaterialDef material;
        material.name = name;
        read_material(r, item.value(), where, material);
        if (!r.ok())
            return;
        out_scene.materials.push_back(std::move(material));
    }
}

struct FileCloser {
    void operator()(std::FILE* file) const { std::fclose(file); }
};

Result<std::string> read_file(const std::string& path)
{
    std::unique_ptr<std::FILE, FileCloser> file(std::fopen(path.c_str(), "rb"));
    if (!file)
        return Error{path, "", std::string("cannot open file: ") + std::strerror(errno)};
    std::string text;
    std::vector<char> chunk(k_read_chunk);
    for (;;) {
        const size_t n = std::fread(chunk.data(), 1, chunk.size(), file.get());
        text.append(chunk.data(), n);
        if (text.size() > scene_io::k_max_scene_bytes)
            return Error{path, "",
                         "file is larger than the scene size limit of " +
                             std::to_string(scene_io::k_max_scene_bytes) + " bytes"};
        if (n < k_read_chunk)
            break;
    }
    if (std::ferror(file.get()))
        return Error{path, "", std::string("cannot read file: ") + std::strerror(errno)};
    return text;
}

// Where includes are looked up and which files are open above this one (to catch cycles).
struct IncludeContext {
    std::filesystem::path base_dir;
    std::vector<std::string> open_files; ///< Canonical paths, outermost first.
};

Result<Scene> read_scene(const Json& root, const std::string& source, IncludeContext& ctx);

bool same_material(const MaterialDef& a, const MaterialDef& b)
{
    return a.density == b.density && a.young == b.young && a.poisson == b.poisson &&
           a.friction == b.friction && a.restitution == b.restitution &&
           a.rolling_resistance == b.rolling_resistance && a.damping_ratio == b.damping_ratio &&
           a.yield_stress == b.yield_stress && a.hardening == b.hardening &&
           a.max_plastic_strain == b.max_plastic_strain && a.remould_threshold == b.remould_threshold;
}

// Appends an included scene: names get the prefix, root bodies and world anchors the transform.
void merge_included(Reader& r, const std::string& where, Scene&& part, const std::string& part_dir,
                    const std::string& prefix, const Vec3& t, const Quat& q, Scene& out_scene)
{
    for (MaterialDef& m : part.materials) {
        const auto same_name = [&](const MaterialDef& o) { return o.name == m.name; };
        const auto it = std::find_if(out_scene.materials.begin(), out_scene.materials.end(), same_name);
        if (it == out_scene.materials.end())
            out_scene.materials.push_back(m);
        else if (!same_material(*it, m))
            return r.fail(pointer_join(where, "file"), "material " + scene_io::quote_text(m.name) + " in " +
                                                           part.source +
                                                           " differs from the one already defined");
    }
    for (SceneBody& b : part.bodies) {
        b.def.name = prefix + b.def.name;
        // Mesh paths are relative to the file that names them: rebase onto the including file's folder.
        if (!b.mesh.empty())
            b.mesh = (std::filesystem::path(part_dir) / b.mesh).lexically_normal().string();
        for (const SceneBody& o : out_scene.bodies)
            if (o.def.name == b.def.name)
                return r.fail(pointer_join(where, "prefix"), "body name " + scene_io::quote_text(b.def.name) +
                                                                 " from " + part.source +
                                                                 " is already taken; choose another prefix");
        if (b.parent.empty()) {
            b.def.position = t + rotate(q, b.def.position);
            b.def.orientation = normalized(q * normalized(b.def.orientation));
            b.def.linear_velocity = rotate(q, b.def.linear_velocity);
            b.def.angular_velocity = rotate(q, b.def.angular_velocity);
        } else {
            b.parent = prefix + b.parent;
        }
        out_scene.bodies.push_back(std::move(b));
    }
    for (SceneConstraint& c : part.constraints) {
        c.def.name = c.def.name.empty() ? c.def.name : prefix + c.def.name;
        c.body_a = prefix + c.body_a;
        if (c.body_b.empty())
            c.def.anchor_b.point = t + rotate(q, c.def.anchor_b.point);
        else
            c.body_b = prefix + c.body_b;
        out_scene.constraints.push_back(std::move(c));
    }
}

void read_include(Reader& r, const Json& item, const std::string& where, IncludeContext& ctx,
                  Scene& out_scene)
{
    if (!r.check_object(item, where, k_include_keys))
        return;
    std::string file, prefix;
    if (const Json* f = r.require(item, where, "file"))
        r.read_string(*f, pointer_join(where, "file"), file);
    if (const Json* p = r.member(item, "prefix"))
        r.read_string(*p, pointer_join(where, "prefix"), prefix);
    Vec3 t{};
    r.field_vec3(item, where, "position", scene_io::any_number(), t);
    double qv[4] = {1, 0, 0, 0};
    if (const Json* o = r.member(item, "orientation"))
        r.read_numbers(*o, pointer_join(where, "orientation"), scene_io::any_number(), qv);
    const Quat q{qv[0], qv[1], qv[2], qv[3]};
    if (r.ok() && !(norm(q) > 0.0))
        return r.fail(pointer_join(where, "orientation"), "expected a non-zero quaternion [w, x, y, z]");
    if (!r.ok())
        return;
    const std::filesystem::path path = ctx.base_dir / file;
    std::error_code ec;
    const std::filesystem::path canonical = std::filesystem::weakly_canonical(path, ec);
    const std::string key = ec ? path.string() : canonical.string();
    if (std::find(ctx.open_files.begin(), ctx.open_files.end(), key) != ctx.open_files.end())
        return r.fail(pointer_join(where, "file"), "include cycle: " + path.string() + " includes itself");
    if (ctx.open_files.size() >= k_max_include_depth)
        return r.fail(pointer_join(where, "file"),
                      "includes nest deeper than " + std::to_string(k_max_include_depth));
    // Only regular files: a FIFO or a device (/dev/stdin) would block or never end.
    if (!std::filesystem::is_regular_file(path, ec))
        return r.fail(pointer_join(where, "file"),
                      "cannot open file: not a regular file (" + path.string() + ")");
    Result<std::string> text = read_file(path.string());
    if (!text)
        return r.fail(pointer_join(where, "file"), text.error().what + " (" + path.string() + ")");
    Result<Json> json = scene_io::parse_json_text(*text, path.string());
    if (!json)
        return r.fail(pointer_join(where, "file"), "in " + json.error().message());
    IncludeContext inner{path.parent_path(), ctx.open_files};
    inner.open_files.push_back(key);
    Result<Scene> part = read_scene(*json, path.string(), inner);
    if (!part)
        return r.fail(pointer_join(where, "file"), "in " + part.error().message());
    merge_included(r, where, std::move(*part), std::filesystem::path(file).parent_path().string(), prefix, t,
                   normalized(q), out_scene);
}

// Included files are scenes of their own; only their materials, bodies and constraints are used.
void read_includes(Reader& r, const Json& root, IncludeContext& ctx, Scene& out_scene)
{
    const Json* includes = r.member(root, "include");
    if (includes == nullptr)
        return;
    if (!includes->is_array())
        return r.fail("/include", "expected an array, found " + scene_io::describe_value(*includes));
    for (size_t i = 0; i < includes->size() && r.ok(); ++i)
        read_include(r, (*includes)[i], pointer_join("/include", i), ctx, out_scene);
}

// Reads the "mesh" files of this file's own bodies (those from index `first` on; included ones were
// read by their own file). A bad file is an error at the body's "mesh" pointer.
void load_render_meshes(Reader& r, const std::filesystem::path& base_dir, size_t first, Scene& scene)
{
    for (size_t i = first; i < scene.bodies.size() && r.ok(); ++i) {
        SceneBody& b = scene.bodies[i];
        if (b.mesh.empty())
            continue;
        const std::string path = (base_dir / b.mesh).string();
        const std::string where = pointer_join(pointer_join("/bodies", i - first), "mesh");
        // As for includes: a FIFO or a device (/dev/stdin) would block or never end.
        std::error_code ec;
        if (std::filesystem::exists(path, ec) && !std::filesystem::is_directory(path, ec) &&
            !std::filesystem::is_regular_file(path, ec))
            return r.fail(where, path + ": not a regular file");
        ImportDef def = default_import_def();
        def.keep_look = true;
        Result<ImportedMesh> m = import_mesh(path, def);
        if (!m)
            return r.fail(where, m.error().message());
        for (const MeshMaterial& mat : m->look.materials)
            if (!mat.base_color_texture.empty() &&
                !std::filesystem::is_regular_file(mat.base_color_texture, ec))
                return r.fail(where, path + ": material \"" + mat.name + "\": texture " +
                                         mat.base_color_texture + " not found");
        b.render_mesh = std::make_shared<const TriangleMesh>(std::move(m->mesh));
        if (!m->look.texcoords.empty() || !m->look.materials.empty())
            b.render_look = std::make_shared<const MeshLook>(std::move(m->look));
    }
}

Result<Scene> read_scene(const Json& root, const std::string& source, IncludeContext& ctx)
{
    if (!root.is_object())
        return Error{source, "",
                     "expected a JSON object at the top level, found " + scene_io::describe_value(root)};
    Reader reader(source);
    Scene scene;
    scene.source = source;
    reader.check_object(root, "", k_top_keys);
    read_settings(reader, root, scene);
    read_materials(reader, root, scene);
    read_camera(reader, root, scene);
    read_includes(reader, root, ctx, scene);
    const size_t included = scene.bodies.size();
    scene_io::read_bodies(reader, root, scene);
    load_render_meshes(reader, ctx.base_dir, included, scene);
    scene_io::read_constraints(reader, root, scene);
    if (!reader.ok())
        return reader.error();
    return scene;
}

Result<Scene> parse_scene_in(std::string_view json_text, const std::string& source, IncludeContext ctx,
                             std::span<const SceneOverride> overrides)
{
    Result<Json> json = scene_io::parse_json_text(json_text, source);
    if (!json)
        return json.error();
    if (Status s = scene_io::apply_overrides(*json, overrides, source); !s)
        return s.error();
    // The readers check every type before converting, so nothing here should throw; this keeps the
    // promise that no exception leaves the public API even if that ever stops being true.
    try {
        return read_scene(*json, source, ctx);
    } catch (const std::exception& e) {
        return Error{source, "", std::string("internal error while reading the scene: ") + e.what()};
    }
}

} // namespace

Result<Scene> load_scene(const std::string& path)
{
    return load_scene(path, {});
}

Result<Scene> load_scene(const std::string& path, std::span<const SceneOverride> overrides)
{
    Result<std::string> text = read_file(path);
    if (!text)
        return text.error();
    std::error_code ec;
    const std::filesystem::path canonical = std::filesystem::weakly_canonical(path, ec);
    IncludeContext ctx{std::filesystem::path(path).parent_path(), {ec ? path : canonical.string()}};
    return parse_scene_in(*text, path, std::move(ctx), overrides);
}

Result<Scene> parse_scene(std::string_view json_text, const std::string& source)
{
    return parse_scene(json_text, source, {});
}

Result<Scene> parse_scene(std::string_view json_text, const std::string& source,
                          std::span<const SceneOverride> overrides)
{
    std::error_code ec;
    std::filesystem::path cwd = std::filesystem::current_path(ec);
    return parse_scene_in(json_text, source, IncludeContext{ec ? std::filesystem::path(".") : cwd, {}},
                          overrides);
}

namespace
{

// A child's pose and velocities are given in its parent's frame: make them world quantities. The
// child moves with the parent's velocity field (v + ω × r) plus its own, like a rigidly attached part.
void place_in_parent(const World& world, Entity parent, BodyDef& def)
{
    const Vec3 origin = body_position(world, parent);
    const Quat q = body_orientation(world, parent);
    const Vec3 position = origin + rotate(q, def.position);
    const Vec3 w = body_angular_velocity(world, parent);
    const Vec3 v =
        body_linear_velocity(world, parent) + cross(w, position - body_center_of_mass(world, parent));
    def.position = position;
    def.orientation = normalized(q * normalized(def.orientation));
    def.linear_velocity = v + rotate(q, def.linear_velocity);
    def.angular_velocity = w + rotate(q, def.angular_velocity);
}

// A Scene may be built or edited in code, so its Defs are checked again before create_body asserts.
Status validate_scene(const Scene& scene)
{
    if (Status status = validate(scene.world); !status)
        return Error{scene.source, "/settings", "invalid settings: " + status.error().message()};
    for (size_t i = 0; i < scene.bodies.size(); ++i) {
        const SceneBody& body = scene.bodies[i];
        const std::string where = scene_io::pointer_join("/bodies", i);
        // Auto bodies are modal with adaptive modes, or rigid where they cannot deform (parse_scene).
        const bool modal_type = body.dynamics == DynamicsType::Modal || body.dynamics == DynamicsType::Full;
        if (body.dynamics == DynamicsType::Auto
                ? body.def.modal.enabled && !(body.def.modal.adaptive_tolerance > 0.0)
                : modal_type != body.def.modal.enabled ||
                      (body.dynamics == DynamicsType::Full) != (body.def.modal.mode_count == k_all_modes))
            return Error{scene.source, where + "/dynamics/type",
                         "dynamics type and BodyDef::modal.enabled disagree"};
        if (Status status = validate(body.def); !status)
            return Error{scene.source, where, "invalid body: " + status.error().message()};
    }
    return {};
}

// Creates scene body i, placed in its parent's frame when it has one.
Status add_scene_body(const Scene& scene, size_t i, World& world)
{
    BodyDef def = scene.bodies[i].def;
    Entity parent{};
    if (!scene.bodies[i].parent.empty()) {
        parent = find_body(world, scene.bodies[i].parent);
        if (parent.is_null())
            return Error{scene.source, scene_io::pointer_join("/bodies", i) + "/parent",
                         "no earlier body named " + scene_io::quote_text(scene.bodies[i].parent)};
        place_in_parent(world, parent, def);
    }
    // Contact properties come from the body's material (density was resolved while reading).
    for (const MaterialDef& m : scene.materials)
        if (m.name == scene.bodies[i].material) {
            def.friction = m.friction;
            def.restitution = m.restitution;
            def.rolling_resistance = m.rolling_resistance;
            def.young = m.young;
            def.poisson = m.poisson;
        }
    // A modal basis can fail to build (too many modes for the lattice, a lattice too coarse to hold
    // the body together): say why before create_body would only refuse.
    if (def.modal.enabled)
        if (auto basis = modal_basis_for(world, def); !basis)
            return Error{scene.source, scene_io::pointer_join("/bodies", i) + "/dynamics",
                         "cannot build the modal basis: " + basis.error().message()};
    const Entity body = create_body(world, def);
    if (body.is_null())
        return Error{scene.source, scene_io::pointer_join("/bodies", i), "the world refused this body"};
    if (!parent.is_null())
        (void)set_body_parent(world, body, parent); // parent is earlier, so no cycle
    return {};
}

Status add_scene_constraint(const Scene& scene, size_t i, World& world)
{
    const SceneConstraint& sc = scene.constraints[i];
    const std::string where = scene_io::pointer_join("/constraints", i);
    ConstraintDef def = sc.def;
    def.a = find_body(world, sc.body_a);
    def.b = sc.body_b.empty() ? Entity{} : find_body(world, sc.body_b);
    if (def.a.is_null() || (!sc.body_b.empty() && def.b.is_null()))
        return Error{scene.source, where, "names a body that is not in the scene"};
    if (Status status = validate(def); !status)
        return Error{scene.source, where, "invalid constraint: " + status.error().message()};
    if (create_constraint(world, def).is_null())
        return Error{scene.source, where, "the world refused this constraint"};
    return {};
}

} // namespace

Result<World> build_world(const Scene& scene)
{
    if (Status status = validate_scene(scene); !status)
        return status.error();
    World world(scene.world);
    for (size_t i = 0; i < scene.bodies.size(); ++i)
        if (Status status = add_scene_body(scene, i, world); !status)
            return status.error();
    for (size_t i = 0; i < scene.constraints.size(); ++i)
        if (Status status = add_scene_constraint(scene, i, world); !status)
            return status.error();
    return world;
}

} // namespace supermodal
