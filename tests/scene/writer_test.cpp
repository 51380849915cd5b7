// Tests for engine/src/scene/writer.cpp: scene_to_json, save_scene, refresh_scene_from_world.
#include "supermodal/body.h"
#include "supermodal/hierarchy.h"
#include "supermodal/scene.h"
#include "supermodal/world.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <gtest/gtest.h>
#include <limits>
#include <sstream>
#include <string>
#include <unistd.h>
#include <vector>

namespace sm = supermodal;
namespace fs = std::filesystem;

namespace
{

// ---- Field-by-field comparison: every field of every Def, compared exactly ---------------------------

struct Diff {
    std::vector<std::string> lines;
    void check(bool same, const std::string& what)
    {
        if (!same)
            lines.push_back(what);
    }
    void num(double a, double b, const std::string& what)
    {
        // Bit-exact: the same value and the same sign of zero.
        check(a == b && std::signbit(a) == std::signbit(b),
              what + ": " + std::to_string(a) + " vs " + std::to_string(b));
    }
    void vec(const sm::Vec3& a, const sm::Vec3& b, const std::string& what)
    {
        num(a.x, b.x, what + ".x");
        num(a.y, b.y, what + ".y");
        num(a.z, b.z, what + ".z");
    }
};

void compare_shape(Diff& d, const sm::ShapeDef& a, const sm::ShapeDef& b, const std::string& w)
{
    d.check(a.type == b.type, w + ".type");
    d.vec(a.radii, b.radii, w + ".radii");
    d.num(a.epsilon1, b.epsilon1, w + ".epsilon1");
    d.num(a.epsilon2, b.epsilon2, w + ".epsilon2");
    d.num(a.taper.kx, b.taper.kx, w + ".taper.kx");
    d.num(a.taper.ky, b.taper.ky, w + ".taper.ky");
    d.num(a.bend.curvature, b.bend.curvature, w + ".bend.curvature");
    d.num(a.bend.angle, b.bend.angle, w + ".bend.angle");
    d.vec(a.plane_normal, b.plane_normal, w + ".plane_normal");
    d.num(a.plane_offset, b.plane_offset, w + ".plane_offset");
    d.check(a.terms.size() == b.terms.size(), w + ".terms.size");
    for (size_t i = 0; i < std::min(a.terms.size(), b.terms.size()); ++i) {
        const std::string t = w + ".terms[" + std::to_string(i) + "]";
        d.vec(a.terms[i].normal, b.terms[i].normal, t + ".normal");
        d.num(a.terms[i].offset, b.terms[i].offset, t + ".offset");
        d.num(a.terms[i].exponent, b.terms[i].exponent, t + ".exponent");
    }
}

void compare_body(Diff& d, const sm::SceneBody& a, const sm::SceneBody& b, const std::string& w)
{
    const sm::BodyDef &x = a.def, &y = b.def;
    d.check(x.name == y.name, w + ".name");
    d.check(x.motion == y.motion, w + ".motion");
    compare_shape(d, x.shape, y.shape, w + ".shape");
    d.num(x.density, y.density, w + ".density");
    d.vec(x.position, y.position, w + ".position");
    d.num(x.orientation.w, y.orientation.w, w + ".orientation.w");
    d.num(x.orientation.x, y.orientation.x, w + ".orientation.x");
    d.num(x.orientation.y, y.orientation.y, w + ".orientation.y");
    d.num(x.orientation.z, y.orientation.z, w + ".orientation.z");
    d.vec(x.linear_velocity, y.linear_velocity, w + ".linear_velocity");
    d.vec(x.angular_velocity, y.angular_velocity, w + ".angular_velocity");
    d.num(x.gravity_scale, y.gravity_scale, w + ".gravity_scale");
    d.check(x.allow_sleep == y.allow_sleep, w + ".allow_sleep");
    d.num(x.friction, y.friction, w + ".friction");
    d.num(x.restitution, y.restitution, w + ".restitution");
    d.check(x.modal.enabled == y.modal.enabled, w + ".modal.enabled");
    d.check(x.modal.mode_count == y.modal.mode_count, w + ".modal.mode_count");
    d.check(x.modal.lattice == y.modal.lattice, w + ".modal.lattice");
    d.check(x.modal.integrator == y.modal.integrator, w + ".modal.integrator");
    d.num(x.modal.damping_ratio, y.modal.damping_ratio, w + ".modal.damping_ratio");
    d.check(x.modal.static_correction == y.modal.static_correction, w + ".modal.static_correction");
    d.num(x.young, y.young, w + ".young");
    d.num(x.poisson, y.poisson, w + ".poisson");
    d.check(a.material == b.material, w + ".material");
    d.check(a.dynamics == b.dynamics, w + ".dynamics");
    d.check(a.parent == b.parent, w + ".parent");
}

void compare_anchor(Diff& d, const sm::AnchorDef& a, const sm::AnchorDef& b, const std::string& w)
{
    d.check(a.kind == b.kind, w + ".kind");
    d.vec(a.point, b.point, w + ".point");
    d.vec(a.direction, b.direction, w + ".direction");
    d.num(a.eta, b.eta, w + ".eta");
    d.num(a.omega, b.omega, w + ".omega");
}

void compare_constraint(Diff& d, const sm::SceneConstraint& a, const sm::SceneConstraint& b,
                        const std::string& w)
{
    const sm::ConstraintDef &x = a.def, &y = b.def;
    d.check(a.body_a == b.body_a && a.body_b == b.body_b, w + " bodies");
    d.check(x.name == y.name, w + ".name");
    d.check(x.type == y.type, w + ".type");
    compare_anchor(d, x.anchor_a, y.anchor_a, w + ".anchor_a");
    compare_anchor(d, x.anchor_b, y.anchor_b, w + ".anchor_b");
    d.num(x.frequency_hz, y.frequency_hz, w + ".frequency_hz");
    d.num(x.damping_ratio, y.damping_ratio, w + ".damping_ratio");
    d.num(x.rest_length, y.rest_length, w + ".rest_length");
    d.num(x.swing_limit, y.swing_limit, w + ".swing_limit");
    d.num(x.twist_limit, y.twist_limit, w + ".twist_limit");
    d.vec(x.axis_a, y.axis_a, w + ".axis_a");
    d.num(x.angular_damping, y.angular_damping, w + ".angular_damping");
    d.num(x.break_force, y.break_force, w + ".break_force");
    d.check(x.collide_connected == y.collide_connected, w + ".collide_connected");
}

/// Every difference between two scenes, one line each; empty when identical (source aside).
std::vector<std::string> scene_diff(const sm::Scene& a, const sm::Scene& b)
{
    Diff d;
    const sm::WorldDef &x = a.world, &y = b.world;
    d.num(x.dt, y.dt, "dt");
    d.check(x.substep_count == y.substep_count, "substep_count");
    d.vec(x.gravity, y.gravity, "gravity");
    d.check(x.max_steps_per_advance == y.max_steps_per_advance, "max_steps_per_advance");
    d.check(x.constraint_iterations == y.constraint_iterations, "constraint_iterations");
    d.check(x.thread_count == y.thread_count, "thread_count");
    d.check(x.split_islands == y.split_islands, "split_islands");
    d.check(x.sleep.enabled == y.sleep.enabled, "sleep.enabled");
    d.num(x.sleep.linear_speed, y.sleep.linear_speed, "sleep.linear_speed");
    d.num(x.sleep.angular_speed, y.sleep.angular_speed, "sleep.angular_speed");
    d.num(x.sleep.time, y.sleep.time, "sleep.time");
    d.check(x.contact.enabled == y.contact.enabled, "contact.enabled");
    d.check(x.contact.solver == y.contact.solver, "contact.solver");
    const sm::SoftContactDef &xs = x.contact.soft, &ys = y.contact.soft;
    d.num(xs.frequency_hz, ys.frequency_hz, "contact.soft.frequency_hz");
    d.num(xs.damping_ratio, ys.damping_ratio, "contact.soft.damping_ratio");
    d.num(xs.push_out_speed, ys.push_out_speed, "contact.soft.push_out_speed");
    d.num(xs.restitution_speed, ys.restitution_speed, "contact.soft.restitution_speed");
    d.check(xs.iterations == ys.iterations, "contact.soft.iterations");
    d.check(xs.relax_iterations == ys.relax_iterations, "contact.soft.relax_iterations");
    d.check(xs.substeps == ys.substeps, "contact.soft.substeps");
    d.check(x.contact.path == y.contact.path, "contact.path");
    d.num(x.contact.frequency_hz, y.contact.frequency_hz, "contact.frequency_hz");
    d.num(x.contact.damping_ratio, y.contact.damping_ratio, "contact.damping_ratio");
    d.num(x.contact.sample_spacing, y.contact.sample_spacing, "contact.sample_spacing");
    d.check(x.contact.max_samples_per_body == y.contact.max_samples_per_body, "contact.max_samples_per_body");
    d.num(x.contact.speculative_speed_factor, y.contact.speculative_speed_factor, "contact.speculative");
    d.check(x.contact.max_auto_substeps == y.contact.max_auto_substeps, "contact.max_auto_substeps");
    d.check(x.contact.deformed_inside_test == y.contact.deformed_inside_test, "contact.deformed_inside_test");
    d.num(a.duration, b.duration, "duration");
    d.check(a.materials.size() == b.materials.size(), "materials.size");
    for (size_t i = 0; i < std::min(a.materials.size(), b.materials.size()); ++i) {
        const sm::MaterialDef &m = a.materials[i], &n = b.materials[i];
        const std::string w = "materials[" + std::to_string(i) + "]";
        d.check(m.name == n.name, w + ".name");
        d.num(m.density, n.density, w + ".density");
        d.num(m.young, n.young, w + ".young");
        d.num(m.poisson, n.poisson, w + ".poisson");
        d.num(m.friction, n.friction, w + ".friction");
        d.num(m.restitution, n.restitution, w + ".restitution");
        d.num(m.damping_ratio, n.damping_ratio, w + ".damping_ratio");
        d.num(m.yield_stress, n.yield_stress, w + ".yield_stress");
        d.num(m.hardening, n.hardening, w + ".hardening");
        d.num(m.max_plastic_strain, n.max_plastic_strain, w + ".max_plastic_strain");
        d.num(m.remould_threshold, n.remould_threshold, w + ".remould_threshold");
    }
    d.check(a.camera.target.has_value() == b.camera.target.has_value(), "camera.target");
    if (a.camera.target && b.camera.target) {
        d.num(a.camera.target->x, b.camera.target->x, "camera.target.x");
        d.num(a.camera.target->y, b.camera.target->y, "camera.target.y");
        d.num(a.camera.target->z, b.camera.target->z, "camera.target.z");
    }
    d.num(a.camera.distance, b.camera.distance, "camera.distance");
    d.num(a.camera.yaw_deg, b.camera.yaw_deg, "camera.yaw");
    d.num(a.camera.pitch_deg, b.camera.pitch_deg, "camera.pitch");
    d.num(a.camera.fov_deg, b.camera.fov_deg, "camera.fov");
    d.check(a.bodies.size() == b.bodies.size(), "bodies.size");
    for (size_t i = 0; i < std::min(a.bodies.size(), b.bodies.size()); ++i)
        compare_body(d, a.bodies[i], b.bodies[i], "bodies[" + std::to_string(i) + "]");
    d.check(a.constraints.size() == b.constraints.size(), "constraints.size");
    for (size_t i = 0; i < std::min(a.constraints.size(), b.constraints.size()); ++i)
        compare_constraint(d, a.constraints[i], b.constraints[i], "constraints[" + std::to_string(i) + "]");
    return d.lines;
}

std::string joined(const std::vector<std::string>& lines)
{
    std::string out;
    for (const std::string& l : lines)
        out += l + "\n";
    return out;
}

/// Writes, reads back and checks the scenes are identical and write the same text again.
sm::Scene round_trip(const sm::Scene& scene)
{
    const std::string text = sm::scene_to_json(scene);
    sm::Result<sm::Scene> back = sm::parse_scene(text, "written");
    EXPECT_TRUE(back) << back.error().message() << "\n" << text;
    if (!back)
        return scene;
    const std::vector<std::string> diff = scene_diff(scene, *back);
    EXPECT_TRUE(diff.empty()) << "fields that changed on the way through the writer:\n" << joined(diff);
    EXPECT_EQ(text, sm::scene_to_json(*back));
    return *back;
}

/// Steps two worlds built from two scenes and compares their state hashes.
void expect_same_run(const sm::Scene& a, const sm::Scene& b, int steps)
{
    sm::Result<sm::World> wa = sm::build_world(a);
    sm::Result<sm::World> wb = sm::build_world(b);
    ASSERT_TRUE(wa) << wa.error().message();
    ASSERT_TRUE(wb) << wb.error().message();
    for (int i = 0; i < steps; ++i) {
        wa->step();
        wb->step();
    }
    EXPECT_EQ(wa->state_hash(), wb->state_hash());
}

const std::string k_source_dir = SM_SOURCE_DIR;

// Every key the writer can produce, with awkward values: an include turned and moved (so its bodies'
// orientations come from a quaternion product), parts, a hyperquadric, taper and bend, a modal body
// with its own damping, a kinematic body, all constraint types and anchor kinds, limits and breaking.
std::string every_field_scene()
{
    return R"({
  "settings": { "dt": 0.0015, "substeps": 3, "gravity": [0.1, -9.80665, 0.2], "duration": 0.7,
                "max_steps_per_advance": 5, "constraint_iterations": 7,
                "contact": { "solver": "soft", "soft": { "frequency": 47.5, "damping_ratio": 3.25,
                             "push_out_speed": 1.5, "restitution_speed": 0.75, "iterations": 9,
                                       "relax_iterations": 4, "substeps": 3 },
                             "path": "sampling", "stiffness": "material", "sample_spacing": 0.03,
                             "max_samples_per_body": 700, "deformed_inside_test": true },
                "threads": 2, "split_islands": true,
                "sleep": { "enabled": false, "linear_speed": 0.125, "angular_speed": 0.75, "time": 1.25 } },
  "camera": { "target": [0.1, 0.5, -0.25], "distance": 3.5, "yaw": -40, "pitch": 35, "fov": 50 },
  "materials": {
    "rubber": { "density": 1100, "young": 5e6, "poisson": 0.45, "friction": 0.9, "restitution": 0.7,
                "rolling_resistance": 0.002, "damping_ratio": 0.05, "yield_stress": 3e5, "hardening": 2e6, "max_plastic_strain": 0.04,
                "remould_threshold": 0.05 },
    "plain": { "density": 0.1 }
  },
  "include": [ { "file": ")" +
           k_source_dir + R"(/samples/parts/chair.json", "prefix": "c_",
                 "position": [0.3, 0.01, -0.2], "orientation": [0.9, 0.1, 0.3, -0.2] } ],
  "bodies": [
    { "name": "floor", "shape": { "type": "plane", "normal": [0.1, 1, 0.05], "offset": -0.01 } },
    { "name": "blob", "material": "rubber", "density": 1234.5678,
      "shape": { "type": "superquadric", "radii": [0.1, 0.07, 0.3], "exponents": [0.7, 1.3],
                 "taper": [0.2, -0.3], "bend": { "curvature": 1.1, "angle": 0.4 } },
      "position": [1, 0.5, 0.1], "orientation": [0.3, -0.4, 0.5, 0.6], "velocity": [0.1, 0.2, -0.3],
      "angular_velocity": [1, -2, 3], "gravity_scale": 0.5, "sleep": false,
      "dynamics": { "type": "modal", "modes": 5, "lattice": [2, 2, 4], "integrator": "central_difference",
                    "damping_ratio": 0.03, "static_correction": true } },
    { "name": "gem", "mass": 2.5, "parent": "blob",
      "shape": { "type": "hyperquadric", "terms": [
        { "normal": [8, 0, 0], "exponent": 6 }, { "normal": [0, 8, 0], "offset": 0.1, "exponent": 6 },
        { "normal": [0, 0, 8], "exponent": 4 }, { "normal": [5, 5, 5], "offset": 0.25, "exponent": 3 } ] },
      "position": [0, 0.2, 0.35], "orientation": [1, 0, 0, 1e-3], "velocity": [0, 0, 1],
      "angular_velocity": [0.5, 0, 0], "motion": "dynamic" },
    { "name": "slider", "material": "plain", "motion": "kinematic",
      "shape": { "type": "superquadric", "radii": [0.2, 0.2, 0.05], "exponents": [0.05, 4] },
      "position": [-1, 0.3, 0], "velocity": [0.5, 0, 0],
      "dynamics": { "type": "rigid", "modes": 3, "lattice": [1, 2, 3] } }
  ],
  "constraints": [
    { "name": "pin", "type": "point", "a": "blob", "b": "gem", "anchor_a": { "surface": [0.3, -2.5] },
      "anchor_b": { "direction": [0, 0, -1] }, "frequency": 45.5, "damping_ratio": 0.33,
      "swing_limit": 0.8, "twist_limit": 0.2, "axis_a": [0, 0, 1], "angular_damping": 0.4,
      "break_force": 1e4, "collide_connected": true },
    { "type": "distance", "a": "blob", "b": "world", "anchor_a": [0.01, 0.02, 0.03],
      "anchor_b": [1, 2, 3], "rest_length": 1.25 },
    { "name": "glue", "type": "weld", "a": "c_seat", "b": "slider", "anchor_a": { "point": [0, 0.1, 0] } }
  ]
})";
}

