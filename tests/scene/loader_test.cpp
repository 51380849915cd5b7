// Tests for engine/src/scene/loader.cpp.
#include "scene/did_you_mean.h"
#include "supermodal/body.h"
#include "supermodal/scene.h"
#include "supermodal/shape.h"
#include "supermodal/world.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <gtest/gtest.h>
#include <numbers>
#include <string>
#include <string_view>

namespace sm = supermodal;

namespace
{

// Values are copied from the text or are exact sums; only a square root (quaternion, plane normal)
// or a closed-form volume may differ from hand arithmetic by a few ulps.
constexpr double k_round_off = 1e-12;

constexpr char k_full_scene[] = R"({
  "$schema": "https://example.org/supermodal/scene-v1.json",
  "comment": "every key of format v1",
  "settings": { "dt": 0.004, "substeps": 4, "gravity": [0, -1.62, 0.5], "duration": 2.5,
                "max_steps_per_advance": 8 },
  "materials": {
    "wood":  { "density": 450, "young": 11e9, "poisson": 0.3, "friction": 0.6, "restitution": 0.25,
               "damping_ratio": 0.02, "yield_stress": 4e7 },
    "steel": { "density": 7850, "comment": "defaults for the rest" }
  },
  "bodies": [
    { "name": "board", "material": "wood",
      "shape": { "type": "superquadric", "radii": [0.5, 0.019, 0.0445], "exponents": [0.1, 0.2],
                 "taper": [0.5, -0.25], "bend": { "curvature": 0.75, "angle": 1.5 } },
      "position": [1, 2, 3], "orientation": [2, 0, 0, 0], "velocity": [4, 5, 6],
      "angular_velocity": [7, 8, 9], "motion": "kinematic", "gravity_scale": 0.5,
      "dynamics": { "type": "rigid", "modes": 12, "lattice": [8, 2, 2] } },
    { "name": "ground", "shape": { "type": "plane", "normal": [0, 2, 0], "offset": -0.5 } }
  ],
  "constraints": []
})";

/// Success if parsing `json` fails with exactly `where` and a `what` containing `phrase`.
::testing::AssertionResult fails_at(std::string_view json, std::string_view where, std::string_view phrase)
{
    const sm::Result<sm::Scene> scene = sm::parse_scene(json, "test.json");
    if (scene)
        return ::testing::AssertionFailure() << "parsed without error";
    const sm::Error& e = scene.error();
    if (e.file != "test.json" || e.where != where || e.what.find(phrase) == std::string::npos)
        return ::testing::AssertionFailure()
               << "got \"" << e.message() << "\"; wanted where \"" << where << "\" and \"" << phrase << "\"";
    return ::testing::AssertionSuccess();
}

/// A scene with one superquadric body whose extra keys are `fields` (a JSON fragment ending in ",").
std::string one_body(std::string_view fields)
{
    return R"({"materials": {"wood": {"density": 450}, "steel": {"density": 7850}}, "bodies": [{)" +
           std::string(fields) +
           R"( "name": "ball", "shape": {"type": "superquadric", "radii": [0.1, 0.2, 0.3]}}]})";
}

} // namespace

TEST(SceneLoader, ReadsEveryFieldOfAValidScene)
{
    const sm::Result<sm::Scene> result = sm::parse_scene(k_full_scene, "full.json");
    ASSERT_TRUE(result) << result.error().message();
    const sm::Scene& scene = *result;
    EXPECT_EQ(scene.source, "full.json");
    EXPECT_EQ(scene.world.dt, 0.004);
    EXPECT_EQ(scene.world.substep_count, 4);
    EXPECT_EQ(scene.world.gravity, (sm::Vec3{0, -1.62, 0.5}));
    EXPECT_EQ(scene.world.max_steps_per_advance, 8);
    EXPECT_EQ(scene.duration, 2.5);

    ASSERT_EQ(scene.materials.size(), 2u);
    const sm::MaterialDef& wood = scene.materials[0];
    EXPECT_EQ(wood.name, "wood"); // file order, not alphabetical
    EXPECT_EQ(wood.density, 450.0);
    EXPECT_EQ(wood.young, 11e9);
    EXPECT_EQ(wood.poisson, 0.3);
    EXPECT_EQ(wood.friction, 0.6);
    EXPECT_EQ(wood.restitution, 0.25);
    EXPECT_EQ(wood.damping_ratio, 0.02);
    EXPECT_EQ(wood.yield_stress, 4e7);
    EXPECT_EQ(scene.materials[1].name, "steel");
    EXPECT_EQ(scene.materials[1].density, 7850.0);
    EXPECT_EQ(scene.materials[1].young, sm::MaterialDef{}.young);

    ASSERT_EQ(scene.bodies.size(), 2u);
    const sm::SceneBody& board = scene.bodies[0];
    EXPECT_EQ(board.def.name, "board");
    EXPECT_EQ(board.material, "wood");
    EXPECT_EQ(board.dynamics, sm::DynamicsType::Rigid);
    EXPECT_EQ(board.def.density, 450.0);
    EXPECT_EQ(board.def.motion, sm::MotionType::Kinematic);
    EXPECT_EQ(board.def.shape.type, sm::ShapeType::Superquadric);
    EXPECT_EQ(board.def.shape.radii, (sm::Vec3{0.5, 0.019, 0.0445}));
    EXPECT_EQ(board.def.shape.epsilon1, 0.1);
    EXPECT_EQ(board.def.shape.epsilon2, 0.2);
    EXPECT_EQ(board.def.shape.taper.kx, 0.5);
    EXPECT_EQ(board.def.shape.taper.ky, -0.25);
    EXPECT_EQ(board.def.shape.bend.curvature, 0.75);
    EXPECT_EQ(board.def.shape.bend.angle, 1.5);
    EXPECT_EQ(board.def.position, (sm::Vec3{1, 2, 3}));
    EXPECT_EQ(board.def.orientation, sm::Quat::identity()); // [2, 0, 0, 0] normalised
    EXPECT_EQ(board.def.linear_velocity, (sm::Vec3{4, 5, 6}));
    EXPECT_EQ(board.def.angular_velocity, (sm::Vec3{7, 8, 9}));
    EXPECT_EQ(board.def.gravity_scale, 0.5);

    const sm::SceneBody& ground = scene.bodies[1];
    EXPECT_EQ(ground.def.name, "ground");
    EXPECT_EQ(ground.material, "");
    EXPECT_EQ(ground.def.motion, sm::MotionType::Static); // a plane's default
    EXPECT_EQ(ground.def.shape.type, sm::ShapeType::Plane);
    EXPECT_EQ(ground.def.shape.plane_normal, (sm::Vec3{0, 1, 0}));
    EXPECT_EQ(ground.def.shape.plane_offset, -0.5);
}

