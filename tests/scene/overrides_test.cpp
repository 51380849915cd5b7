// Tests for engine/src/scene/overrides.cpp: SceneOverride through parse_scene and load_scene.
#include "supermodal/scene.h"

#include <filesystem>
#include <fstream>
#include <gtest/gtest.h>
#include <string>
#include <string_view>
#include <vector>

namespace sm = supermodal;

namespace
{

constexpr char k_scene[] = R"({
  "settings": { "dt": 0.001, "duration": 1.0 },
  "materials": { "wood": { "density": 450 }, "a/b~c": { "density": 900 } },
  "bodies": [
    { "name": "ball", "material": "wood", "shape": { "type": "superquadric", "radii": [0.1, 0.1, 0.1] },
      "position": [0, 10, 0] },
    { "name": "ground", "shape": { "type": "plane", "normal": [0, 1, 0] } }
  ]
})";

sm::Result<sm::Scene> parse(std::vector<sm::SceneOverride> overrides)
{
    return sm::parse_scene(k_scene, "test.json", overrides);
}

/// Success if the overrides are refused with where == `where` and a message containing `phrase`.
::testing::AssertionResult refused(std::vector<sm::SceneOverride> overrides, std::string_view where,
                                   std::string_view phrase)
{
    const sm::Result<sm::Scene> scene = parse(std::move(overrides));
    if (scene)
        return ::testing::AssertionFailure() << "parsed without error";
    const sm::Error& e = scene.error();
    if (e.file != "test.json" || e.where != where || e.what.find(phrase) == std::string::npos)
        return ::testing::AssertionFailure()
               << "got \"" << e.message() << "\"; wanted where \"" << where << "\" and \"" << phrase << "\"";
    return ::testing::AssertionSuccess();
}

} // namespace

TEST(SceneOverrides, ReplaceValuesInObjectsAndArrays)
{
    const sm::Result<sm::Scene> scene = parse(
        {{"/settings/dt", "0.004"}, {"/bodies/0/position/1", "3.5"}, {"/materials/wood/density", "700"}});
    ASSERT_TRUE(scene) << scene.error().message();
    // Values are copied from the JSON text, so they compare exactly.
    EXPECT_EQ(scene->world.dt, 0.004);
    EXPECT_EQ(scene->bodies[0].def.position.y, 3.5);
    EXPECT_EQ(scene->materials[0].density, 700.0);
    EXPECT_EQ(scene->bodies[0].def.density, 700.0); // the body takes its material's density
}

TEST(SceneOverrides, WholeArraysAndObjectsAndEscapedKeys)
{
    const sm::Result<sm::Scene> scene = parse({{"/bodies/0/position", "[1, 2, 3]"},
                                               {"/materials/a~1b~0c/density", "1200"},
                                               {"/bodies/0/material", "\"a/b~c\""}});
    ASSERT_TRUE(scene) << scene.error().message();
    EXPECT_EQ(scene->bodies[0].def.position.x, 1.0);
    EXPECT_EQ(scene->bodies[0].def.position.z, 3.0);
    EXPECT_EQ(scene->bodies[0].def.density, 1200.0);
}

TEST(SceneOverrides, AddAMissingMemberOfAnExistingObject)
{
    const sm::Result<sm::Scene> scene =
        parse({{"/settings/substeps", "4"}, {"/bodies/0/velocity", "[0, 1, 0]"}});
    ASSERT_TRUE(scene) << scene.error().message();
    EXPECT_EQ(scene->world.substep_count, 4);
    EXPECT_EQ(scene->bodies[0].def.linear_velocity.y, 1.0);
}

TEST(SceneOverrides, ApplyInOrderTheLastWins)
{
    const sm::Result<sm::Scene> scene = parse({{"/settings/duration", "2"}, {"/settings/duration", "0.25"}});
    ASSERT_TRUE(scene) << scene.error().message();
    EXPECT_EQ(scene->duration, 0.25);
}

