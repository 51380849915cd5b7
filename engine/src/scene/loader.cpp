// SPDX-License-Identifier: MIT
// Scene format v1: file → text → JSON DOM → Scene → World. All checking happens while reading the
// DOM, so every problem is reported with the JSON pointer of the value at fault; validate() on the
// resulting Defs runs too, but only as a guard against the loader and the Defs drifting apart.
#include "scene/body_reader.h"
#include "scene/json_reader.h"
#include "scene/json_text.h"
#include "supermodal/scene.h"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <exception>
#include <memory>
#include <vector>

namespace supermodal
{
namespace
{

using scene_io::Json;
using scene_io::Reader;

const std::vector<std::string_view> k_top_keys = {"settings", "materials", "bodies", "constraints"};
const std::vector<std::string_view> k_settings_keys = {
    "dt", "substeps", "gravity", "duration", "max_steps_per_advance", "threads"};
const std::vector<std::string_view> k_material_keys = {
    "density", "young", "poisson", "friction", "restitution", "damping_ratio", "yield_stress"};
// Same bound as validate(const WorldDef&): more substeps than this is a mistake, not a setting.
constexpr double k_max_substeps = 1000.0;
// Same bound as validate(const WorldDef&) on thread_count.
constexpr double k_max_threads = 64.0;
// Read size for scene files [bytes].
constexpr size_t k_read_chunk = size_t{1} << 16;

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
    r.field_int(*settings, where, "max_steps_per_advance", scene_io::at_least(1.0),
                world.max_steps_per_advance);
    r.field_int(*settings, where, "threads", scene_io::closed(1.0, k_max_threads), world.thread_count);
    if (!r.ok())
        return;
    if (Status status = validate(world); !status)
        r.fail(where, "invalid settings: " + status.error().message());
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
    r.field_number(value, where, "damping_ratio", at_least(0.0), out_material.damping_ratio);
    r.field_number(value, where, "yield_stress", above(0.0), out_material.yield_stress);
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

void read_constraints(Reader& r, const Json& root)
{
    const Json* constraints = r.member(root, "constraints");
    if (constraints == nullptr)
        return;
    if (!constraints->is_array())
        return r.fail("/constraints", "expected an array, found " + scene_io::describe_value(*constraints));
    // TODO(#7): penalty constraints. Refused rather than ignored: a chair without joints falls apart.
    if (!constraints->empty())
        r.fail("/constraints", "constraints are not supported yet (issue #7)");
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

Result<Scene> read_scene(const Json& root, const std::string& source)
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
    scene_io::read_bodies(reader, root, scene);
    read_constraints(reader, root);
    if (!reader.ok())
        return reader.error();
    return scene;
}

} // namespace

Result<Scene> load_scene(const std::string& path)
{
    Result<std::string> text = read_file(path);
    if (!text)
        return text.error();
    return parse_scene(*text, path);
}

Result<Scene> parse_scene(std::string_view json_text, const std::string& source)
{
    Result<Json> json = scene_io::parse_json_text(json_text, source);
    if (!json)
        return json.error();
    // The readers check every type before converting, so nothing here should throw; this keeps the
    // promise that no exception leaves the public API even if that ever stops being true.
    try {
        return read_scene(*json, source);
    } catch (const std::exception& e) {
        return Error{source, "", std::string("internal error while reading the scene: ") + e.what()};
    }
}

Result<World> build_world(const Scene& scene)
{
    // A Scene may be built or edited in code, so its Defs are checked again before create_body asserts.
    if (Status status = validate(scene.world); !status)
        return Error{scene.source, "/settings", "invalid settings: " + status.error().message()};
    for (size_t i = 0; i < scene.bodies.size(); ++i) {
        const SceneBody& body = scene.bodies[i];
        const std::string where = scene_io::pointer_join("/bodies", i);
        if (body.dynamics != DynamicsType::Rigid)
            return Error{scene.source, where + "/dynamics/type",
                         "modal dynamics are not implemented yet (issue #6); use \"rigid\""};
        if (Status status = validate(body.def); !status)
            return Error{scene.source, where, "invalid body: " + status.error().message()};
    }
    World world(scene.world);
    for (size_t i = 0; i < scene.bodies.size(); ++i) {
        BodyDef def = scene.bodies[i].def;
        // Contact properties come from the body's material (density was resolved while reading).
        for (const MaterialDef& m : scene.materials)
            if (m.name == scene.bodies[i].material) {
                def.friction = m.friction;
                def.restitution = m.restitution;
            }
        if (create_body(world, def).is_null())
            return Error{scene.source, scene_io::pointer_join("/bodies", i), "the world refused this body"};
    }
    return world;
}

} // namespace supermodal
