// Contact sample density from the error budget (engine/src/contact/sample_density.cpp): the measured
// sampling gap, the spacing an auto body is given, and what that gap means for a body at rest.
#include "contact/collider.h"
#include "contact/sample_density.h"
#include "supermodal/body.h"
#include "supermodal/modal.h"
#include "supermodal/scene.h"
#include "supermodal/world.h"
#include "support/shapes.h"

#include <gtest/gtest.h>
#include <string>

namespace sm = supermodal;

namespace
{

constexpr double k_radius = 0.025; // [m], the ball of ball_on_board

double gap_at(const sm::ShapeDef& shape, double spacing)
{
    const auto reference = sm::sample_surface(shape, spacing / 16.0, 200000);
    return sm::sampling_gap(sm::sample_surface(shape, spacing, 100000), reference);
}

// A steel ball dropped 1 mm onto a floor, left to settle 1 s; returns its height [m] and what auto chose.
struct Rest {
    double height = 0.0;
    sm::BodyModalActivity activity{};
};
Rest ball_at_rest(const std::string& budget)
{
    const sm::Result<sm::Scene> scene =
        sm::parse_scene(R"({"settings": {"dt": 0.001, "accuracy": {"displacement": )" + budget + R"(}},
      "materials": {"steel": {"density": 7850, "young": 200e9, "poisson": 0.29, "restitution": 0.1}},
      "bodies": [{"name": "floor", "shape": {"type": "plane"}},
                 {"name": "ball", "material": "steel", "position": [0, 0.026, 0], "dynamics": {"type": "auto"},
                  "orientation": [0.9, 0.3, 0.2, 0.25],
                  "shape": {"type": "superquadric", "radii": [0.025, 0.025, 0.025]}}]})");
    EXPECT_TRUE(scene) << scene.error().message();
    sm::Result<sm::World> world = sm::build_world(*scene);
    EXPECT_TRUE(world) << world.error().message();
    const sm::Entity ball = sm::find_body(*world, "ball");
    for (int s = 0; s < 1000; ++s)
        world->step();
    return {sm::body_position(*world, ball).y, sm::body_modal_activity(*world, ball)};
}

} // namespace

TEST(SampleDensity, SphereGapIsPositiveQuadraticInSpacingAndUnderTheChordBound)
{
    // A sample lattice of spacing h leaves holes of circumradius about h/√3…h, so a plane pressed on a
    // sphere of radius R can reach between samples by at most the sagitta of a chord 2h: h²/(2R).
    // Halving h should quarter the gap (between 2.5× and 6× allowed: the holes are not all alike).
    const sm::ShapeDef ball = sm::test::superquadric({k_radius, k_radius, k_radius}, 1.0, 1.0);
    const double h = k_radius / 4.0;
    const double coarse = gap_at(ball, h), fine = gap_at(ball, h / 2.0);
    EXPECT_GT(coarse, 0.0);
    EXPECT_LT(coarse, h * h / (2.0 * k_radius));
    EXPECT_GT(coarse / fine, 2.5);
    EXPECT_LT(coarse / fine, 6.0);
}

TEST(SampleDensity, ChoosesTheCoarsestSpacingThatMeetsTheTolerance)
{
    const sm::ShapeDef ell = sm::test::superquadric({0.06, 0.04, 0.03}, 1.0, 1.0);
    const sm::SampleDensityChoice loose = sm::choose_sample_spacing(ell, 1.0, 4000);
    EXPECT_TRUE(loose.met);
    EXPECT_DOUBLE_EQ(loose.spacing, 4.0 * sm::default_sample_spacing(ell)); // the coarsest candidate
    // Between the default spacing's gap and half of it: the default is too coarse, half is enough.
    const sm::SampleDensityChoice at_default = sm::choose_sample_spacing(ell, 1e-9, 100000);
    const double g1 = gap_at(ell, sm::default_sample_spacing(ell));
    const double g_half = gap_at(ell, 0.5 * sm::default_sample_spacing(ell));
    ASSERT_LT(g_half, g1);
    const sm::SampleDensityChoice mid = sm::choose_sample_spacing(ell, 0.5 * (g1 + g_half), 100000);
    EXPECT_TRUE(mid.met);
    EXPECT_DOUBLE_EQ(mid.spacing, 0.5 * sm::default_sample_spacing(ell));
    EXPECT_LE(mid.gap, 0.5 * (g1 + g_half));
    // Out of reach: the finest candidate, reported as not met.
    EXPECT_FALSE(at_default.met);
    EXPECT_DOUBLE_EQ(at_default.spacing, 0.25 * sm::default_sample_spacing(ell));
}

TEST(SampleDensity, AnAutoBallRestsWhereTheFinelySampledBallDoesWithinItsGap)
{
    // The point of the gap: a coarsely sampled body sinks between its samples by at most the gap. A
    // 4 mm budget gives the ball a quarter, 1 mm, and it takes the coarsest spacing; a 4 µm budget
    // samples it as finely as it can. Their resting heights differ by no more than the coarse gap, plus
    // 5% of it for how the touching samples share the penalty's own rest sink (measured on this pose:
    // 0.3204 mm apart, gap 0.3218 mm: the pole falls in one of the widest holes).
    const Rest coarse = ball_at_rest("4e-3"), fine = ball_at_rest("4e-6");
    EXPECT_TRUE(coarse.activity.sampling_gap_met);
    EXPECT_LE(coarse.activity.sampling_gap, 1e-3);
    EXPECT_GT(fine.activity.contact_samples, 4 * coarse.activity.contact_samples);
    EXPECT_LT(fine.activity.sampling_gap, coarse.activity.sampling_gap);
    EXPECT_LE(std::abs(coarse.height - fine.height), 1.05 * coarse.activity.sampling_gap)
        << "coarse " << coarse.height << " fine " << fine.height;
    EXPECT_EQ(coarse.activity.most_active_modes, 0); // a resting steel ball stays rigid
}

TEST(SampleDensity, AWorldSpacingOverridesTheBudget)
{
    const sm::Result<sm::Scene> scene = sm::parse_scene(
        R"({"settings": {"dt": 0.001, "accuracy": {"displacement": 4e-3}, "contact": {"sample_spacing": 0.004}},
      "bodies": [{"name": "ball", "position": [0, 1, 0], "dynamics": {"type": "auto"},
                  "shape": {"type": "superquadric", "radii": [0.025, 0.025, 0.025]}}]})");
    ASSERT_TRUE(scene) << scene.error().message();
    sm::Result<sm::World> world = sm::build_world(*scene);
    ASSERT_TRUE(world) << world.error().message();
    const sm::BodyModalActivity a = sm::body_modal_activity(*world, sm::find_body(*world, "ball"));
    EXPECT_TRUE(a.adaptive);
    EXPECT_EQ(a.contact_samples, 0); // not chosen: the scene's spacing holds
}
