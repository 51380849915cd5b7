// Tests for editor/camera.cpp: orbit keeps the distance, zoom-to-cursor keeps the point under the cursor,
// pan moves the target's depth with the cursor, framing puts every box inside the frustum (and touches
// its edge with no margin), and the camera's pixels and rays are the renderer's.
#include "camera.h"
#include "supermodal/world.h"

#ifdef SM_HAS_RENDER
#include "supermodal/render.h"
#endif

#include <cmath>
#include <gtest/gtest.h>
#include <vector>

namespace sm = supermodal;
namespace ed = supermodal::editor;

namespace
{

sm::CameraDef camera(double yaw, double pitch, double distance = 3.0, sm::Vec3 target = {0.2, 0.5, -0.1})
{
    sm::CameraDef c;
    c.target = target;
    c.distance = distance;
    c.yaw_deg = yaw;
    c.pitch_deg = pitch;
    c.fov_deg = 40.0;
    return c;
}

/// Deterministic boxes scattered over a few metres (a small LCG: the same boxes every run).
std::vector<sm::Aabb> scattered_boxes(unsigned seed, int count)
{
    unsigned state = seed;
    const auto next = [&] {
        state = state * 1664525u + 1013904223u;
        return static_cast<double>(state >> 8) / static_cast<double>(1u << 24); // [0, 1)
    };
    std::vector<sm::Aabb> boxes;
    for (int i = 0; i < count; ++i) {
        const sm::Vec3 c{4.0 * next() - 2.0, 2.0 * next(), 4.0 * next() - 2.0};
        const sm::Vec3 half{0.05 + 0.5 * next(), 0.05 + 0.5 * next(), 0.05 + 0.5 * next()};
        boxes.push_back({c - half, c + half});
    }
    return boxes;
}

/// The largest |NDC| over the boxes' corners (1 = on the view's edge), all corners required in front;
/// with `clip`, also between the renderer's near and far planes.
double max_ndc(const sm::CameraDef& cam, const std::vector<sm::Aabb>& boxes, double w, double h,
               bool clip = true)
{
    double m = 0.0;
    for (const sm::Aabb& b : boxes)
        for (int k = 0; k < 8; ++k) {
            const sm::Vec3 corner{(k & 1) ? b.max.x : b.min.x, (k & 2) ? b.max.y : b.min.y,
                                  (k & 4) ? b.max.z : b.min.z};
            const std::optional<ed::ViewPixel> p = ed::view_pixel(cam, w, h, corner);
            if (!p)
                return INFINITY;
            // The renderer's near and far planes (engine/src/render/view.cpp): 0.02 and 14 distances.
            if (clip) {
                EXPECT_GT(p->depth, 0.02 * cam.distance);
                EXPECT_LT(p->depth, 14.0 * cam.distance);
            }
            m = std::max({m, std::abs(2.0 * p->x / w - 1.0), std::abs(1.0 - 2.0 * p->y / h)});
        }
    return m;
}

} // namespace

TEST(EditorCamera, OrbitKeepsTheDistanceToTheTargetAndThePitchInRange)
{
    sm::CameraDef c = camera(30.0, 20.0);
    const sm::Vec3 target = *c.target;
    for (const auto& [dyaw, dpitch] :
         {std::pair{-30.0, 0.0}, std::pair{200.0, 45.0}, std::pair{-725.0, -300.0}, std::pair{0.5, 89.0},
          std::pair{12.0, -7.0}}) {
        const double pitch_before = c.pitch_deg;
        c = ed::orbit(c, dyaw, dpitch);
        // |eye − target| is the distance whatever the angles: rounding of a 3 m length, 1e-15 relative.
        EXPECT_NEAR(sm::length(ed::camera_eye(c) - target), 3.0, 1e-12) << dyaw << ", " << dpitch;
        EXPECT_EQ(c.distance, 3.0);
        EXPECT_EQ(*c.target, target);
        EXPECT_LE(std::abs(c.pitch_deg), 89.0);
        EXPECT_LE(std::abs(c.yaw_deg), 180.0);
        if (std::abs(pitch_before + dpitch) <= 89.0) {
            EXPECT_NEAR(c.pitch_deg, pitch_before + dpitch, 1e-12);
        }
    }
    // A turn of 360° comes back to the same eye.
    const sm::CameraDef a = camera(10.0, 5.0), b = ed::orbit(a, 360.0, 0.0);
    EXPECT_NEAR(sm::length(ed::camera_eye(a) - ed::camera_eye(b)), 0.0, 1e-12);
}