TEST(SceneOverrides, ValuesAreValidatedLikeTheFile)
{
    EXPECT_TRUE(refused({{"/settings/dt", "-1"}}, "/settings/dt", "expected a number in (0, 1]"));
    EXPECT_TRUE(refused({{"/settings/dt", "\"fast\""}}, "/settings/dt", "a string"));
    EXPECT_TRUE(refused({{"/bodies/0/material", "\"oak\""}}, "/bodies/0/material", "wood"));
    // A new member must be a key the format knows.
    EXPECT_TRUE(refused({{"/settings/dtt", "1"}}, "/settings/dtt", "unknown key"));
}

TEST(SceneOverrides, MissingParentsAndElementsNameThePointer)
{
    EXPECT_TRUE(refused({{"/bodies/2/position/0", "1"}}, "/bodies/2/position/0", "/bodies/2 does not exist"));
    EXPECT_TRUE(refused({{"/bodies/2/position/0", "1"}}, "/bodies/2/position/0", "has 2 elements"));
    EXPECT_TRUE(refused({{"/camera/distance", "1"}}, "/camera/distance", "/camera does not exist"));
    EXPECT_TRUE(refused({{"/bodies/0/position/3", "1"}}, "/bodies/0/position/3", "does not exist"));
    // A material given by name is a string: there is nothing below it to set.
    EXPECT_TRUE(
        refused({{"/bodies/0/material/density", "1"}}, "/bodies/0/material/density", "not an object"));
}

TEST(SceneOverrides, MalformedPointersAreRefused)
{
    EXPECT_TRUE(refused({{"settings/dt", "1"}}, "settings/dt", "starts with '/'"));
    EXPECT_TRUE(refused({{"", "1"}}, "", "starts with '/'"));
    EXPECT_TRUE(refused({{"/settings~2/dt", "1"}}, "/settings~2/dt", "'~'"));
    EXPECT_TRUE(refused({{"/bodies/01/name", "\"x\""}}, "/bodies/01/name", "expected an index"));
    EXPECT_TRUE(refused({{"/bodies/-/name", "\"x\""}}, "/bodies/-/name", "expected an index"));
    EXPECT_TRUE(refused({{"/bodies/99999999999999999999/name", "\"x\""}}, "/bodies/99999999999999999999/name",
                        "expected an index"));
}

TEST(SceneOverrides, ValueTextMustBeJson)
{
    EXPECT_TRUE(refused({{"/settings/dt", "fast"}}, "/settings/dt", "not JSON"));
    EXPECT_TRUE(refused({{"/settings/dt", std::string(100, '[') + std::string(100, ']')}}, "/settings/dt",
                        "not JSON"));
}

TEST(SceneOverrides, LoadSceneKeepsIncludesRelativeToTheFile)
{
    // The overrides apply to the file's own JSON; its include is still found next to it.
    const auto dir = std::filesystem::temp_directory_path() / "supermodal_overrides_include";
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    std::ofstream(dir / "part.json")
        << R"({"bodies": [{"name": "b", "shape": {"type": "superquadric", "radii": [1, 1, 1]}}]})";
    std::ofstream(dir / "main.json") << R"({"include": [{"file": "part.json", "prefix": "p_"}],
      "bodies": [{"name": "a", "shape": {"type": "superquadric", "radii": [1, 1, 1]}}]})";
    const std::vector<sm::SceneOverride> o = {{"/bodies/0/position", "[0, 2, 0]"}};
    const sm::Result<sm::Scene> scene = sm::load_scene((dir / "main.json").string(), o);
    ASSERT_TRUE(scene) << scene.error().message();
    ASSERT_EQ(scene->bodies.size(), 2u);
    EXPECT_EQ(scene->bodies[0].def.name, "p_b");
    EXPECT_EQ(scene->bodies[1].def.name, "a");
    EXPECT_EQ(scene->bodies[1].def.position.y, 2.0);
    EXPECT_EQ(scene->bodies[0].def.position.y, 0.0);
    std::filesystem::remove_all(dir);
}
