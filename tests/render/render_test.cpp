// SPDX-License-Identifier: MIT
// The renderer: EGL start-up and its error, framing, the mesh cache, modal deformation, interpolation.
#include "supermodal/body.h"
#include "supermodal/geometry.h"
#include "supermodal/hierarchy.h"
#include "supermodal/modal.h"
#include "supermodal/render.h"
#include "supermodal/scene.h"
#include "supermodal/world.h"

#include <cmath>
#include <cstdlib>
#include <gtest/gtest.h>
#include <memory>
#include <numbers>

namespace sm = supermodal;

namespace
{

sm::RenderDef small_def()
{
    sm::RenderDef d = sm::default_render_def();
    d.width = 160;
    d.height = 120;
    return d;
}

sm::Renderer make_renderer(const sm::RenderDef& def = small_def())
{
    sm::Result<sm::Renderer> r = sm::Renderer::create(def);
    if (!r) {
        ADD_FAILURE() << "no offscreen renderer (install EGL + Mesa: scripts/deps.sh): "
                      << r.error().message();
        std::abort(); // every test here needs one; a clear message beats a cascade
    }
    return std::move(*r);
}

sm::World load(const std::string& scene_path)
{
    sm::Result<sm::Scene> scene = sm::load_scene(std::string(SM_SOURCE_DIR) + "/" + scene_path);
    EXPECT_TRUE(scene) << scene.error().message();
    sm::Result<sm::World> world = sm::build_world(*scene);
    EXPECT_TRUE(world) << world.error().message();
    return std::move(*world);
}

// Fraction of pixels whose channels differ by more than `tolerance`.
double differing(const sm::Image& a, const sm::Image& b, int tolerance = 0)
{
    sm::Result<sm::ImageDiff> d = sm::compare_images(a, b, tolerance);
    EXPECT_TRUE(d) << d.error().message();
    return d ? d->differing_fraction : 1.0;
}

TEST(RenderDef, ValidateRefusesBadSizes)
{
    sm::RenderDef d = sm::default_render_def();
    EXPECT_TRUE(sm::validate(d));
    d.width = 0;
    EXPECT_FALSE(sm::validate(d));
    d = sm::default_render_def();
    d.samples = 0;
    EXPECT_FALSE(sm::validate(d));
    for (double bad_gap : {-1.0, 0.001, 200.0, std::nan("")}) {
        d = sm::default_render_def();
        d.gap_pixels = bad_gap;
        EXPECT_FALSE(sm::validate(d)) << bad_gap;
    }
    d = sm::default_render_def();
    d.gap_pixels = 0.0; // off
    EXPECT_TRUE(sm::validate(d));
    d = sm::default_render_def();
    d.deformation_scale = std::nan("");
    EXPECT_FALSE(sm::validate(d));
    EXPECT_FALSE(sm::Renderer::create(d)); // refused before EGL is touched
}

// Without an EGL vendor library the renderer must report it, not crash. Runs in a fresh process so
// glvnd reads the empty vendor list before anything else opened EGL.
TEST(RendererDeathTest, NoEglGivesAClearError)
{
    GTEST_FLAG_SET(death_test_style, "threadsafe");
    EXPECT_EXIT(
        {
            setenv("__EGL_VENDOR_LIBRARY_FILENAMES", "/nonexistent/egl_vendor.json", 1);
            sm::Result<sm::Renderer> r = sm::Renderer::create(small_def());
            if (!r) {
                std::fprintf(stderr, "%s\n", r.error().message().c_str());
                std::exit(3);
            }
            std::exit(0);
        },
        ::testing::ExitedWithCode(3), "no EGL display");
}

TEST(Renderer, ReportsTheDeviceAndDrawsTheSky)
{
    sm::Renderer r = make_renderer();
    EXPECT_NE(r.device_name().find("OpenGL ES"), std::string::npos) << r.device_name();
    sm::World w;
    sm::Image img;
    sm::RenderDef def = small_def();
    def.grid = false;
    sm::Renderer bare = make_renderer(def);
    ASSERT_TRUE(bare.render(w, sm::CameraDef{}, img));
    ASSERT_EQ(img.rgba.size(), size_t{160 * 120 * 4});
    // Top-left pixel: the sky's top colour (within 8-bit rounding and the gradient's first row).
    EXPECT_NEAR(img.rgba[0], 255 * def.sky_top.x, 3.0);
    EXPECT_NEAR(img.rgba[2], 255 * def.sky_top.z, 3.0);
    const size_t bottom = (size_t{119} * 160) * 4;
    EXPECT_NEAR(img.rgba[bottom + 1], 255 * def.sky_bottom.y, 3.0);
}

// Every corner of every body's box lies inside the framed camera's view rectangle, and the framing is
// tight: some corner is within the 10% margin of an edge.
TEST(Framing, FitsEveryBody)
{
    sm::World w = load("samples/gallery.json");
    const double aspect = 16.0 / 9.0;
    const double tan_v = std::tan(20.0 * std::numbers::pi / 180), tan_h = tan_v * aspect;
    for (double yaw : {0.0, 45.0, 200.0})
        for (double pitch : {-30.0, 10.0, 80.0}) {
            const sm::CameraDef c = sm::frame_bodies(
                w, sm::CameraDef{.target = std::nullopt, .yaw_deg = yaw, .pitch_deg = pitch, .fov_deg = 40.0},
                aspect);
            ASSERT_TRUE(c.target.has_value());
            ASSERT_GT(c.distance, 0.0);
            const double y = yaw * std::numbers::pi / 180, p = pitch * std::numbers::pi / 180;
            const sm::Vec3 back{std::cos(p) * std::sin(y), std::sin(p), std::cos(p) * std::cos(y)};
            const sm::Vec3 right = sm::normalized(sm::cross(-back, sm::Vec3{0, 1, 0}));
            const sm::Vec3 up = sm::cross(right, -back);
            const sm::Vec3 eye = *c.target + c.distance * back;
            double fullest = 0.0; // largest fraction of the half-width or half-height used
            for (sm::Entity b : sm::world_bodies(w)) {
                if (sm::body_shape(w, b).type == sm::ShapeType::Plane)
                    continue;
                const sm::Aabb box =
                    sm::world_aabb(sm::body_shape(w, b), sm::body_position(w, b), sm::body_orientation(w, b));
                for (int k = 0; k < 8; ++k) {
                    const sm::Vec3 corner{(k & 1) ? box.max.x : box.min.x, (k & 2) ? box.max.y : box.min.y,
                                          (k & 4) ? box.max.z : box.min.z};
                    const sm::Vec3 r = corner - eye;
                    const double depth = sm::dot(r, -back);
                    ASSERT_GT(depth, 0.0);
                    const double used = std::max(std::abs(sm::dot(r, right)) / (depth * tan_h),
                                                 std::abs(sm::dot(r, up)) / (depth * tan_v));
                    EXPECT_LE(used, 1.0) << "yaw " << yaw << " pitch " << pitch;
                    fullest = std::max(fullest, used);
                }
            }
            // With the 10% margin on the distance the extreme corner still fills over 80% of the half
            // frame: the framing is tight, not a loose bounding sphere.
            EXPECT_GT(fullest, 0.8) << "yaw " << yaw << " pitch " << pitch;
        }
}

// Under MSAA the bodies are drawn on their own multisampled layer over a single-sample ground and sky.
// A ball sunk halfway into the ground must still show only its upper half, and the layer must land
// where the single-sample image draws the ball: the two images differ only along edges. The pixel
// 0.8 of the ball's apparent radius below its centre shows the ground; with no grid there (nothing to
// hide the lower half) it shows the ball.
TEST(Renderer, MultisampledBodiesStayBehindTheGround)
{
    sm::World w;
    sm::BodyDef ball = sm::default_body_def();
    ball.shape.radii = {0.3, 0.3, 0.3};
    ball.motion = sm::MotionType::Static;
    (void)sm::create_body(w, ball);
    const sm::CameraDef cam{.target = sm::Vec3{0, 0, 0}, .distance = 1.6, .yaw_deg = 0, .pitch_deg = 25};
    sm::RenderDef one = small_def(), none = small_def();
    one.samples = 1;
    none.grid = false;
    sm::Image layered, single, ungrounded;
    ASSERT_TRUE(make_renderer().render(w, cam, layered));
    ASSERT_TRUE(make_renderer(one).render(w, cam, single));
    ASSERT_TRUE(make_renderer(none).render(w, cam, ungrounded));
    EXPECT_LT(differing(layered, single, 16), 0.02);
    const double alpha = std::asin(0.3 / 1.6); // the ball's apparent radius [rad]
    const double half_fov = 0.5 * cam.fov_deg * std::numbers::pi / 180.0;
    const int row = 60 + static_cast<int>(std::lround(60.0 * std::tan(0.8 * alpha) / std::tan(half_fov)));
    const size_t at = (static_cast<size_t>(row) * 160 + 80) * 4;
    int to_single = 0, to_ungrounded = 0;
    for (size_t c = 0; c < 3; ++c) {
        to_single = std::max(to_single, std::abs(layered.rgba[at + c] - single.rgba[at + c]));
        to_ungrounded = std::max(to_ungrounded, std::abs(layered.rgba[at + c] - ungrounded.rgba[at + c]));
    }
    EXPECT_LE(to_single, 16) << "row " << row;
    EXPECT_GT(to_ungrounded, 32) << "row " << row << ": the lower half would show here";
}

// Level of detail and curvature spacing: at 1280x720 the chair drawn with the defaults (each rigid body
// at the fewest segments within a quarter pixel of its surface) is no further from a fine render (96
// segments everywhere) than the chair drawn with even 32-segment meshes, the renderer's meshes before.
TEST(Renderer, LevelOfDetailKeepsThePicture)
{
    sm::World w = load("samples/chair_with_dummy.json");
    for (int i = 0; i < 200; ++i)
        w.step();
    sm::RenderDef fine = sm::default_render_def();
    fine.gap_pixels = 0.0;
    fine.tessellation = 96;
    sm::Image reference, lod, even;
    ASSERT_TRUE(make_renderer(fine).render(w, sm::CameraDef{}, reference));
    ASSERT_TRUE(make_renderer(sm::default_render_def()).render(w, sm::CameraDef{}, lod));
    sm::Renderer r = make_renderer(sm::default_render_def());
    for (sm::Entity b : sm::world_bodies(w))
        if (sm::body_shape(w, b).type == sm::ShapeType::Superquadric)
            r.set_body_mesh(b, std::make_shared<sm::TriangleMesh>(sm::tessellate(sm::body_shape(w, b), 32)));
    ASSERT_TRUE(r.render(w, sm::CameraDef{}, even));
    const double lod_off = differing(lod, reference, 16), even_off = differing(even, reference, 16);
    std::printf("pixels off by more than 16/255 from the fine render: level of detail %.5f, even 32 %.5f\n",
                lod_off, even_off);
    EXPECT_LE(lod_off, even_off);
}

// Under MSAA the grid and the sky are drawn once per view and copied back while the camera stands
// still: every frame must still equal, bit for bit, the frame a fresh renderer draws, whether the
// bodies moved under a still camera or the camera moved away and back.
TEST(Renderer, AStillCameraReusesTheBackgroundExactly)
{
    sm::World w = load("samples/chair_with_dummy.json");
    const sm::CameraDef near{.target = sm::Vec3{0, 0.5, 0}, .distance = 2.5, .yaw_deg = 30, .pitch_deg = 15};
    const sm::CameraDef far{.target = sm::Vec3{0, 0.5, 0}, .distance = 4.0, .yaw_deg = -40, .pitch_deg = 25};
    sm::Renderer kept = make_renderer();
    sm::Image first, again, fresh;
    ASSERT_TRUE(kept.render(w, near, first));
    ASSERT_TRUE(kept.render(w, near, again));
    EXPECT_EQ(differing(first, again), 0.0);
    for (int i = 0; i < 100; ++i)
        w.step(); // the dummy falls onto the seat: bodies and shadows move, the background stays
    for (const sm::CameraDef& camera : {near, far, near}) {
        ASSERT_TRUE(kept.render(w, camera, again));
        ASSERT_TRUE(make_renderer().render(w, camera, fresh));
        EXPECT_EQ(differing(again, fresh), 0.0) << camera.distance;
    }
    EXPECT_GT(differing(first, again, 16), 0.001); // the bodies did move on screen
}

TEST(Renderer, TessellatesEachDistinctShapeOnce)
{
    sm::World w = load("samples/chair_with_dummy.json");
    sm::Renderer r = make_renderer();
    sm::Image img;
    ASSERT_TRUE(r.render(w, sm::CameraDef{}, img));
    const int first = r.cached_mesh_count();
    // The four legs share one shape, the arms and legs of the dummy share theirs: fewer meshes than bodies.
    EXPECT_LT(first, static_cast<int>(sm::world_bodies(w).size()) - 4);
    for (int i = 0; i < 5; ++i) {
        w.step();
        ASSERT_TRUE(r.render(w, sm::CameraDef{}, img));
    }
    EXPECT_EQ(r.cached_mesh_count(), first); // moving bodies reuse their meshes
    sm::ShapeDef seat = sm::body_shape(w, sm::find_body(w, "chair_seat"));
    seat.radii.x *= 1.2;
    ASSERT_TRUE(sm::set_body_shape(w, sm::find_body(w, "chair_seat"), seat));
    ASSERT_TRUE(r.render(w, sm::CameraDef{}, img));
    EXPECT_EQ(r.cached_mesh_count(), first + 1); // a changed shape is tessellated once more
}

// A modal board drawn with amplitudes differs from its rest shape; with deformation_scale 0 it does not.
TEST(Renderer, DrawsModalDeformation)
{
    sm::World w = load("samples/ball_on_board.json");
    const sm::Entity board = sm::find_body(w, "board");
    const sm::ModalBasis* basis = sm::body_modal_basis(w, board);
    ASSERT_NE(basis, nullptr);
    const sm::CameraDef cam{.target = sm::Vec3{0, 0.12, 0}, .distance = 1.4, .yaw_deg = 0, .pitch_deg = 10};
    sm::Renderer r = make_renderer();
    sm::Image rest, bent, unscaled;
    ASSERT_TRUE(r.render(w, cam, rest));
    // Mode 1 (a bending mode) with an amplitude that moves the ends by about 5 cm.
    std::vector<double> q(static_cast<size_t>(basis->mode_count), 0.0), v(q.size(), 0.0);
    const double end =
        sm::length(sm::modal_displacement(*basis, sm::Vec3{0.5, 0, 0}, std::vector<double>{1.0}));
    ASSERT_GT(end, 0.0);
    q[0] = 0.05 / end;
    ASSERT_TRUE(sm::set_body_modal_state(w, board, q, v));
    ASSERT_TRUE(r.render(w, cam, bent));
    EXPECT_GT(differing(rest, bent, 16), 0.005);
    sm::RenderDef def = small_def();
    def.deformation_scale = 0.0;
    sm::Renderer flat = make_renderer(def);
    ASSERT_TRUE(flat.render(w, cam, unscaled));
    EXPECT_EQ(differing(rest, unscaled), 0.0);
}

// A body given a render mesh draws that mesh: the tessellation itself handed back as a mesh gives the
// same image bit for bit; a different mesh (the board's tessellation at half the resolution, the
// ball's at twice its size) changes it; bent by the board's modes like the tessellation.
TEST(Renderer, DrawsAGivenRenderMeshAndBendsIt)
{
    sm::World w = load("samples/ball_on_board.json");
    const sm::Entity board = sm::find_body(w, "board");
    const sm::Entity ball = sm::find_body(w, "ball");
    const sm::CameraDef cam{.target = sm::Vec3{0, 0.12, 0}, .distance = 1.4, .yaw_deg = 0, .pitch_deg = 10};
    const sm::RenderDef def = small_def();
    sm::Renderer r = make_renderer();
    sm::Image plain, same, other, bent, bent_plain;
    ASSERT_TRUE(r.render(w, cam, plain));
    r.set_body_mesh(board, std::make_shared<sm::TriangleMesh>(
                               sm::tessellate(sm::body_shape(w, board), def.tessellation)));
    ASSERT_TRUE(r.render(w, cam, same));
    EXPECT_EQ(differing(plain, same), 0.0);
    sm::ShapeDef big = sm::body_shape(w, ball);
    big.radii = 2.0 * big.radii;
    r.set_body_mesh(ball, std::make_shared<sm::TriangleMesh>(sm::tessellate(big, def.tessellation)));
    ASSERT_TRUE(r.render(w, cam, other));
    EXPECT_GT(differing(plain, other, 16), 0.001);
    r.set_body_mesh(ball, nullptr); // back to the tessellation
    // Bent: the given mesh follows the modes as the tessellation does.
    const sm::ModalBasis* basis = sm::body_modal_basis(w, board);
    ASSERT_NE(basis, nullptr);
    std::vector<double> q(static_cast<size_t>(basis->mode_count), 0.0), v(q.size(), 0.0);
    q[0] = 0.05 / sm::length(sm::modal_displacement(*basis, sm::Vec3{0.5, 0, 0}, std::vector<double>{1.0}));
    ASSERT_TRUE(sm::set_body_modal_state(w, board, q, v));
    ASSERT_TRUE(r.render(w, cam, bent));
    sm::Renderer r2 = make_renderer();
    ASSERT_TRUE(r2.render(w, cam, bent_plain));
    EXPECT_EQ(differing(bent, bent_plain), 0.0);
    EXPECT_GT(differing(plain, bent, 16), 0.005);
}

// Interpolated frames at alpha = 0 show the previous step's poses; Current shows the last step's.
TEST(Renderer, InterpolatesBetweenSteps)
{
    sm::World w;
    sm::BodyDef ball = sm::default_body_def();
    ball.shape.radii = {0.2, 0.2, 0.2};
    ball.linear_velocity = {20.0, 0, 0}; // 4 cm per 2 ms step: many pixels at this framing
    ball.gravity_scale = 0.0;
    (void)sm::create_body(w, ball);
    const sm::CameraDef cam{.target = sm::Vec3{0, 0, 0}, .distance = 2.0, .yaw_deg = 0, .pitch_deg = 0};
    sm::Renderer r = make_renderer();
    sm::Image after1, after2, blended;
    w.step();
    ASSERT_TRUE(r.render(w, cam, after1));
    w.step();
    ASSERT_TRUE(r.render(w, cam, after2));
    ASSERT_EQ(w.interpolation_alpha(), 0.0);
    ASSERT_TRUE(r.render(w, cam, blended, sm::PoseSource::Interpolated));
    EXPECT_GT(differing(after1, after2, 16), 0.002);
    // nlerp of an unchanged unit quaternion may move its last bits: allow a one-level difference.
    EXPECT_EQ(differing(after1, blended, 1), 0.0);
}

TEST(Images, PngRoundTripAndDiff)
{
    sm::Image a{4, 2, std::vector<uint8_t>(32, 10)};
    sm::Image b = a;
    b.rgba[5] = 40; // pixel 1, green
    const std::string path = testing::TempDir() + "/roundtrip.png";
    ASSERT_TRUE(sm::write_png(path, b));
    sm::Result<sm::Image> back = sm::read_png(path);
    ASSERT_TRUE(back) << back.error().message();
    EXPECT_EQ(back->rgba, b.rgba);
    sm::Result<sm::ImageDiff> d = sm::compare_images(a, *back, 29);
    ASSERT_TRUE(d);
    EXPECT_EQ(d->differing_pixels, 1);
    EXPECT_EQ(d->max_difference, 30);
    EXPECT_EQ(d->diff.rgba[4], 255); // red marks the differing pixel
    EXPECT_EQ(sm::compare_images(a, *back, 30)->differing_pixels, 0);
    EXPECT_FALSE(sm::compare_images(a, sm::Image{2, 2, std::vector<uint8_t>(16)}, 0));
}

} // namespace