TEST(SceneLoader, AppliesDefaultsToAnEmptyScene)
{
    const sm::Result<sm::Scene> scene = sm::parse_scene("{}");
    ASSERT_TRUE(scene) << scene.error().message();
    EXPECT_EQ(scene->source, "<string>");
    EXPECT_TRUE(scene->bodies.empty());
    EXPECT_TRUE(scene->materials.empty());
    EXPECT_EQ(scene->duration, 5.0);
    const sm::WorldDef defaults = sm::default_world_def();
    EXPECT_EQ(scene->world.dt, defaults.dt);
    EXPECT_EQ(scene->world.substep_count, defaults.substep_count);
    EXPECT_EQ(scene->world.gravity, defaults.gravity);
}

TEST(SceneLoader, NormalisesOrientationAndBodyDefaults)
{
    const sm::Result<sm::Scene> scene = sm::parse_scene(one_body(R"("orientation": [0, 0, 3, 4],)"));
    ASSERT_TRUE(scene) << scene.error().message();
    const sm::BodyDef& def = scene->bodies[0].def;
    EXPECT_NEAR(def.orientation.w, 0.0, k_round_off);
    EXPECT_NEAR(def.orientation.y, 0.6, k_round_off);
    EXPECT_NEAR(def.orientation.z, 0.8, k_round_off);
    EXPECT_EQ(def.motion, sm::MotionType::Dynamic);
    EXPECT_EQ(def.density, sm::MaterialDef{}.density); // no material: the default material
    EXPECT_EQ(def.shape.epsilon1, 1.0);
    EXPECT_EQ(def.shape.epsilon2, 1.0);
}

TEST(SceneLoader, IntegralFloatIsAnInteger)
{
    const sm::Result<sm::Scene> scene = sm::parse_scene(R"({"settings": {"substeps": 2.0}})");
    ASSERT_TRUE(scene) << scene.error().message();
    EXPECT_EQ(scene->world.substep_count, 2);
}

TEST(SceneLoader, MassSetsDensityFromTheShapeVolume)
{
    const sm::Result<sm::Scene> scene = sm::parse_scene(one_body(R"("material": "wood", "mass": 3,)"));
    ASSERT_TRUE(scene) << scene.error().message();
    const sm::BodyDef& def = scene->bodies[0].def;
    EXPECT_NEAR(def.density * sm::superquadric_volume(def.shape), 3.0, 3.0 * k_round_off);
}

TEST(SceneLoader, BodyDensityOverridesMaterial)
{
    const sm::Result<sm::Scene> scene = sm::parse_scene(one_body(R"("material": "wood", "density": 123,)"));
    ASSERT_TRUE(scene) << scene.error().message();
    EXPECT_EQ(scene->bodies[0].def.density, 123.0);
}

TEST(SceneLoaderErrors, NumberOutOfRange)
{
    EXPECT_TRUE(
        fails_at(R"({"settings": {"dt": -1}})", "/settings/dt", "expected a number in (0, 1], found -1"));
    EXPECT_TRUE(fails_at(R"({"settings": {"dt": 0}})", "/settings/dt", "found 0"));
    EXPECT_TRUE(fails_at(R"({"settings": {"duration": -2.5}})", "/settings/duration",
                         "expected a number > 0, found -2.5"));
    EXPECT_TRUE(fails_at(R"({"materials": {"wood": {"poisson": 0.5}}})", "/materials/wood/poisson",
                         "expected a number in (-1, 0.5), found 0.5"));
    EXPECT_TRUE(fails_at(R"({"bodies": [{"name": "b", "shape": {"type": "superquadric", "radii": [1, 1, 1],
                         "exponents": [1, 4.5]}}]})",
                         "/bodies/0/shape/exponents/1", "expected a number in (0, 4], found 4.5"));
    EXPECT_TRUE(
        fails_at(R"({"bodies": [{"name": "b", "shape": {"type": "superquadric", "radii": [1, -1, 1]}}]})",
                 "/bodies/0/shape/radii/1", "expected a number > 0, found -1"));
    EXPECT_TRUE(
        fails_at(one_body(R"("density": 0,)"), "/bodies/0/density", "expected a number > 0, found 0"));
}

