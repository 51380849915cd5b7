// Tests for engine/src/geometry/hyperquadric.cpp.
#include "geometry/hyperquadric_internal.h"
#include "geometry/hyperquadric_solve.h"
#include "geometry/mass_deformed.h"
#include "supermodal/geometry.h"
#include "supermodal/shape.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <gtest/gtest.h>
#include <numbers>
#include <random>
#include <utility>

namespace sm = supermodal;

namespace
{

// H, its log and the ray roots are a few dozen floating-point operations: a few hundred ulps at most.
constexpr double k_round_off = 1e-12;
// Quadrature of smooth hyperquadrics (γ ≤ 6) at the default order measures ≤ 1e-11 against the
// Dirichlet formulas (docs/geometry.md); 1e-8 leaves room for other compilers and libm.
constexpr double k_smooth_quadrature = 1e-8;
// Central differences, h = 1e-6 of the slab width: truncation ~1e-12·H''', round-off ~1e-10.
constexpr double k_fd_tolerance = 1e-6;

sm::ShapeDef hyperquadric(std::vector<sm::HyperquadricTerm> terms)
{
    sm::ShapeDef s = sm::default_shape_def();
    s.type = sm::ShapeType::Hyperquadric;
    s.terms = std::move(terms);
    return s;
}

/// Three skew terms: the linear image of {Σ|u_i|^γ_i ≤ 1}, with det N = 3.
sm::ShapeDef skew(double g1, double g2, double g3)
{
    return hyperquadric({{{2, 0, 0}, 0.1, g1}, {{0.5, 1.5, 0}, -0.2, g2}, {{0.3, 0.2, 1.0}, 0.0, g3}});
}

/// Williams & Pentland's construction: the 4-D hypercube Σ|X_j|^γ ≤ 1 cut by the hyperplane through
/// h·n with n = (1, 1, 1, 1)/2; x are coordinates in an orthonormal basis (a, b, c) of that hyperplane,
/// so X_j = (a_j, b_j, c_j)·x + h·n_j: four terms.
sm::ShapeDef hypercube_slice(double gamma, double h)
{
    const double r2 = std::sqrt(2.0), r6 = std::sqrt(6.0), r12 = std::sqrt(12.0);
    const sm::Vec3 rows[4] = {
        {1 / r2, 1 / r6, 1 / r12}, {-1 / r2, 1 / r6, 1 / r12}, {0, -2 / r6, 1 / r12}, {0, 0, -3 / r12}};
    std::vector<sm::HyperquadricTerm> terms;
    for (const sm::Vec3& row : rows)
        terms.push_back({row, 0.5 * h, gamma});
    return hyperquadric(terms);
}

/// ∫ Π|u_i|^(p_i − 1) over {Σ|u_i|^γ_i ≤ 1} (Dirichlet): 8·Π(Γ(p_i/γ_i)/γ_i) / Γ(1 + Σ p_i/γ_i).
double dirichlet(const double (&p)[3], const double (&g)[3])
{
    double num = 8.0, sum = 0.0;
    for (int i = 0; i < 3; ++i) {
        num *= std::tgamma(p[i] / g[i]) / g[i];
        sum += p[i] / g[i];
    }
    return num / std::tgamma(1.0 + sum);
}

} // namespace

TEST(Hyperquadric, ValueAndMeasureAtKnownPoints)
{
    const sm::ShapeDef cube = hyperquadric({{{2, 0, 0}, 0, 8}, {{0, 2, 0}, 0, 8}, {{0, 0, 2}, 0, 8}});
    EXPECT_EQ(sm::hyperquadric_value(cube, {0, 0, 0}), 0.0);
    EXPECT_EQ(sm::hyperquadric_measure(cube, {0, 0, 0}), -1.0);
    EXPECT_NEAR(sm::hyperquadric_value(cube, {0.5, 0, 0}), 1.0, k_round_off);
    EXPECT_NEAR(sm::hyperquadric_measure(cube, {0, -0.5, 0}), 0.0, k_round_off);
    // Along an axis H^(1/γ) − 1 is exactly the distance in slab half-widths.
    EXPECT_NEAR(sm::hyperquadric_measure(cube, {0, 0, 1.5}), 2.0, k_round_off);
    EXPECT_NEAR(sm::hyperquadric_value(cube, {0.25, 0.25, 0.25}), 3.0 / 256.0, k_round_off);
    // Saturates instead of overflowing; the log stays exact.
    const sm::ShapeDef steep = hyperquadric({{{1, 0, 0}, 0, 400}, {{0, 1, 0}, 0, 400}, {{0, 0, 1}, 0, 400}});
    EXPECT_EQ(sm::hyperquadric_value(steep, {1e6, 0, 0}), 1e300);
    EXPECT_NEAR(sm::hyperquadric_log_value(steep, {1e6, 0, 0}), 400 * std::log(1e6), k_round_off * 1e4);
    EXPECT_NEAR(sm::hyperquadric_measure(steep, {1e6, 0, 0}), 1e6 - 1, 1e6 * k_round_off);
}