std::vector<fs::path> sample_scenes()
{
    std::vector<fs::path> out;
    for (const fs::directory_entry& e : fs::directory_iterator(k_source_dir + "/samples"))
        if (e.path().extension() == ".json")
            out.push_back(e.path());
    std::sort(out.begin(), out.end());
    return out;
}

} // namespace

TEST(SceneWriter, EverySampleReadsBackIdenticalAndRunsTheSame)
{
    const std::vector<fs::path> samples = sample_scenes();
    ASSERT_GE(samples.size(), 3u);
    for (const fs::path& path : samples) {
        SCOPED_TRACE(path.string());
        sm::Result<sm::Scene> scene = sm::load_scene(path.string());
        ASSERT_TRUE(scene) << scene.error().message();
        const sm::Scene back = round_trip(*scene);
        // 50 steps reach contact in every sample (they start touching or within a few mm); any
        // difference in the written numbers would show in the hash.
        expect_same_run(*scene, back, 50);
    }
}

TEST(SceneWriter, EveryFieldReadsBackIdenticalAndRunsTheSame)
{
    sm::Result<sm::Scene> scene = sm::parse_scene(every_field_scene(), "every_field");
    ASSERT_TRUE(scene) << scene.error().message();
    // The included chair was turned, so its orientations are products that normalisation cannot
    // reproduce from rounded text: they must read back as written, bit for bit.
    ASSERT_EQ(scene->bodies.size(), 10u);
    const sm::Scene back = round_trip(*scene);
    expect_same_run(*scene, back, 30);
    const std::string text = sm::scene_to_json(*scene);
    EXPECT_EQ(text.find("\"include\""), std::string::npos) << "includes are flattened";
    EXPECT_NE(text.find("\"c_leg_fl\""), std::string::npos) << "included names keep their prefix";
}