TEST(SceneLoaderErrors, WrongTypeOrLength)
{
    EXPECT_TRUE(fails_at(one_body(R"("position": "up",)"), "/bodies/0/position",
                         "expected an array of 3 numbers, found a string \"up\""));
    EXPECT_TRUE(fails_at(one_body(R"("velocity": [1, 2],)"), "/bodies/0/velocity",
                         "expected an array of 3 numbers, found an array of 2 values"));
    EXPECT_TRUE(fails_at(one_body(R"("position": [0, null, 0],)"), "/bodies/0/position/1",
                         "expected a finite number, found null"));
    EXPECT_TRUE(fails_at(R"({"settings": [1, 2, 3]})", "/settings", "expected an object, found an array"));
    EXPECT_TRUE(fails_at(R"({"bodies": {"a": 1}})", "/bodies", "expected an array, found an object"));
    EXPECT_TRUE(fails_at(R"({"bodies": [{"name": 7, "shape": {"type": "plane"}}]})", "/bodies/0/name",
                         "expected a string, found 7"));
    EXPECT_TRUE(fails_at(R"({"bodies": [true]})", "/bodies/0", "expected an object, found true"));
}

TEST(SceneLoaderErrors, IntegerFieldRejectsFractions)
{
    EXPECT_TRUE(fails_at(R"({"settings": {"substeps": 2.5}})", "/settings/substeps",
                         "expected an integer in [1, 1000], found 2.5"));
    EXPECT_TRUE(fails_at(R"({"settings": {"substeps": 1001}})", "/settings/substeps", "found 1001"));
    EXPECT_TRUE(fails_at(R"({"settings": {"max_steps_per_advance": 0}})", "/settings/max_steps_per_advance",
                         "expected an integer in [1, 2147483647], found 0"));
    EXPECT_TRUE(fails_at(one_body(R"("dynamics": {"type": "rigid", "lattice": [8, 2.5, 2]},)"),
                         "/bodies/0/dynamics/lattice/1", "expected an integer"));
}

TEST(SceneLoaderErrors, UnknownKeySuggestsTheClosest)
{
    EXPECT_TRUE(
        fails_at(R"({"bodies": [{"name": "b", "shape": {"type": "superquadric", "radi": [1, 1, 1]}}]})",
                 "/bodies/0/shape/radi", "unknown key \"radi\"; did you mean \"radii\"?"));
    EXPECT_TRUE(fails_at(R"({"setings": {}})", "/setings", "did you mean \"settings\"?"));
    EXPECT_TRUE(fails_at(one_body(R"("angular_velocty": [0, 0, 0],)"), "/bodies/0/angular_velocty",
                         "did you mean \"angular_velocity\"?"));
    // Nothing close: list what is known instead.
    EXPECT_TRUE(fails_at(R"({"settings": {"zzzzzz": 1}})", "/settings/zzzzzz",
                         "unknown key \"zzzzzz\"; known keys: dt, substeps, gravity"));
    // A key of the other shape type says so.
    EXPECT_TRUE(fails_at(R"({"bodies": [{"name": "g", "shape": {"type": "plane", "radii": [1, 1, 1]}}]})",
                         "/bodies/0/shape/radii", "\"radii\" does not apply to a plane"));
}

TEST(SceneLoaderErrors, UnknownChoiceSuggestsTheClosest)
{
    EXPECT_TRUE(fails_at(one_body(R"("motion": "dinamic",)"), "/bodies/0/motion",
                         "expected \"static\", \"kinematic\" or \"dynamic\", found \"dinamic\"; did you mean "
                         "\"dynamic\"?"));
    EXPECT_TRUE(fails_at(R"({"bodies": [{"name": "b", "shape": {"type": "sphere"}}]})",
                         "/bodies/0/shape/type",
                         "expected \"superquadric\", \"plane\" or \"hyperquadric\", found \"sphere\""));
}

TEST(SceneLoader, ReadsTheContactSolverAndItsSettings)
{
    const auto scene = sm::parse_scene(R"({"settings": {"contact": {"solver": "soft", "soft": {
        "frequency": 45, "damping_ratio": 2, "push_out_speed": 0.5, "restitution_speed": 0.2,
        "iterations": 12, "relax_iterations": 3, "substeps": 4}}}})");
    ASSERT_TRUE(scene) << scene.error().message();
    const sm::ContactDef& c = scene->world.contact;
    EXPECT_EQ(c.solver, sm::ContactSolver::Soft);
    EXPECT_EQ(c.soft.frequency_hz, 45.0);
    EXPECT_EQ(c.soft.damping_ratio, 2.0);
    EXPECT_EQ(c.soft.push_out_speed, 0.5);
    EXPECT_EQ(c.soft.restitution_speed, 0.2);
    EXPECT_EQ(c.soft.iterations, 12);
    EXPECT_EQ(c.soft.relax_iterations, 3);
    EXPECT_EQ(c.soft.substeps, 4);
}

