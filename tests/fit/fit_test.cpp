// Tests for engine/src/fit: superquadrics recovered from meshes of known shapes, noisy points, and
// data that is no superquadric at all.
#include "fit/fit_cases.h"
#include "supermodal/fit.h"
#include "support/shapes.h"

#include <algorithm>
#include <cstdio>
#include <gtest/gtest.h>
#include <random>
#include <string>

namespace sm = supermodal;
using sm::test::PosedShape;

namespace
{

std::string sci(double x)
{
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.3g", x);
    return buf;
}

// The fit accuracy docs/pipeline.md states: radii to 1 % (relative), ε to 0.02 (absolute). The mesh vertices lie
// exactly on the surface, so the residual vanishes at the truth and the solver's stopping rule
// (relative cost decrease < 1e-12) leaves far less than this; the tolerance guards the basin, i.e. that
// the right minimum was found. Taper to 0.02 and bend curvature to 2 % are stated in the same spirit.
constexpr double k_radius_tol = 0.01;
constexpr double k_epsilon_tol = 0.02;
constexpr double k_taper_tol = 0.02;
constexpr double k_bend_tol = 0.02;

sm::ShapeDef shape(sm::Vec3 r, double e1, double e2, sm::Taper taper = {}, sm::Bend bend = {})
{
    sm::ShapeDef s = sm::test::superquadric(r, e1, e2);
    s.taper = taper;
    s.bend = bend;
    return s;
}

/// Compares a fit to the truth up to the shape's symmetries: each true axis is matched to the fitted
/// axis most parallel to it, so a1 ↔ a2 swaps and (for ε1 = ε2) any relabelling are allowed.
void expect_recovered(const PosedShape& truth, const sm::FitResult& fit, const char* label)
{
    SCOPED_TRACE(label);
    ::testing::Test::RecordProperty(std::string(label) + " rms_relative", sci(fit.rms_relative));
    ::testing::Test::RecordProperty(std::string(label) + " rms_m", sci(fit.rms_m));
    int match[3];
    double sign[3];
    for (int j = 0; j < 3; ++j) {
        const sm::Vec3 t =
            sm::rotate(truth.orientation, sm::Vec3{j == 0 ? 1.0 : 0, j == 1 ? 1.0 : 0, j == 2 ? 1.0 : 0});
        double best = -1.0;
        for (int i = 0; i < 3; ++i) {
            const sm::Vec3 f =
                sm::rotate(fit.orientation, sm::Vec3{i == 0 ? 1.0 : 0, i == 1 ? 1.0 : 0, i == 2 ? 1.0 : 0});
            if (std::abs(sm::dot(t, f)) > best) {
                best = std::abs(sm::dot(t, f));
                match[j] = i;
                sign[j] = sm::dot(t, f) < 0 ? -1.0 : 1.0;
            }
        }
        EXPECT_GT(best, 0.99) << "axis " << j << " not matched";
    }
    double radius_error = 0.0;
    for (int j = 0; j < 3; ++j) {
        EXPECT_NEAR(fit.shape.radii[match[j]] / truth.shape.radii[j], 1.0, k_radius_tol) << "radius " << j;
        radius_error =
            std::max(radius_error, std::abs(fit.shape.radii[match[j]] / truth.shape.radii[j] - 1.0));
    }
    const double epsilon_error = std::max(std::abs(fit.shape.epsilon1 - truth.shape.epsilon1),
                                          std::abs(fit.shape.epsilon2 - truth.shape.epsilon2));
    // Measured values for docs/pipeline.md (--gtest_output=json shows them).
    ::testing::Test::RecordProperty(std::string(label) + " radius_error", sci(radius_error));
    ::testing::Test::RecordProperty(std::string(label) + " epsilon_error", sci(epsilon_error));
    const bool same_polar = match[2] == 2;
    if (truth.shape.epsilon1 != truth.shape.epsilon2) {
        EXPECT_TRUE(same_polar) << "polar axis not recovered";
    }
    EXPECT_NEAR(fit.shape.epsilon1, truth.shape.epsilon1, k_epsilon_tol);
    EXPECT_NEAR(fit.shape.epsilon2, truth.shape.epsilon2, k_epsilon_tol);
    if (same_polar) {
        // Taper scales x and y with z: a flipped z flips its sign, a swapped x, y swaps the factors.
        const double k_true[2] = {truth.shape.taper.kx, truth.shape.taper.ky};
        const double k_fit[2] = {fit.shape.taper.kx, fit.shape.taper.ky};
        for (int j = 0; j < 2; ++j)
            EXPECT_NEAR(sign[2] * k_fit[match[j]], k_true[j], k_taper_tol) << "taper " << j;
    }
    const double k_true = truth.shape.bend.curvature;
    EXPECT_NEAR(fit.shape.bend.curvature, k_true, k_bend_tol * std::max(k_true, 1.0 / truth.shape.radii.z));
    if (k_true > 0.0) { // the direction the body curves towards, in the world
        auto dir = [](const sm::Quat& q, double a) { return sm::rotate(q, {std::cos(a), std::sin(a), 0.0}); };
        EXPECT_GT(sm::dot(dir(truth.orientation, truth.shape.bend.angle),
                          dir(fit.orientation, fit.shape.bend.angle)),
                  0.99);
    }
    // Vertex data fits to round-off. The flat 4:2:1 mesh (ε1 = 1.5, ε2 = 0.3) also has large triangles
    // on its nearly flat faces, which get interior samples on the facets, inside the curved surface:
    // its best fit (also when started at the truth) is 0.23 % rms, still inside the tolerances above.
    EXPECT_LT(fit.rms_relative, 5e-3);
    EXPECT_TRUE(fit.acceptable);
}

struct Case {
    const char* label;
    sm::ShapeDef shape;
    bool taper, bend;
};

const Case k_cases[] = {
    {"rounded box 2:3:5", shape({0.2, 0.3, 0.5}, 0.5, 0.5), false, false},
    {"cylinder-like 1:2:4", shape({0.1, 0.2, 0.4}, 0.3, 1.0), false, false},
    {"flat 4:2:1", shape({0.4, 0.2, 0.1}, 1.5, 0.3), false, false},
    {"pinched 2:1:4", shape({0.3, 0.15, 0.6}, 1.0, 1.5), false, false},
    {"small 5:2:6", shape({0.25, 0.1, 0.3}, 0.8, 0.4), false, false},
    {"tapered", shape({0.2, 0.15, 0.4}, 0.7, 0.9, {0.3, -0.2}), true, false},
    {"bent", shape({0.1, 0.12, 0.5}, 0.6, 1.0, {}, {1.0, 0.4}), false, true},
    {"tapered and bent", shape({0.12, 0.1, 0.45}, 0.5, 0.8, {0.25, 0.15}, {0.8, -1.0}), true, true},
};

} // namespace