TEST(SceneWriter, DoublesReadBackBitForBit)
{
    sm::Scene scene;
    sm::SceneBody body;
    body.def = sm::default_body_def();
    body.def.name = "odd";
    // Values with no short decimal form, the smallest normal, a huge one and a negative zero.
    body.def.position = {0.1 + 0.2, 1.0 / 3.0, -std::numeric_limits<double>::min()};
    body.def.linear_velocity = {1e300 / 7.0, -0.0, std::nextafter(1.0, 2.0)};
    body.def.shape.radii = {std::nextafter(0.25, 0.0), 2.0 / 3.0, 1e-7 * 3.0};
    body.def.density = 1000.0 + 1e-12;
    scene.bodies.push_back(body);
    scene.world.dt = 1.0 / 3000.0;
    round_trip(scene);
}

TEST(SceneWriter, SaveReplacesTheFileAtomicallyAndRefusesABadFolder)
{
    const fs::path dir = fs::temp_directory_path() / ("sm_writer_test_" + std::to_string(::getpid()));
    fs::remove_all(dir);
    fs::create_directories(dir);
    const std::string path = (dir / "scene.json").string();
    {
        std::ofstream old(path);
        old << "old contents";
    }
    sm::Result<sm::Scene> scene = sm::load_scene(k_source_dir + "/samples/chair_with_dummy.json");
    ASSERT_TRUE(scene) << scene.error().message();
    sm::Status saved = sm::save_scene(*scene, path);
    ASSERT_TRUE(saved) << saved.error().message();
    sm::Result<sm::Scene> back = sm::load_scene(path);
    ASSERT_TRUE(back) << back.error().message();
    EXPECT_TRUE(scene_diff(*scene, *back).empty()) << joined(scene_diff(*scene, *back));
    // Only the scene itself is left in the folder: the temporary file was renamed, not copied.
    EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator{}), 1);

    const std::string missing = (dir / "no_such_folder" / "scene.json").string();
    sm::Status failed = sm::save_scene(*scene, missing);
    ASSERT_FALSE(failed);
    EXPECT_NE(failed.error().message().find("cannot write the scene"), std::string::npos)
        << failed.error().message();
    EXPECT_FALSE(fs::exists(missing));
    fs::remove_all(dir);
    // A device takes the text in place: renaming over it would make /dev/null a file.
    sm::Status to_device = sm::save_scene(*scene, "/dev/null");
    EXPECT_TRUE(to_device) << to_device.error().message();
    EXPECT_TRUE(fs::is_character_file("/dev/null"));
}