TEST(SceneLoaderErrors, ContactSolverSettingsNameTheirPointer)
{
    EXPECT_TRUE(fails_at(R"({"settings": {"contact": {"solver": "sofft"}}})", "/settings/contact/solver",
                         "did you mean \"soft\"?"));
    EXPECT_TRUE(fails_at(R"({"settings": {"contact": {"soft": {"push_out_speed": 0}}}})",
                         "/settings/contact/soft/push_out_speed", "expected a number > 0, found 0"));
    EXPECT_TRUE(fails_at(R"({"settings": {"contact": {"soft": {"iterations": 0}}}})",
                         "/settings/contact/soft/iterations", "found 0"));
    EXPECT_TRUE(fails_at(R"({"settings": {"contact": {"soft": {"relax_iterations": -1}}}})",
                         "/settings/contact/soft/relax_iterations", "found -1"));
    EXPECT_TRUE(fails_at(R"({"settings": {"contact": {"soft": {"relax_iterations": 101}}}})",
                         "/settings/contact/soft/relax_iterations", "found 101"));
    EXPECT_TRUE(fails_at(R"({"settings": {"split_islands": 1}})", "/settings/split_islands", "expected true or false, found 1"));
    EXPECT_TRUE(fails_at(R"({"settings": {"contact": {"soft": {"substeps": 65}}}})",
                         "/settings/contact/soft/substeps", "found 65"));
    EXPECT_TRUE(fails_at(R"({"settings": {"contact": {"soft": {"substeps": -1}}}})",
                         "/settings/contact/soft/substeps", "found -1"));
    EXPECT_TRUE(fails_at(R"({"settings": {"contact": {"soft": {"frequenzy": 3}}}})",
                         "/settings/contact/soft/frequenzy", "did you mean \"frequency\"?"));
}

TEST(SceneLoader, SleepSettingsAndBodyOptOut)
{
    const sm::Result<sm::Scene> off = sm::parse_scene(R"({"settings": {"sleep": false}})", "t.json");
    ASSERT_TRUE(off) << off.error().message();
    EXPECT_FALSE(off->world.sleep.enabled);
    const sm::Result<sm::Scene> on = sm::parse_scene(
        R"({"settings": {"sleep": {"linear_speed": 0.1, "angular_speed": 2, "time": 1.5}},
            "bodies": [{"name": "b", "shape": {"type": "superquadric", "radii": [0.1, 0.1, 0.1]},
                        "sleep": false}]})",
        "t.json");
    ASSERT_TRUE(on) << on.error().message();
    EXPECT_TRUE(on->world.sleep.enabled);
    EXPECT_EQ(on->world.sleep.linear_speed, 0.1);
    EXPECT_EQ(on->world.sleep.angular_speed, 2.0);
    EXPECT_EQ(on->world.sleep.time, 1.5);
    EXPECT_FALSE(on->bodies[0].def.allow_sleep);
}

TEST(SceneLoaderErrors, SleepSettingsNameTheirPointer)
{
    EXPECT_TRUE(fails_at(R"({"settings": {"sleep": 1}})", "/settings/sleep", "expected an object"));
    EXPECT_TRUE(fails_at(R"({"settings": {"sleep": {"enabled": "yes"}}})", "/settings/sleep/enabled",
                         "expected true or false"));
    EXPECT_TRUE(fails_at(R"({"settings": {"sleep": {"time": 0}}})", "/settings/sleep/time",
                         "expected a number > 0, found 0"));
    EXPECT_TRUE(fails_at(R"({"settings": {"sleep": {"linear_sped": 0.1}}})", "/settings/sleep/linear_sped",
                         "did you mean \"linear_speed\"?"));
    EXPECT_TRUE(fails_at(R"({"bodies": [{"name": "b", "shape": {"type": "superquadric", "radii": [1, 1, 1]},
                                          "sleep": 0}]})",
                         "/bodies/0/sleep", "expected true or false"));
}

TEST(SceneLoaderErrors, UnknownMaterialListsTheMaterials)
{
    EXPECT_TRUE(fails_at(one_body(R"("material": "oak",)"), "/bodies/0/material",
                         "unknown material \"oak\"; materials are: wood, steel"));
    EXPECT_TRUE(fails_at(one_body(R"("material": "wod",)"), "/bodies/0/material",
                         "unknown material \"wod\"; did you mean \"wood\"? materials are: wood, steel"));
    EXPECT_TRUE(fails_at(R"({"bodies": [{"name": "b", "material": "oak",
                         "shape": {"type": "superquadric", "radii": [1, 1, 1]}}]})",
                         "/bodies/0/material", "the scene defines no materials"));
}

TEST(SceneLoaderErrors, DuplicateBodyName)
{
    constexpr char k_twice[] = R"({"bodies": [
      {"name": "ball", "shape": {"type": "superquadric", "radii": [1, 1, 1]}},
      {"name": "other", "shape": {"type": "superquadric", "radii": [1, 1, 1]}},
      {"name": "ball", "shape": {"type": "superquadric", "radii": [1, 1, 1]}}]})";
    EXPECT_TRUE(fails_at(k_twice, "/bodies/2/name", "duplicate body name \"ball\" (first at /bodies/0)"));
}

TEST(SceneLoaderErrors, MissingOrEmptyName)
{
    EXPECT_TRUE(fails_at(R"({"bodies": [{"shape": {"type": "superquadric", "radii": [1, 1, 1]}}]})",
                         "/bodies/0", "missing required key \"name\""));
    EXPECT_TRUE(fails_at(R"({"bodies": [{"name": "", "shape": {"type": "plane"}}]})", "/bodies/0/name",
                         "expected a non-empty name"));
    EXPECT_TRUE(fails_at(R"({"bodies": [{"name": "b"}]})", "/bodies/0", "missing required key \"shape\""));
}

TEST(SceneLoaderErrors, ZeroLengthDirections)
{
    EXPECT_TRUE(fails_at(one_body(R"("orientation": [0, 0, 0, 0],)"), "/bodies/0/orientation",
                         "orientation quaternion has zero length"));
    EXPECT_TRUE(fails_at(R"({"bodies": [{"name": "g", "shape": {"type": "plane", "normal": [0, 0, 0]}}]})",
                         "/bodies/0/shape/normal", "plane normal has zero length"));
}

