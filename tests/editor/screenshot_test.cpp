// Tests for editor/render_hook.cpp: the ImGui windows drawn over the 3-D view in the screenshot, and the
// plain 3-D view when they are hidden.
#ifdef SM_HAS_RENDER
#include "render_hook.h"
#include "supermodal/body.h"
#include "supermodal/render.h"
#include "ui.h"

#include <algorithm>
#include <gtest/gtest.h>
#include <imgui.h>
#include <imgui_internal.h>

namespace sm = supermodal;
namespace ed = supermodal::editor;

namespace
{

constexpr int k_width = 1280, k_height = 720; // the editor's default display

struct Rect {
    int x0, y0, x1, y1; // [px], half-open
};

/// Pixels where some channel of a and b differs by more than `tolerance`, over the rectangle.
double differing_fraction(const sm::Image& a, const sm::Image& b, const Rect& r, int tolerance)
{
    long long differ = 0, total = 0;
    for (int y = r.y0; y < r.y1; ++y)
        for (int x = r.x0; x < r.x1; ++x) {
            const size_t i = (static_cast<size_t>(y) * a.width + x) * 4;
            int d = 0;
            for (int c = 0; c < 3; ++c)
                d = std::max(d, std::abs(int(a.rgba[i + c]) - int(b.rgba[i + c])));
            differ += d > tolerance;
            ++total;
        }
    return total == 0 ? 0.0 : static_cast<double>(differ) / total;
}

} // namespace

TEST(EditorScreenshot, WindowsAreDrawnOverTheViewAndHiddenWindowsLeaveThePlainView)
{
    ed::EditorSession session;
    ASSERT_TRUE(session.load(std::string(SM_SOURCE_DIR) + "/samples/ball_on_board.json"));
    session.step(10);
    ed::EditorUi ui(session, k_width, k_height);
    ui.select_body("board");
    ui.frame(0.0);
    sm::Result<sm::Image> with = ed::render_editor_image(session, ui, k_width, k_height);
    ASSERT_TRUE(with) << with.error().message();

    // The five windows' rectangles, as ImGui laid them out in that frame.
    std::vector<Rect> windows;
    ImGui::SetCurrentContext(ui.context());
    for (const char* name : {"Scene", "Parts", "Body", "Run", "Speed / accuracy"}) {
        ImGuiWindow* w = ImGui::FindWindowByName(name);
        ASSERT_NE(w, nullptr) << name;
        ASSERT_TRUE(w->Active) << name;
        windows.push_back({std::max(0, int(w->Pos.x)), std::max(0, int(w->Pos.y)),
                           std::min(k_width, int(w->Pos.x + w->Size.x)),
                           std::min(k_height, int(w->Pos.y + w->Size.y))});
    }

    // The camera and rectangle of the 3-D view between the panels.
    const sm::CameraDef camera_with = ed::editor_camera(session, ui);
    const sm::PixelRect rect_with = ed::view_rect(ui, k_width, k_height);
    EXPECT_EQ(rect_with.width, 800); // between the 211 px and 269 px columns
    EXPECT_EQ(rect_with.height, k_height);

    ui.show_windows = false;
    ui.frame(0.0);
    sm::Result<sm::Image> hidden = ed::render_editor_image(session, ui, k_width, k_height);
    ASSERT_TRUE(hidden) << hidden.error().message();

    // The plain 3-D view through the renderer alone, coloured as the editor colours it.
    sm::RenderDef def = sm::default_render_def();
    def.width = k_width;
    def.height = k_height;
    sm::Result<sm::Renderer> renderer = sm::Renderer::create(def);
    ASSERT_TRUE(renderer) << renderer.error().message();
    const std::vector<sm::Vec3> colors = sm::scene_body_colors(session.scene());
    const std::vector<sm::Entity> bodies = sm::world_bodies(session.world());
    for (size_t i = 0; i < bodies.size(); ++i)
        renderer->set_body_color(bodies[i], colors[i]);
    sm::Image plain;
    ASSERT_TRUE(renderer->render(session.world(), ed::editor_camera(session, ui), plain,
                                 sm::PoseSource::Interpolated));
    sm::Image plain_with; // the view as drawn between the panels, nothing over it
    ASSERT_TRUE(renderer->render(session.world(), camera_with, plain_with, sm::PoseSource::Interpolated, {},
                                 rect_with));

    // Hidden windows: the same GL calls on the same deterministic driver, so the same bytes (tolerance 0).
    const Rect all{0, 0, k_width, k_height};
    EXPECT_EQ(differing_fraction(*hidden, plain, all, 0), 0.0);

    for (size_t k = 0; k < windows.size(); ++k) {
        const Rect& r = windows[k];
        ASSERT_GT(r.x1 - r.x0, 50) << k;
        ASSERT_GT(r.y1 - r.y0, 50) << k;
        // A window's 94%-opaque dark background over the light 3-D view: nearly every pixel changes by far
        // more than 16 levels (rounding and anti-aliasing change a few levels at most).
        EXPECT_GT(differing_fraction(*with, plain_with, r, 16), 0.9) << "window " << k;
        // Its text was drawn from the uploaded font atlas: near-white pixels (the dark style's text is
        // white; the background under it is ≤ 30 levels). Without the atlas the glyphs would not show.
        int bright = 0;
        for (int y = r.y0; y < r.y1; ++y)
            for (int x = r.x0; x < r.x1; ++x) {
                const size_t i = (static_cast<size_t>(y) * k_width + x) * 4;
                bright += with->rgba[i] > 200 && with->rgba[i + 1] > 200 && with->rgba[i + 2] > 200;
            }
        EXPECT_GT(bright, 100) << "window " << k << " shows no text";
    }
    // Away from the windows (2 px apart, for their anti-aliased borders) the view is untouched.
    long long outside_differ = 0;
    for (int y = 0; y < k_height; ++y)
        for (int x = 0; x < k_width; ++x) {
            const bool near_window = std::any_of(windows.begin(), windows.end(), [&](const Rect& r) {
                return x >= r.x0 - 2 && x < r.x1 + 2 && y >= r.y0 - 2 && y < r.y1 + 2;
            });
            if (near_window)
                continue;
            const size_t i = (static_cast<size_t>(y) * k_width + x) * 4;
            outside_differ += with->rgba[i] != plain_with.rgba[i] ||
                              with->rgba[i + 1] != plain_with.rgba[i + 1] ||
                              with->rgba[i + 2] != plain_with.rgba[i + 2];
        }
    EXPECT_EQ(outside_differ, 0);
}

TEST(EditorScreenshot, ASecondScreenshotOfTheSameFrameIsIdentical)
{
    // The font texture is uploaded per screenshot: the draw commands must follow the new one.
    ed::EditorSession session;
    ASSERT_TRUE(session.load(std::string(SM_SOURCE_DIR) + "/samples/ball_on_board.json"));
    ed::EditorUi ui(session, 640, 360);
    ui.frame(0.0);
    sm::Result<sm::Image> a = ed::render_editor_image(session, ui, 640, 360);
    sm::Result<sm::Image> b = ed::render_editor_image(session, ui, 640, 360);
    ASSERT_TRUE(a && b);
    EXPECT_EQ(differing_fraction(*a, *b, {0, 0, 640, 360}, 0), 0.0);
}
#endif