TEST(SceneWriter, RefreshKeepsTheRunningStateAndEditedShapes)
{
    sm::Result<sm::Scene> scene = sm::load_scene(k_source_dir + "/samples/chair_with_dummy.json");
    ASSERT_TRUE(scene) << scene.error().message();
    sm::Result<sm::World> world = sm::build_world(*scene);
    ASSERT_TRUE(world) << world.error().message();
    for (int i = 0; i < 200; ++i)
        world->step();
    sm::ShapeDef seat = sm::body_shape(*world, sm::find_body(*world, "chair_seat"));
    seat.radii.x = 0.3;
    ASSERT_TRUE(sm::set_body_shape(*world, sm::find_body(*world, "chair_seat"), seat));

    sm::Scene refreshed = *scene;
    ASSERT_TRUE(sm::refresh_scene_from_world(refreshed, *world));
    EXPECT_EQ(refreshed.bodies[0].def.shape.radii.x, 0.3);
    // Parts stay in their parent's frame: a rebuilt world puts every body where the running one has it.
    sm::Result<sm::World> rebuilt = sm::build_world(refreshed);
    ASSERT_TRUE(rebuilt) << rebuilt.error().message();
    // Tolerance: the parent-frame round trip is a few rotations of O(1 m) quantities, so a few ulps
    // of 1 m/s or 1 m; 1e-12 leaves room and is far below any physical change in 200 steps.
    constexpr double k_tol = 1e-12;
    for (const sm::SceneBody& b : refreshed.bodies) {
        SCOPED_TRACE(b.def.name);
        const sm::Entity e0 = sm::find_body(*world, b.def.name);
        const sm::Entity e1 = sm::find_body(*rebuilt, b.def.name);
        EXPECT_LT(sm::length(sm::body_position(*world, e0) - sm::body_position(*rebuilt, e1)), k_tol);
        EXPECT_LT(sm::length(sm::body_linear_velocity(*world, e0) - sm::body_linear_velocity(*rebuilt, e1)),
                  k_tol);
        EXPECT_LT(sm::length(sm::body_angular_velocity(*world, e0) - sm::body_angular_velocity(*rebuilt, e1)),
                  k_tol);
        const sm::Quat q0 = sm::body_orientation(*world, e0), q1 = sm::body_orientation(*rebuilt, e1);
        EXPECT_GT(std::abs(q0.w * q1.w + q0.x * q1.x + q0.y * q1.y + q0.z * q1.z), 1.0 - k_tol);
    }
    // The dummy has moved in 200 steps (0.2 s of fall onto the seat), so the refresh did something.
    const sm::SceneBody& first_dummy = refreshed.bodies[6];
    EXPECT_GT(sm::length(first_dummy.def.position - scene->bodies[6].def.position), 1e-4);

    sm::Scene stale = *scene;
    stale.bodies[0].def.name = "not_in_the_world";
    const sm::Vec3 before = stale.bodies[1].def.position;
    EXPECT_FALSE(sm::refresh_scene_from_world(stale, *world));
    EXPECT_EQ(stale.bodies[1].def.position, before) << "a failed refresh changes nothing";
}