TEST(SceneLoaderErrors, NumberTooLargeForADouble)
{
    EXPECT_TRUE(fails_at(one_body(R"("position": [0, 1e999, 0],)"), "/bodies/0/position/1",
                         "expected a finite number, found 1e999"));
    EXPECT_TRUE(fails_at(R"({"settings": {"dt": -1e999}})", "/settings/dt", "expected a finite number"));
}

TEST(SceneLoaderErrors, SyntaxErrorGivesLineAndColumn)
{
    constexpr char k_trailing_comma[] = "{\n  \"settings\": {\"dt\": 0.01,}\n}";
    EXPECT_TRUE(fails_at(k_trailing_comma, "line 2, column 27", "invalid JSON"));
    EXPECT_TRUE(fails_at("", "line 1, column 1", "unexpected end of input"));
    EXPECT_TRUE(fails_at("{\"bodies\": [{\"name\": \"\xff\"}]}", "line 1, column 23", "invalid JSON"));
}

TEST(SceneLoaderErrors, DuplicateJsonKey)
{
    EXPECT_TRUE(
        fails_at(R"({"settings": {"dt": 0.01, "dt": 0.02}})", "/settings/dt", "duplicate key \"dt\""));
}

TEST(SceneLoaderErrors, TopLevelMustBeAnObject)
{
    EXPECT_TRUE(
        fails_at("[1, 2]", "", "expected a JSON object at the top level, found an array of 2 values"));
    EXPECT_TRUE(fails_at("3", "", "found 3"));
}

TEST(SceneLoaderErrors, ConstraintsNameTheirPointer)
{
    EXPECT_TRUE(fails_at(R"({"constraints": {}})", "/constraints", "expected an array"));
    EXPECT_TRUE(
        fails_at(R"({"constraints": [{"a": "x"}]})", "/constraints/0", "missing required key \"type\""));
    const std::string two =
        R"({"bodies": [{"name": "seat", "shape": {"type": "superquadric", "radii": [1, 1, 1]}},
                                           {"name": "leg", "shape": {"type": "superquadric", "radii": [1, 1, 1]}}],
                                "constraints": [)";
    EXPECT_TRUE(fails_at(two + R"({"type": "point", "a": "seta"}]})", "/constraints/0/a",
                         "no body named \"seta\"; did you mean \"seat\"?"));
    EXPECT_TRUE(fails_at(two + R"({"type": "hinge", "a": "seat"}]})", "/constraints/0/type", "hinge"));
    EXPECT_TRUE(fails_at(R"({"bodies": [{"name": "leg", "parent": "seat", "shape": {"type": "superquadric",
                          "radii": [1, 1, 1]}}, {"name": "seat", "shape": {"type": "superquadric", "radii": [1, 1, 1]}}]})",
                         "/bodies/0/parent",
                         "no earlier body named \"seat\" (a parent is listed before its children)"));
    EXPECT_TRUE(fails_at(two + R"({"type": "point", "a": "seat", "b": "seat"}]})", "/constraints/0/b",
                         "two different bodies"));
    EXPECT_TRUE(fails_at(two + R"({"type": "point", "a": "seat", "frequency": 0}]})",
                         "/constraints/0/frequency", "> 0"));
    EXPECT_TRUE(fails_at(two + R"({"type": "point", "a": "seat", "anchor_a": {"direction": [0, 0, 0]}}]})",
                         "/constraints/0/anchor_a/direction", "non-zero"));
    EXPECT_TRUE(fails_at(two + R"({"type": "point", "a": "seat", "anchor_a": {"surface": [2, 0]}}]})",
                         "/constraints/0/anchor_a/surface/0", "latitude"));
    EXPECT_TRUE(fails_at(two + R"({"type": "weld", "a": "seat", "b": "leg", "swing_limit": 1}]})",
                         "/constraints/0", "\"point\" constraints only"));
    EXPECT_TRUE(fails_at(two + R"({"type": "point", "a": "seat", "anchor_b": {"direction": [1, 0, 0]}}]})",
                         "/constraints/0/anchor_b", "world must be a point"));
    EXPECT_TRUE(fails_at(two + R"({"type": "point", "a": "seat", "collide_connected": 1}]})",
                         "/constraints/0/collide_connected", "true or false"));
    EXPECT_TRUE(fails_at(two + R"({"type": "point", "a": "seat", "anchr_a": [0, 0, 0]}]})",
                         "/constraints/0/anchr_a", "did you mean \"anchor_a\""));
}

TEST(SceneLoader, ConstraintsBuildIntoTheWorld)
{
    const sm::Result<sm::Scene> scene = sm::parse_scene(R"({
      "bodies": [{"name": "seat", "shape": {"type": "superquadric", "radii": [0.2, 0.2, 0.05]}},
                 {"name": "leg", "position": [0, -0.3, 0], "shape": {"type": "superquadric", "radii": [0.1, 0.1, 0.1]}}],
      "constraints": [{"name": "j", "type": "distance", "a": "seat", "b": "leg",
                       "anchor_a": {"direction": [0, 0, -1]}, "anchor_b": [0, 0.5, 0],
                       "frequency": 12, "damping_ratio": 0.3, "break_force": 1e4},
                      {"type": "weld", "a": "leg", "b": "world", "anchor_b": [0, 1, 0]}]})");
    ASSERT_TRUE(scene) << scene.error().message();
    ASSERT_EQ(scene->constraints.size(), 2u);
    sm::Result<sm::World> world = sm::build_world(*scene);
    ASSERT_TRUE(world) << world.error().message();
    const sm::Constraint j = sm::find_constraint(*world, "j");
    ASSERT_FALSE(j.is_null());
    const sm::ConstraintDef& d = sm::constraint_def(*world, j);
    EXPECT_EQ(d.type, sm::ConstraintType::Distance);
    EXPECT_EQ(d.frequency_hz, 12.0);
    EXPECT_EQ(d.damping_ratio, 0.3);
    EXPECT_EQ(d.break_force, 1e4);
    EXPECT_EQ(d.a, sm::find_body(*world, "seat"));
    // The direction anchor sits on the seat's surface: 0.05 m below its centre along −z.
    const auto [pa, pb] = sm::constraint_anchors(*world, j);
    EXPECT_NEAR(pa.z, -0.05, 1e-12);
    EXPECT_EQ(sm::world_constraints(*world).size(), 2u);
}

