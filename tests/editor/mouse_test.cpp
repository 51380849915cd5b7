// Tests for rays through screen pixels (editor/render_hook.cpp, engine/src/render/camera_ray.cpp) and the
// script's click, pixel drag and pixel push actions.
#ifdef SM_HAS_RENDER
#include "render_hook.h"
#include "script.h"
#include "supermodal/body.h"
#include "supermodal/render.h"
#include "ui.h"

#include <gtest/gtest.h>
#include <sstream>

namespace sm = supermodal;
namespace ed = supermodal::editor;

namespace
{

const std::string k_board = std::string(SM_SOURCE_DIR) + "/samples/ball_on_board.json";

std::array<double, 2> pixel_of(const ed::EditorSession& s, ed::EditorUi& ui, const sm::Vec3& p)
{
    const auto px = ed::screen_pixel(s, ui, p);
    EXPECT_TRUE(px.has_value());
    return px.value_or(std::array<double, 2>{-1, -1});
}

double distance_to_ray(const ed::Ray& r, const sm::Vec3& p)
{
    const sm::Vec3 d = sm::normalized(r.direction);
    const sm::Vec3 off = p - r.origin;
    return sm::length(off - sm::dot(off, d) * d);
}

} // namespace

TEST(EditorMouse, TheRayThroughABodysProjectedCentrePassesThroughItAndPicksIt)
{
    ed::EditorSession s;
    ASSERT_TRUE(s.load(k_board));
    for (const auto& [w, h] : {std::pair{1280, 720}, std::pair{640, 640}}) {
        ed::EditorUi ui(s, w, h);
        for (const char* name : {"ball", "board", "support_left", "support_right"}) {
            const sm::Vec3 centre = sm::body_position(s.world(), sm::find_body(s.world(), name));
            const auto [x, y] = pixel_of(s, ui, centre);
            ASSERT_GE(x, 0.0);
            ASSERT_LE(x, w);
            sm::Result<ed::Ray> ray = ed::screen_ray(s, ui, x, y);
            ASSERT_TRUE(ray) << ray.error().message();
            // Two routes (the renderer's float view-projection matrix one way, the orbit axes and the
            // field of view back): float rounding of a matrix at ~1 m gives ~1e-6 m; a wrong axis,
            // aspect or flipped y would miss by centimetres.
            EXPECT_LT(distance_to_ray(*ray, centre), 1e-5) << name << " at " << w << "x" << h;
        }
        // The ball and the board are in plain view: a click on their centres selects them.
        for (const char* name : {"ball", "board"}) {
            const auto [x, y] = pixel_of(s, ui, sm::body_position(s.world(), sm::find_body(s.world(), name)));
            const std::optional<ed::PickHit> hit = s.pick(*ed::screen_ray(s, ui, x, y));
            ASSERT_TRUE(hit.has_value()) << name;
            EXPECT_EQ(hit->name, name);
        }
        // The view's top-left corner looks over the bodies: nothing there but (far away) the floor.
        const std::optional<ed::PickHit> corner = s.pick(*ed::screen_ray(s, ui, ui.viewport().x0 + 1, 1));
        EXPECT_TRUE(!corner || corner->name == "floor") << corner->name;
    }
}

TEST(EditorMouse, ScriptClickAndPixelDragActOnTheBodyUnderTheMouse)
{
    ed::EditorSession s;
    ed::EditorUi ui(s, 1280, 720);
    ASSERT_TRUE(s.load(k_board));
    const sm::Vec3 ball = sm::body_position(s.world(), sm::find_body(s.world(), "ball"));
    const auto [x, y] = pixel_of(s, ui, ball);
    std::ostringstream log;
    const auto run = [&](const std::string& actions) {
        return ed::run_script_text(R"({"actions": [)" + actions + "]}", "test", ".", s, ui, log);
    };
    const std::string px = std::to_string(x), py = std::to_string(y);
    ed::ScriptOutcome ok =
        run(R"({"action": "click", "x": )" + px + R"(, "y": )" + py + R"(, "expect": "ball"})");
    EXPECT_EQ(ok.failure, ed::ScriptFailure::None) << ok.error.message();
    EXPECT_EQ(ui.selected_body(), "ball");
    ed::ScriptOutcome wrong =
        run(R"({"action": "click", "x": )" + px + R"(, "y": )" + py + R"(, "expect": "board"})");
    EXPECT_EQ(wrong.failure, ed::ScriptFailure::CheckFailed);
    ed::ScriptOutcome outside = run(R"({"action": "click", "x": 2000, "y": 10})");
    EXPECT_EQ(outside.failure, ed::ScriptFailure::BadScript);
    EXPECT_EQ(outside.error.where, "/actions/0/x");

    // Drag the ball 100 px up the screen for 0.5 s: it rises (gravity alone would drop it 1.2 m).
    ed::ScriptOutcome drag = run(R"({"action": "drag", "x0": )" + px + R"(, "y0": )" + py + R"(, "x1": )" +
                                 px + R"(, "y1": )" + std::to_string(y - 100) + R"(, "steps": 1000})");
    ASSERT_EQ(drag.failure, ed::ScriptFailure::None) << drag.error.message();
    const sm::Vec3 after = sm::body_position(s.world(), sm::find_body(s.world(), "ball"));
    EXPECT_GT(after.y, ball.y + 0.05);
    // It followed the mouse: it hangs from the grabbed surface point, which sits the spring's sag
    // g/ω² = 15.5 mm below the target, so its centre is within radius + sag (25 + 15.5 mm; 5 mm for the
    // swing left after 0.5 s at ζ = 0.7) of the ray through the pixel it was pulled to, and below it.
    EXPECT_LT(distance_to_ray(*ed::screen_ray(s, ui, x, y - 100), after), 0.025 + 0.0155 + 0.005);
    EXPECT_GT(pixel_of(s, ui, after)[1], y - 100);
}
#endif