TEST(EditorCamera, ZoomToCursorKeepsThePointUnderTheCursor)
{
    const double w = 800, h = 720;
    const ed::CameraControlDef control;
    for (const sm::CameraDef& c0 : {camera(30.0, 20.0), camera(-120.0, -40.0, 0.7), camera(75.0, 85.0, 12.0)})
        for (const auto& [x, y] : {std::pair{400.0, 360.0}, std::pair{13.0, 700.0}, std::pair{790.5, 2.5}})
            for (const double depth : {0.3, 1.0, 4.0}) // along the cursor's ray, in distances
                for (const double factor : {0.85, 0.5, 1.0 / 0.85, 3.0, 1e-9}) {
                    const ed::Ray ray = ed::view_ray(c0, w, h, x, y);
                    const sm::Vec3 p = ray.origin + depth * c0.distance * ray.direction;
                    const sm::CameraDef c1 = ed::zoom_towards(c0, p, factor, control);
                    const std::optional<ed::ViewPixel> px = ed::view_pixel(c1, w, h, p);
                    ASSERT_TRUE(px.has_value());
                    // The point stays on the pixel: double rounding of ~1e3 px coordinates (1e-12 px);
                    // a target moved by the wrong amount would shift it by pixels.
                    EXPECT_NEAR(px->x, x, 1e-7) << x << ", " << y << " ×" << factor;
                    EXPECT_NEAR(px->y, y, 1e-7) << x << ", " << y << " ×" << factor;
                    // The distance scales (1e-9 is clamped to the closest approach).
                    const double expected = std::max(c0.distance * factor, control.min_distance);
                    EXPECT_NEAR(c1.distance, expected, 1e-12 * expected);
                    EXPECT_EQ(c1.yaw_deg, c0.yaw_deg);
                    EXPECT_EQ(c1.pitch_deg, c0.pitch_deg);
                }
    // Zooming towards the target itself keeps the target.
    const sm::CameraDef c = camera(30.0, 20.0);
    const sm::CameraDef z = ed::zoom_towards(c, *c.target, 0.5);
    EXPECT_NEAR(sm::length(*z.target - *c.target), 0.0, 1e-15);
    EXPECT_DOUBLE_EQ(z.distance, 1.5);
}

TEST(EditorCamera, PanMovesThePointAtTheTargetsDepthWithTheCursor)
{
    const double w = 800, h = 720;
    for (const sm::CameraDef& c0 : {camera(30.0, 20.0), camera(-150.0, 60.0, 9.0)})
        for (const auto& [dx, dy] : {std::pair{100.0, 0.0}, std::pair{0.0, -40.0}, std::pair{-33.0, 77.0}}) {
            const auto before = ed::view_pixel(c0, w, h, *c0.target);
            const sm::CameraDef c1 = ed::pan_pixels(c0, dx, dy, h);
            const auto after = ed::view_pixel(c1, w, h, *c0.target);
            ASSERT_TRUE(before && after);
            EXPECT_NEAR(after->x - before->x, dx, 1e-9);
            EXPECT_NEAR(after->y - before->y, dy, 1e-9);
            EXPECT_EQ(c1.distance, c0.distance);
        }
}