TEST(SceneLoaderErrors, DynamicsErrors)
{
    // Modal scenes themselves are tested in modal_scene_test.cpp.
    EXPECT_TRUE(fails_at(R"({"settings": {"accuracy": {"displacement": 0}}})",
                         "/settings/accuracy/displacement", "expected a number > 0, found 0"));
    EXPECT_TRUE(fails_at(R"({"settings": {"accuracy": {"force": 1}}})", "/settings/accuracy/force", "force"));
    EXPECT_TRUE(fails_at(one_body(R"("dynamics": {"type": "rigid", "modes": 0},)"),
                         "/bodies/0/dynamics/modes", "expected an integer"));
}

TEST(SceneLoaderErrors, PlaneRules)
{
    EXPECT_TRUE(fails_at(R"({"bodies": [{"name": "g", "motion": "dynamic", "shape": {"type": "plane"}}]})",
                         "/bodies/0/motion", "a plane must be \"static\", found \"dynamic\""));
    EXPECT_TRUE(fails_at(R"({"bodies": [{"name": "g", "mass": 2, "shape": {"type": "plane"}}]})",
                         "/bodies/0/mass", "\"mass\" applies only to superquadrics"));
    EXPECT_TRUE(fails_at(one_body(R"("mass": 2, "density": 3,)"), "/bodies/0/mass",
                         "give either \"density\" or \"mass\", not both"));
    EXPECT_TRUE(fails_at(one_body(R"("mass": -2,)"), "/bodies/0/mass", "expected a number > 0, found -2"));
}

TEST(SceneLoaderErrors, PointerEscapesSlashAndTilde)
{
    EXPECT_TRUE(fails_at(R"({"materials": {"a/b~c": {"density": -1}}})", "/materials/a~1b~0c/density",
                         "expected a number > 0"));
}

TEST(SceneLoaderErrors, HostileInputIsRefusedWithoutCrashing)
{
    // nlohmann parses iteratively, but the depth cap is checked first so no later pass has to care.
    const std::string deep = std::string(100000, '[') + std::string(100000, ']');
    EXPECT_TRUE(fails_at(deep, "line 1, column 65", "nested deeper than 64 levels"));
    const std::string huge((size_t{64} << 20) + 1, ' ');
    EXPECT_TRUE(fails_at(huge, "", "the limit is 67108864 bytes"));
    const std::string long_key = "{\"" + std::string(100000, 'k') + "\": 1}";
    EXPECT_TRUE(fails_at(long_key, "/" + std::string(100000, 'k'), "unknown key"));
    std::string wide = "{\"materials\": {";
    for (int i = 0; i <= 10000; ++i)
        wide += (i > 0 ? ", \"m" : "\"m") + std::to_string(i) + "\": {}";
    const std::string at_comma = "line 1, column " + std::to_string(wide.rfind(", \"m10000") + 1);
    EXPECT_TRUE(fails_at(wide + "}}", at_comma, "more than 10000 keys"));
}

TEST(SceneLoaderErrors, MessageJoinsFileWhereAndWhat)
{
    const sm::Result<sm::Scene> scene = sm::parse_scene(R"({"settings": {"dt": -1}})", "s.json");
    ASSERT_FALSE(scene);
    EXPECT_EQ(scene.error().message(), "s.json: /settings/dt: expected a number in (0, 1], found -1");
}

TEST(SceneLoaderFile, MissingFile)
{
    const std::string path = "/nonexistent/supermodal/scene.json";
    const sm::Result<sm::Scene> scene = sm::load_scene(path);
    ASSERT_FALSE(scene);
    EXPECT_EQ(scene.error().file, path);
    EXPECT_EQ(scene.error().where, "");
    EXPECT_EQ(scene.error().what, "cannot open file: No such file or directory");
}

TEST(SceneLoaderFile, ReadsAFileAndNamesItInErrors)
{
    const std::filesystem::path dir = std::filesystem::temp_directory_path() / "supermodal_loader_test";
    std::filesystem::create_directories(dir);
    const std::string good = (dir / "good.json").string(), bad = (dir / "bad.json").string();
    std::ofstream(good) << one_body("");
    std::ofstream(bad) << R"({"settings": {"dt": "fast"}})";

    const sm::Result<sm::Scene> scene = sm::load_scene(good);
    ASSERT_TRUE(scene) << scene.error().message();
    EXPECT_EQ(scene->source, good);
    ASSERT_EQ(scene->bodies.size(), 1u);

    const sm::Result<sm::Scene> failed = sm::load_scene(bad);
    ASSERT_FALSE(failed);
    EXPECT_EQ(failed.error().file, bad);
    EXPECT_EQ(failed.error().where, "/settings/dt");
    EXPECT_EQ(sm::load_scene(dir.string()).error().what, "cannot read file: Is a directory");
    std::filesystem::remove_all(dir);
}