TEST(Hyperquadric, NormalIsTheGradientDirection)
{
    const sm::ShapeDef s = skew(2.5, 4, 6);
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> unit(-0.6, 0.6);
    for (int i = 0; i < 200; ++i) {
        const sm::Vec3 p{unit(rng), unit(rng), unit(rng)};
        sm::Vec3 grad;
        for (int c = 0; c < 3; ++c) {
            sm::Vec3 h{};
            h[c] = 1e-6;
            grad[c] = (sm::hyperquadric_value(s, p + h) - sm::hyperquadric_value(s, p - h)) / 2e-6;
        }
        EXPECT_LT(sm::length(sm::hyperquadric_normal(s, p) - sm::normalized(grad)), k_fd_tolerance);
    }
    // Where every term vanishes the gradient is zero: the documented fallback.
    const sm::ShapeDef cube = hyperquadric({{{1, 0, 0}, 0, 4}, {{0, 1, 0}, 0, 4}, {{0, 0, 1}, 0, 4}});
    EXPECT_EQ(sm::hyperquadric_normal(cube, {0, 0, 0}), (sm::Vec3{0, 0, 1}));
}

TEST(Hyperquadric, ThreeTermMassMatchesDirichletFormulas)
{
    // x = N⁻¹(u − d) maps {Σ|u_i|^γ_i ≤ 1} onto the body: V = ∫du / |det N|, the centre is where every
    // term vanishes, and the second moment about it is N⁻¹·diag(∫u_i²)·N⁻ᵀ / |det N|.
    // γ ≥ 2 only: below 2, |t|^γ has an unbounded second derivative where a term vanishes and the
    // quadrature slows to about h^2.5 (γ = 1.5: 5e-8 at the default order; docs/geometry.md).
    for (const auto& g : {std::array<double, 3>{2, 2, 2}, {3, 3, 3}, {4, 4, 2.5}}) {
        const sm::ShapeDef s = skew(g[0], g[1], g[2]);
        const double gamma[3] = {g[0], g[1], g[2]};
        const double det_n = 3.0;
        const sm::QuadratureMass q = sm::quadrature_mass(s, 1.0, sm::k_default_mass_order);
        const double volume = dirichlet({1, 1, 1}, gamma) / det_n;
        EXPECT_NEAR(q.properties.volume / volume, 1.0, k_smooth_quadrature);
        EXPECT_EQ(q.properties.mass, q.properties.volume);
        // Centre: 2x = −0.1, 0.5x + 1.5y = 0.2, 0.3x + 0.2y + z = 0.
        const double x0 = -0.05, y0 = (0.2 - 0.5 * x0) / 1.5, z0 = -0.3 * x0 - 0.2 * y0;
        EXPECT_LT(sm::length(q.properties.center_of_mass - sm::Vec3{x0, y0, z0}), k_smooth_quadrature);
        // N⁻¹ by rows of the adjugate: columns c_i with N c_i = e_i.
        const sm::Vec3 c0{0.5, -0.5 / 3, -0.15 + 0.1 / 3}, c1{0, 1 / 1.5, -0.2 / 1.5}, c2{0, 0, 1};
        const sm::Vec3 inv_cols[3] = {c0, c1, c2};
        double second[3][3] = {};
        for (int i = 0; i < 3; ++i) {
            double p[3] = {1, 1, 1};
            p[i] = 3;
            const double ui2 = dirichlet(p, gamma) / det_n;
            for (int r = 0; r < 3; ++r)
                for (int c = 0; c < 3; ++c)
                    second[r][c] += inv_cols[i][r] * inv_cols[i][c] * ui2;
        }
        const double trace = second[0][0] + second[1][1] + second[2][2];
        for (int r = 0; r < 3; ++r)
            for (int c = 0; c < 3; ++c)
                EXPECT_NEAR(q.inertia_tensor.m[r][c], (r == c ? trace : 0.0) - second[r][c],
                            k_smooth_quadrature * trace);
    }
}