TEST(EditorCamera, FramingPutsEveryBoxInsideTheViewAndTouchesItsEdgeWithoutMargin)
{
    for (unsigned seed = 1; seed <= 6; ++seed) {
        const std::vector<sm::Aabb> boxes = scattered_boxes(seed, 1 + static_cast<int>(seed));
        for (const double yaw : {0.0, 30.0, -135.0})
            for (const double pitch : {-60.0, 20.0, 89.0})
                for (const auto& [w, h] :
                     {std::pair{800.0, 720.0}, std::pair{1280.0, 400.0}, std::pair{300.0, 900.0}}) {
                    // Start far off and looking elsewhere: framing sets target and distance.
                    const sm::CameraDef start = camera(yaw, pitch, 100.0, {50, -3, 7});
                    const sm::CameraDef framed = ed::frame_boxes(start, boxes, w / h, 1.1);
                    const double m = max_ndc(framed, boxes, w, h);
                    EXPECT_LE(m, 1.0) << "seed " << seed << " yaw " << yaw << " pitch " << pitch << " " << w;
                    // With no margin the fit is tight: some corner lies on the view's edge (the
                    // fitted distance is a maximum over corners; 1e-9 is rounding).
                    const sm::CameraDef tight = ed::frame_boxes(start, boxes, w / h, 1.0);
                    EXPECT_NEAR(max_ndc(tight, boxes, w, h, false), 1.0, 1e-9) << "seed " << seed;
                    EXPECT_EQ(framed.yaw_deg, yaw);
                    EXPECT_EQ(framed.pitch_deg, pitch);
                }
    }
}

TEST(EditorCamera, FramingNothingShowsTheTwoMetreCubeAtTheOrigin)
{
    const sm::CameraDef c = ed::frame_boxes(camera(30, 20), {}, 1.5);
    EXPECT_EQ(*c.target, (sm::Vec3{0, 0, 0}));
    EXPECT_LE(max_ndc(c, {sm::Aabb{{-1, -1, -1}, {1, 1, 1}}}, 900, 600), 1.0);
}

#ifdef SM_HAS_RENDER
TEST(EditorCamera, TheSceneFramingAndThePixelRaysAreTheRenderers)
{
    sm::Result<sm::Scene> scene = sm::load_scene(std::string(SM_SOURCE_DIR) + "/samples/ball_on_board.json");
    ASSERT_TRUE(scene) << scene.error().message();
    sm::Result<sm::World> world = sm::build_world(*scene);
    ASSERT_TRUE(world) << world.error().message();
    for (const double aspect : {800.0 / 720.0, 16.0 / 9.0, 0.5}) {
        // The load framing equals frame_bodies(), the renderer's own (same corners, same margin).
        const sm::CameraDef ours = ed::frame_scene_camera(scene->camera, ed::body_boxes(*world), aspect);
        const sm::CameraDef theirs = sm::frame_bodies(*world, scene->camera, aspect);
        EXPECT_NEAR(sm::length(*ours.target - *theirs.target), 0.0, 1e-12);
        EXPECT_NEAR(ours.distance, theirs.distance, 1e-12);
    }
    // Rays and pixels: the renderer's camera_ray() (the same axes, 1e-12) and project_to_pixel()
    // (its float view-projection matrix: ~1e-7 relative, under 1e-3 px at 800 px).
    const sm::CameraDef c = ed::orbit(camera(30.0, 20.0), 47.0, -12.0);
    for (const auto& [x, y] : {std::pair{400.0, 360.0}, std::pair{10.0, 20.0}, std::pair{799.0, 700.0}}) {
        const ed::Ray ours = ed::view_ray(c, 800, 720, x, y);
        const sm::CameraRay theirs = sm::camera_ray(*world, c, 800, 720, x, y);
        EXPECT_NEAR(sm::length(ours.origin - theirs.origin), 0.0, 1e-12);
        EXPECT_NEAR(sm::length(ours.direction - theirs.direction), 0.0, 1e-12);
        const sm::Vec3 p = ours.origin + 2.0 * ours.direction;
        const auto px = sm::project_to_pixel(*world, c, 800, 720, p);
        ASSERT_TRUE(px.has_value());
        EXPECT_NEAR((*px)[0], x, 1e-3);
        EXPECT_NEAR((*px)[1], y, 1e-3);
    }
}
#endif