TEST(Fit, RecoversKnownSuperquadricsFromMeshes)
{
    unsigned seed = 1;
    for (const Case& c : k_cases) {
        const PosedShape truth = sm::test::random_pose(c.shape, seed++);
        sm::FitDef def = sm::default_fit_def();
        def.taper = c.taper;
        def.bend = c.bend;
        const auto fit = sm::fit_superquadric(sm::test::posed_mesh(truth, 48), def);
        ASSERT_TRUE(fit) << fit.error().message();
        expect_recovered(truth, *fit, c.label);
    }
}

TEST(Fit, NoisyPointsDegradeGracefully)
{
    // Gaussian noise of σ = 1 % of the size on every coordinate. The offset of a noisy point along the
    // normal has standard deviation σ; the radial distance measures it along the ray from the centre,
    // longer by 1/cos(ray, normal) on an elongated body (measured 1.20 σ here), so 0.9–1.5 σ is asked.
    // The parameters should move by a few σ/size at most: radii to 3 %, ε to 0.1.
    const PosedShape truth = sm::test::random_pose(shape({0.2, 0.3, 0.5}, 0.6, 0.8), 42);
    const sm::TriangleMesh mesh = sm::test::posed_mesh(truth, 48);
    double size = 0.0;
    sm::Vec3 centroid{};
    for (const sm::Vec3& p : mesh.positions)
        centroid += p / double(mesh.positions.size());
    for (const sm::Vec3& p : mesh.positions)
        size += sm::dot(p - centroid, p - centroid) / double(mesh.positions.size());
    size = std::sqrt(size);
    const double sigma = 0.01 * size;
    std::mt19937_64 rng(7);
    std::normal_distribution<double> noise(0.0, sigma);
    std::vector<sm::Vec3> points;
    for (const sm::Vec3& p : mesh.positions)
        points.push_back(p + sm::Vec3{noise(rng), noise(rng), noise(rng)});
    const auto fit = sm::fit_superquadric(points);
    ASSERT_TRUE(fit) << fit.error().message();
    EXPECT_GT(fit->rms_m / sigma, 0.9);
    EXPECT_LT(fit->rms_m / sigma, 1.5);
    EXPECT_GT(fit->rms_relative, 0.009);
    EXPECT_LT(fit->rms_relative, 0.015);
    const sm::FitResult& f = *fit;
    double radii_fit[3] = {f.shape.radii.x, f.shape.radii.y, f.shape.radii.z};
    std::sort(radii_fit, radii_fit + 3);
    const double radii_true[3] = {0.2, 0.3, 0.5};
    for (int i = 0; i < 3; ++i)
        EXPECT_NEAR(radii_fit[i] / radii_true[i], 1.0, 0.03);
    EXPECT_NEAR(f.shape.epsilon1, 0.6, 0.1);
    EXPECT_NEAR(f.shape.epsilon2, 0.8, 0.1);
    double radius_error = 0.0;
    for (int i = 0; i < 3; ++i)
        radius_error = std::max(radius_error, std::abs(radii_fit[i] / radii_true[i] - 1.0));
    RecordProperty("noisy radius_error", sci(radius_error));
    RecordProperty("noisy epsilon_error",
                   sci(std::max(std::abs(f.shape.epsilon1 - 0.6), std::abs(f.shape.epsilon2 - 0.8))));
    RecordProperty("noisy rms_relative", sci(f.rms_relative));
    RecordProperty("noisy rms/sigma", sci(fit->rms_m / sigma));
}

