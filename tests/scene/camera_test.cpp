// SPDX-License-Identifier: MIT
// The scene's "camera" object (docs/scene_format.md): defaults, values, and errors with JSON pointers.
#include "supermodal/scene.h"

#include <gtest/gtest.h>

namespace sm = supermodal;

TEST(SceneCamera, AbsentMeansFramedDefaults)
{
    sm::Result<sm::Scene> s = sm::parse_scene("{}");
    ASSERT_TRUE(s) << s.error().message();
    EXPECT_FALSE(s->camera.target.has_value());
    EXPECT_EQ(s->camera.distance, 0.0);
    EXPECT_EQ(s->camera.yaw_deg, 30.0);
    EXPECT_EQ(s->camera.pitch_deg, 20.0);
    EXPECT_EQ(s->camera.fov_deg, 40.0);
}

TEST(SceneCamera, ReadsEveryField)
{
    sm::Result<sm::Scene> s = sm::parse_scene(
        R"({"camera": {"target": [1, 2, 3], "distance": 4.5, "yaw": -20, "pitch": 35, "fov": 60}})");
    ASSERT_TRUE(s) << s.error().message();
    ASSERT_TRUE(s->camera.target.has_value());
    EXPECT_EQ(s->camera.target->z, 3.0);
    EXPECT_EQ(s->camera.distance, 4.5);
    EXPECT_EQ(s->camera.yaw_deg, -20.0);
    EXPECT_EQ(s->camera.pitch_deg, 35.0);
    EXPECT_EQ(s->camera.fov_deg, 60.0);
}

TEST(SceneCamera, ErrorsNameThePointer)
{
    const struct {
        const char* json;
        const char* where;
    } cases[] = {
        {R"({"camera": {"pitch": 90}})", "/camera/pitch"},
        {R"({"camera": {"fov": 0}})", "/camera/fov"},
        {R"({"camera": {"distance": -1}})", "/camera/distance"},
        {R"({"camera": {"target": [0, 1]}})", "/camera/target"},
        {R"({"camera": {"yaww": 3}})", "/camera"},
        {R"({"camera": 3})", "/camera"},
    };
    for (const auto& c : cases) {
        sm::Result<sm::Scene> s = sm::parse_scene(c.json);
        ASSERT_FALSE(s) << c.json;
        EXPECT_EQ(s.error().where.rfind(c.where, 0), 0u) << c.json << " -> " << s.error().message();
    }
}
