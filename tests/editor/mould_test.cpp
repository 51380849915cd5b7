// Tests for editor/mould.cpp: pressing a plastic body leaves a dent; an elastic one springs back.
#include "session.h"
#include "supermodal/body.h"
#include "supermodal/modal.h"

#include <cmath>
#include <cstdio>
#include <gtest/gtest.h>

namespace sm = supermodal;
namespace ed = supermodal::editor;

namespace
{

struct Dent {
    double reached = 0.0; ///< Deepest while pressed [m].
    double kept = 0.0;    ///< Left after letting go and settling [m].
    double plastic_strain = 0.0;
    double slid = 0.0; ///< Horizontal distance the block moved from where it settled [m].
};

// Settle on the floor, press the top's centre 10 mm deep for 0.3 s, let go, settle 0.7 s.
Dent press(double yield_stress)
{
    ed::EditorSession s;
    EXPECT_TRUE(s.load(std::string(SM_SOURCE_DIR) + "/tests/editor/clay.json"));
    EXPECT_TRUE(s.set("/materials/clay/yield_stress", yield_stress));
    s.step(300);
    const ed::Ray down{{0.0, 0.5, 0.0}, {0.0, -1.0, 0.0}};
    const std::optional<ed::PickHit> hit = s.pick(down);
    EXPECT_TRUE(hit && hit->name == "clay");
    const sm::Entity clay = hit->body;
    const sm::Vec3 dir_shape = sm::rotate(sm::conjugate(sm::body_orientation(s.world(), clay)), {0, -1, 0});
    const double before = s.sink_along(clay, hit->point_shape, dir_shape);
    const sm::Vec3 start = sm::body_position(s.world(), clay);
    const sm::Status ok = s.mould(down, 0.01, 300);
    EXPECT_TRUE(ok) << ok.error().message();
    s.step(300 + 700);
    Dent d;
    d.reached = s.mould_depth_reached();
    d.kept = s.sink_along(clay, hit->point_shape, dir_shape) - before;
    d.plastic_strain = sm::body_plastic_state(s.world(), clay).plastic_strain;
    const sm::Vec3 moved = sm::body_position(s.world(), clay) - start;
    d.slid = std::hypot(moved.x, moved.z);
    return d;
}

} // namespace

TEST(EditorMould, APlasticBodyKeepsTheDentAnElasticOneSpringsBack)
{
    const Dent clay = press(2e4);
    const Dent elastic = press(1e12); // far above any stress here: elastic
    // Both were pressed to about the asked 10 mm (the finger's force overshoots a little while it grows).
    EXPECT_GT(clay.reached, 0.009);
    EXPECT_GT(elastic.reached, 0.009);
    EXPECT_GT(clay.plastic_strain, 0.0);
    EXPECT_EQ(elastic.plastic_strain, 0.0);
    // Clay keeps most of its dent; the elastic block comes back to within 1 mm (its damping settles
    // the modes well inside the 0.7 s).
    EXPECT_GT(clay.kept, 0.5 * clay.reached);
    EXPECT_LT(std::abs(elastic.kept), 0.001);
    // Pressed straight down at its middle, the block stays where it stood: by symmetry it would not move
    // at all; a tenth of a millimetre allows for the order the soft solver takes its rows in. (Contact
    // that took the moulded body's spring-back toward its old shape for motion slid it 0.18 m.)
    EXPECT_LT(clay.slid, 1e-4);
    EXPECT_LT(elastic.slid, 1e-4);
    std::printf(
        "clay: reached %.4g m, kept %.4g m, plastic strain %.3g, slid %.3g m; elastic: reached %.4g m, "
        "kept %.4g m, slid %.3g m\n",
        clay.reached, clay.kept, clay.plastic_strain, clay.slid, elastic.reached, elastic.kept, elastic.slid);
}

#ifdef SM_HAS_RENDER
#include "render_hook.h"
#include "script.h"
#include "supermodal/render.h"
#include "ui.h"

#include <sstream>

TEST(EditorMould, ScriptPushWithADepthAtAPixelMouldsTheClay)
{
    ed::EditorSession s;
    ed::EditorUi ui(s, 960, 540);
    std::ostringstream log;
    const std::string clay = std::string(SM_SOURCE_DIR) + "/tests/editor/clay.json";
    ed::ScriptOutcome settle = ed::run_script_text(R"({"actions": [{"action": "load", "file": ")" + clay +
                                                       R"("}, {"action": "step", "count": 300}]})",
                                                   "test", ".", s, ui, log);
    ASSERT_EQ(settle.failure, ed::ScriptFailure::None) << settle.error.message();
    // The middle of the top face, where the view camera shows it.
    const sm::Entity body = sm::find_body(s.world(), "clay");
    const sm::Vec3 top = sm::body_deformed_point(s.world(), body, {0, 0.05, 0});
    const auto px = ed::screen_pixel(s, ui, top);
    ASSERT_TRUE(px);
    const std::string at = R"("x": )" + std::to_string((*px)[0]) + R"(, "y": )" + std::to_string((*px)[1]);
    // Both a force and a depth: refused.
    ed::ScriptOutcome both =
        ed::run_script_text(R"({"actions": [{"action": "push", )" + at + R"(, "force": 10, "depth": 0.01}]})",
                            "test", ".", s, ui, log);
    EXPECT_EQ(both.failure, ed::ScriptFailure::BadScript);
    // The finger presses along the camera's ray through that pixel, obliquely: measure the dent along it.
    const auto ray = ed::screen_ray(s, ui, (*px)[0], (*px)[1]);
    ASSERT_TRUE(ray);
    const sm::Vec3 down_shape =
        sm::rotate(sm::conjugate(sm::body_orientation(s.world(), body)), ray->direction);
    const sm::Vec3 middle{0, 0.05, 0};
    const double before = s.sink_along(body, middle, down_shape);
    ed::ScriptOutcome pushed =
        ed::run_script_text(R"({"actions": [{"action": "push", )" + at +
                                R"(, "depth": 0.01, "steps": 300}, {"action": "step", "count": 700}]})",
                            "test", ".", s, ui, log);
    ASSERT_EQ(pushed.failure, ed::ScriptFailure::None) << pushed.error.message();
    EXPECT_GT(s.mould_depth_reached(), 0.009);
    EXPECT_GT(sm::body_plastic_state(s.world(), body).plastic_strain, 0.0);
    // The top's middle stays pressed in by more than half the 10 mm asked, in the body's frame (the
    // in-process test above finds most of it kept).
    EXPECT_GT(s.sink_along(body, middle, down_shape) - before, 0.005);
}
#endif