TEST(Hyperquadric, HypercubeSliceWithSquaresIsABall)
{
    // With γ = 2 the four terms sum to |x|² + h², since the basis is orthonormal and ⟂ n: a ball.
    for (double h : {0.0, 0.6}) {
        const double radius = std::sqrt(1 - h * h);
        const sm::MassProperties mp = sm::compute_mass_properties(hypercube_slice(2, h), 1.0);
        EXPECT_NEAR(mp.volume, 4.0 / 3.0 * std::numbers::pi * radius * radius * radius, k_smooth_quadrature);
        EXPECT_LT(sm::length(mp.center_of_mass), k_smooth_quadrature);
    }
}

TEST(Hyperquadric, SteepTermsApproachTheCutPolytope)
{
    // With m terms through the origin, s·P ⊂ {Σ|t_i|^γ ≤ 1} ⊂ P for the polytope P = {max|t_i| ≤ 1} and
    // s = m^(−1/γ) (Σ ≤ m·max^γ): rigorous bounds s³·V_P ≤ V ≤ V_P. The hypercube slice through the
    // centre is a regular octahedron with vertices at distance 2 (the points (1, 1, −1, −1)):
    // V_P = 4/3·2³. A cube cut by the slab |x + y + z| ≤ 1: V_P = 8 − 2·(4/3).
    const sm::ShapeDef cut_cube =
        hyperquadric({{{1, 0, 0}, 0, 64}, {{0, 1, 0}, 0, 64}, {{0, 0, 1}, 0, 64}, {{1, 1, 1}, 0, 64}});
    const double shrink = std::pow(4.0, -3.0 / 64);
    for (const auto& [s, polytope] :
         {std::pair{hypercube_slice(64, 0), 32.0 / 3}, std::pair{cut_cube, 16.0 / 3}}) {
        const double v = sm::compute_mass_properties(s, 1.0).volume;
        EXPECT_GT(v, shrink * polytope);
        EXPECT_LT(v, polytope);
    }
}

TEST(Hyperquadric, UnboundedOrEmptyBodiesAreRecognised)
{
    const sm::ShapeDef flat = hyperquadric({{{1, 0, 0}, 0, 2}, {{0, 1, 0}, 0, 2}, {{1, 1, 0}, 0, 2}});
    EXPECT_FALSE(sm::hyperquadric_center(flat).is_bounded);
    const sm::ShapeDef apart =
        hyperquadric({{{1, 0, 0}, 0, 2}, {{0, 1, 0}, 0, 2}, {{0, 0, 1}, 0, 2}, {{1, 0, 0}, -3, 2}});
    const sm::HyperquadricCenter c = sm::hyperquadric_center(apart);
    EXPECT_TRUE(c.is_bounded);
    EXPECT_FALSE(c.is_non_empty);
    for (const sm::ShapeDef& s : {flat, apart}) {
        EXPECT_TRUE(sm::tessellate_hyperquadric(s, 16).indices.empty());
        EXPECT_TRUE(sm::sample_hyperquadric_surface(s, 0.1, 1000).empty());
        EXPECT_EQ(sm::compute_mass_properties(s, 1.0).mass, 0.0);
    }
}

TEST(Hyperquadric, RandomInputsGiveFiniteResults)
{
    std::mt19937_64 rng(11);
    std::uniform_real_distribution<double> unit(-1.0, 1.0);
    constexpr int k_shapes = 200, k_points = 200;
    for (int i = 0; i < k_shapes; ++i) {
        std::vector<sm::HyperquadricTerm> terms;
        for (int t = 0; t < 3 + i % 4; ++t)
            terms.push_back({{3 * unit(rng), 3 * unit(rng), 3 * unit(rng)},
                             unit(rng),
                             std::pow(10.0, 1.5 * unit(rng) + 0.5)});
        const sm::ShapeDef s = hyperquadric(terms);
        for (int k = 0; k < k_points; ++k) {
            const double scale = std::pow(10.0, 6.5 + 6.5 * unit(rng));
            const sm::Vec3 p{scale * unit(rng), scale * unit(rng), scale * unit(rng)};
            ASSERT_TRUE(std::isfinite(sm::hyperquadric_value(s, p)));
            ASSERT_TRUE(std::isfinite(sm::hyperquadric_measure(s, p)));
            ASSERT_TRUE(sm::is_finite(sm::hyperquadric_normal(s, p)));
            ASSERT_TRUE(std::isfinite(sm::shape_measure(s, p)));
        }
        const sm::HyperquadricCenter c = sm::hyperquadric_center(s);
        ASSERT_TRUE(sm::is_finite(c.point));
        if (c.is_bounded && c.is_non_empty && i % 10 == 0) {
            const sm::TriangleMesh mesh = sm::tessellate_hyperquadric(s, 8);
            for (const sm::Vec3& v : mesh.positions)
                ASSERT_TRUE(sm::is_finite(v));
        }
    }
}