TEST(SceneLoaderBuildWorld, CreatesBodiesInFileOrder)
{
    const sm::Result<sm::Scene> scene = sm::parse_scene(R"({
      "settings": {"dt": 0.005, "substeps": 2, "gravity": [0, -3, 0]},
      "materials": {"steel": {"density": 7850}},
      "bodies": [
        {"name": "ground", "shape": {"type": "plane"}},
        {"name": "ball", "material": "steel", "position": [1, 2, 3],
         "shape": {"type": "superquadric", "radii": [0.1, 0.1, 0.1]}},
        {"name": "brick", "mass": 2.5, "position": [-1, 0.5, 0],
         "shape": {"type": "superquadric", "radii": [0.2, 0.1, 0.05], "exponents": [0.5, 0.5]}}]})");
    ASSERT_TRUE(scene) << scene.error().message();
    sm::Result<sm::World> world = sm::build_world(*scene);
    ASSERT_TRUE(world) << world.error().message();
    EXPECT_EQ(world->settings().dt, 0.005);
    EXPECT_EQ(world->settings().substep_count, 2);
    EXPECT_EQ(world->settings().gravity, (sm::Vec3{0, -3, 0}));

    const std::vector<sm::Entity> bodies = sm::world_bodies(*world);
    ASSERT_EQ(bodies.size(), 3u);
    EXPECT_EQ(sm::body_name(*world, bodies[0]), "ground");
    EXPECT_EQ(sm::body_name(*world, bodies[1]), "ball");
    EXPECT_EQ(sm::body_name(*world, bodies[2]), "brick");
    EXPECT_EQ(sm::body_motion(*world, bodies[0]), sm::MotionType::Static);

    const sm::Entity ball = sm::find_body(*world, "ball");
    ASSERT_FALSE(ball.is_null());
    EXPECT_EQ(sm::body_position(*world, ball), (sm::Vec3{1, 2, 3}));
    const double ball_volume = 4.0 / 3.0 * std::numbers::pi * 0.1 * 0.1 * 0.1;
    EXPECT_NEAR(sm::body_mass_properties(*world, ball).mass, 7850.0 * ball_volume,
                7850.0 * ball_volume * 1e-9);

    const sm::Entity brick = sm::find_body(*world, "brick");
    ASSERT_FALSE(brick.is_null());
    EXPECT_EQ(sm::body_position(*world, brick), (sm::Vec3{-1, 0.5, 0}));
    EXPECT_NEAR(sm::body_mass_properties(*world, brick).mass, 2.5, 2.5 * k_round_off);
}

TEST(SceneLoaderBuildWorld, RefusesWhatTheLoaderWouldRefuse)
{
    sm::Scene scene;
    scene.bodies.push_back({.def = sm::default_body_def(),
                            .material = "",
                            .dynamics = sm::DynamicsType::Modal,
                            .parent = "",
                            .mesh = "",
                            .render_mesh = nullptr});
    sm::Result<sm::World> modal = sm::build_world(scene);
    ASSERT_FALSE(modal);
    EXPECT_EQ(modal.error().where, "/bodies/0/dynamics/type");

    scene.bodies[0].dynamics = sm::DynamicsType::Rigid;
    scene.bodies[0].def.density = -1.0;
    sm::Result<sm::World> negative = sm::build_world(scene);
    ASSERT_FALSE(negative);
    EXPECT_EQ(negative.error().where, "/bodies/0");

    scene.bodies.clear();
    scene.world.dt = 0.0;
    sm::Result<sm::World> bad_settings = sm::build_world(scene);
    ASSERT_FALSE(bad_settings);
    EXPECT_EQ(bad_settings.error().where, "/settings");
}

TEST(SceneLoaderDidYouMean, EditDistance)
{
    EXPECT_EQ(sm::scene_io::edit_distance("kitten", "sitting"), 3u);
    EXPECT_EQ(sm::scene_io::edit_distance("", "abc"), 3u);
    EXPECT_EQ(sm::scene_io::edit_distance("radii", "radii"), 0u);
}

TEST(SceneLoaderDidYouMean, SuggestsOnlyLikelyTypos)
{
    const std::vector<std::string_view> keys = {"dt", "substeps", "gravity", "duration"};
    EXPECT_EQ(sm::scene_io::closest_match("substep", keys), "substeps");
    EXPECT_EQ(sm::scene_io::closest_match("gravty", keys), "gravity");
    EXPECT_EQ(sm::scene_io::closest_match("x", keys), ""); // "x" → "dt" replaces everything
    EXPECT_EQ(sm::scene_io::closest_match("timestep", keys), "");
    EXPECT_EQ(sm::scene_io::did_you_mean("duraton", keys), "; did you mean \"duration\"?");
}

namespace
{

/// A scene with one hyperquadric body whose "terms" value is `terms` and extra keys `fields`.
std::string one_hyperquadric(std::string_view terms, std::string_view fields = "")
{
    return R"({"bodies": [{"name": "hq", )" + std::string(fields) +
           R"( "shape": {"type": "hyperquadric", "terms": )" + std::string(terms) + "}}]}";
}

// A rounded cube of side 1 (γ = 8) cut by a rounded slab across its diagonal: the paper's kind of solid.
constexpr char k_cut_cube_terms[] = R"([{"normal": [2, 0, 0], "offset": 0, "exponent": 8},
    {"normal": [0, 2, 0], "exponent": 8}, {"normal": [0, 0, 2], "offset": 0, "exponent": 8},
    {"normal": [1.5, 1.5, 1.5], "offset": 0.25, "exponent": 8}])";

} // namespace