namespace
{

sm::TriangleMesh box_mesh(sm::Vec3 half, sm::Vec3 centre)
{
    // ε = 0.1 is the fit's lower bound: within 1 % of a radius of a sharp box, so a fair "box".
    sm::test::PosedShape b{shape(half, 0.1, 0.1), centre, sm::Quat::identity()};
    return sm::test::posed_mesh(b, 48);
}

} // namespace

TEST(Fit, NonSuperquadricsReportALargeError)
{
    // Two separated boxes and an L of two touching boxes: no single superquadric comes near, so the
    // relative error must be far above both the exact fits (< 0.5 %) and 1 % noise (≈ 1 %): > 5 %.
    sm::TriangleMesh pair = box_mesh({0.2, 0.2, 0.2}, {-0.6, 0, 0});
    sm::test::append_mesh(pair, box_mesh({0.2, 0.2, 0.2}, {0.6, 0, 0}));
    sm::TriangleMesh ell = box_mesh({0.5, 0.1, 0.1}, {0.5, 0.1, 0.1});
    sm::test::append_mesh(ell, box_mesh({0.1, 0.4, 0.1}, {0.1, 0.6, 0.1}));
    for (const auto* mesh : {&pair, &ell}) {
        const auto fit = sm::fit_superquadric(*mesh);
        ASSERT_TRUE(fit) << fit.error().message();
        EXPECT_GT(fit->rms_relative, 0.05);
        EXPECT_FALSE(fit->acceptable);
        RecordProperty(mesh == &pair ? "pair rms_relative" : "L rms_relative", sci(fit->rms_relative));
    }
}

TEST(Fit, PartsSplitTwoSeparatedBoxes)
{
    // Split along the longest axis into two: each half is one box again, fitted like exact data.
    sm::TriangleMesh pair = box_mesh({0.2, 0.15, 0.1}, {-0.6, 0, 0});
    sm::test::append_mesh(pair, box_mesh({0.2, 0.15, 0.1}, {0.6, 0, 0}));
    const auto parts = sm::fit_superquadric_parts(pair, 2);
    ASSERT_TRUE(parts) << parts.error().message();
    ASSERT_EQ(parts->size(), 2u);
    for (const sm::FitResult& f : *parts) {
        EXPECT_LT(f.rms_relative, 0.005);
        EXPECT_NEAR(std::abs(f.position.x), 0.6, 0.006);
        double r[3] = {f.shape.radii.x, f.shape.radii.y, f.shape.radii.z};
        std::sort(r, r + 3);
        EXPECT_NEAR(r[0], 0.1, 0.001);
        EXPECT_NEAR(r[1], 0.15, 0.0015);
        EXPECT_NEAR(r[2], 0.2, 0.002);
    }
}

TEST(Fit, RefusesBadInput)
{
    std::vector<sm::Vec3> few(10, sm::Vec3{1, 2, 3});
    EXPECT_FALSE(sm::fit_superquadric(few));
    std::vector<sm::Vec3> same(100, sm::Vec3{1, 2, 3});
    const auto r = sm::fit_superquadric(same);
    ASSERT_FALSE(r);
    EXPECT_NE(r.error().what.find("span"), std::string::npos);
    std::vector<sm::Vec3> nan_point = sm::tessellate(shape({1, 1, 1}, 1, 1), 16).positions;
    nan_point[3].y = std::nan("");
    EXPECT_FALSE(sm::fit_superquadric(nan_point));
    sm::TriangleMesh empty;
    EXPECT_FALSE(sm::fit_superquadric(empty));
    EXPECT_FALSE(sm::fit_superquadric_parts(empty, 0));
}