TEST(SceneLoader, ReadsAHyperquadric)
{
    const sm::Result<sm::Scene> scene = sm::parse_scene(one_hyperquadric(k_cut_cube_terms, R"("mass": 2,)"));
    ASSERT_TRUE(scene) << scene.error().message();
    const sm::ShapeDef& shape = scene->bodies[0].def.shape;
    EXPECT_EQ(shape.type, sm::ShapeType::Hyperquadric);
    ASSERT_EQ(shape.terms.size(), 4u);
    EXPECT_EQ(shape.terms[1].normal, (sm::Vec3{0, 2, 0}));
    EXPECT_EQ(shape.terms[1].offset, 0.0) << "offset defaults to 0";
    EXPECT_EQ(shape.terms[3].offset, 0.25);
    EXPECT_EQ(shape.terms[3].exponent, 8.0);
    // "mass" divides by the quadrature volume, which build_world's mass properties use as well.
    sm::Result<sm::World> world = sm::build_world(*scene);
    ASSERT_TRUE(world) << world.error().message();
    EXPECT_NEAR(sm::body_mass_properties(*world, sm::find_body(*world, "hq")).mass, 2.0, 2.0 * k_round_off);
}

TEST(SceneLoader, MassOfATaperedBodyUsesTheTaperedVolume)
{
    const sm::Result<sm::Scene> scene = sm::parse_scene(R"({"bodies": [{"name": "cone", "mass": 3,
        "shape": {"type": "superquadric", "radii": [0.1, 0.1, 0.3], "taper": [0.8, 0.8],
                  "bend": {"curvature": 1.5, "angle": 0.3}}}]})");
    ASSERT_TRUE(scene) << scene.error().message();
    const sm::BodyDef& def = scene->bodies[0].def;
    EXPECT_EQ(def.shape.taper.kx, 0.8);
    EXPECT_EQ(def.shape.bend.curvature, 1.5);
    EXPECT_NEAR(def.density * sm::compute_mass_properties(def.shape, 1.0).volume, 3.0, 3.0 * k_round_off);
    // The taper grows the volume by kx·ky/a3²·∫z² dV, so the untapered volume would be wrong here.
    EXPECT_GT(std::abs(def.density * sm::superquadric_volume(def.shape) - 3.0), 0.1);
}

TEST(SceneLoaderErrors, HyperquadricRules)
{
    const std::string t = R"({"normal": [1, 0, 0], "exponent": 2})";
    EXPECT_TRUE(fails_at(one_hyperquadric("[" + t + ", " + t + "]"), "/bodies/0/shape/terms",
                         "expected an array of 3 to 256 terms"));
    EXPECT_TRUE(fails_at(R"({"bodies": [{"name": "hq", "shape": {"type": "hyperquadric"}}]})",
                         "/bodies/0/shape", "missing required key \"terms\""));
    EXPECT_TRUE(fails_at(one_hyperquadric(R"([{"normal": [1, 0, 0], "exponent": 0}, {}, {}])"),
                         "/bodies/0/shape/terms/0/exponent", "expected a number > 0, found 0"));
    EXPECT_TRUE(fails_at(one_hyperquadric(R"([{"normal": [1, 0, 0], "exponant": 2}, {}, {}])"),
                         "/bodies/0/shape/terms/0/exponant", "did you mean \"exponent\"?"));
    EXPECT_TRUE(fails_at(one_hyperquadric("[" + t + ", " + t + R"(, {"normal": [0, 0, 0], "exponent": 2}])"),
                         "/bodies/0/shape/terms/2/normal", "term normal has zero length"));
    EXPECT_TRUE(fails_at(one_hyperquadric("[" + t + ", " + t + R"(, {"normal": [0, 1], "exponent": 2}])"),
                         "/bodies/0/shape/terms/2/normal", "expected an array of 3 numbers"));
    // Normals in one plane: the body runs off to infinity along z.
    EXPECT_TRUE(fails_at(one_hyperquadric(R"([{"normal": [1, 0, 0], "exponent": 2},
        {"normal": [0, 1, 0], "exponent": 2}, {"normal": [1, 1, 0], "exponent": 4}])"),
                         "/bodies/0/shape/terms", "do not span 3-D"));
    // Two slabs that do not meet: nothing is inside.
    EXPECT_TRUE(fails_at(one_hyperquadric(R"([{"normal": [1, 0, 0], "exponent": 2},
        {"normal": [0, 1, 0], "exponent": 2}, {"normal": [0, 0, 1], "exponent": 2},
        {"normal": [1, 0, 0], "offset": -3, "exponent": 2}])"),
                         "/bodies/0/shape/terms", "the terms leave no inside"));
    // Keys of the other shape types say so, both ways.
    EXPECT_TRUE(
        fails_at(R"({"bodies": [{"name": "hq", "shape": {"type": "hyperquadric", "taper": [0, 0]}}]})",
                 "/bodies/0/shape/taper", "\"taper\" does not apply to a hyperquadric"));
    EXPECT_TRUE(fails_at(R"({"bodies": [{"name": "s", "shape": {"type": "superquadric", "terms": []}}]})",
                         "/bodies/0/shape/terms", "\"terms\" does not apply to a superquadric"));
}
