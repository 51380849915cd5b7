// Tests for engine/src/geometry/mass_properties.cpp.
#include "supermodal/shape.h"
#include "support/shapes.h"

#include <cmath>
#include <gtest/gtest.h>
#include <numbers>

namespace sm = supermodal;

namespace
{

using supermodal::test::superquadric;

// lgamma-based Beta values carry ~1e-15 relative error each; a few products stay below 1e-12.
constexpr double k_closed_form_rel = 1e-12;

// Midpoint-rule quadrature of the solid {F < 1} on an n³ grid over the bounding box: returns volume and
// second moments ∫x², ∫y², ∫z². Error falls like 1/n for the boundary cells.
struct Moments {
    double volume = 0, sxx = 0, syy = 0, szz = 0;
};
Moments quadrature(const sm::ShapeDef& s, int n)
{
    Moments m;
    const sm::Vec3 a = s.radii;
    const double dv = 8.0 * a.x * a.y * a.z / (double(n) * n * n);
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j)
            for (int k = 0; k < n; ++k) {
                const double x = a.x * (-1.0 + (2.0 * i + 1.0) / n);
                const double y = a.y * (-1.0 + (2.0 * j + 1.0) / n);
                const double z = a.z * (-1.0 + (2.0 * k + 1.0) / n);
                const double xy = std::pow(std::pow(std::abs(x / a.x), 2.0 / s.epsilon2) +
                                               std::pow(std::abs(y / a.y), 2.0 / s.epsilon2),
                                           s.epsilon2 / s.epsilon1);
                if (xy + std::pow(std::abs(z / a.z), 2.0 / s.epsilon1) >= 1.0)
                    continue;
                m.volume += dv;
                m.sxx += x * x * dv;
                m.syy += y * y * dv;
                m.szz += z * z * dv;
            }
    return m;
}

} // namespace

TEST(MassProperties, EllipsoidMatchesClosedForm)
{
    const sm::ShapeDef s = superquadric({1, 2, 3}, 1, 1);
    const sm::MassProperties mp = sm::compute_mass_properties(s, 2.0);
    const double v = 4.0 / 3.0 * std::numbers::pi * 6.0;
    EXPECT_NEAR(mp.volume, v, k_closed_form_rel * v);
    EXPECT_NEAR(mp.mass, 2.0 * v, k_closed_form_rel * 2 * v);
    // Solid ellipsoid: I_xx = m (b² + c²) / 5, ...
    const double m = mp.mass;
    EXPECT_NEAR(mp.inertia_diagonal.x, m * (4 + 9) / 5.0, k_closed_form_rel * m * 3);
    EXPECT_NEAR(mp.inertia_diagonal.y, m * (1 + 9) / 5.0, k_closed_form_rel * m * 3);
    EXPECT_NEAR(mp.inertia_diagonal.z, m * (1 + 4) / 5.0, k_closed_form_rel * m * 3);
}

TEST(MassProperties, SmallExponentsApproachTheBox)
{
    // At ε = 0.01 the superquadric fills its box to within ~1.5% (corner rounding shrinks like ε).
    constexpr double k_box_rel = 0.02;
    const sm::ShapeDef s = superquadric({0.5, 1.0, 1.5}, 0.01, 0.01);
    const sm::MassProperties mp = sm::compute_mass_properties(s, 1.0);
    const double v = 1.0 * 2.0 * 3.0;
    EXPECT_NEAR(mp.volume, v, k_box_rel * v);
    EXPECT_NEAR(mp.inertia_diagonal.x, v * (4 + 9) / 12.0, k_box_rel * v * 13 / 12.0);
    EXPECT_NEAR(mp.inertia_diagonal.z, v * (1 + 4) / 12.0, k_box_rel * v * 5 / 12.0);
    EXPECT_TRUE(std::isfinite(mp.volume) && std::isfinite(mp.inertia_diagonal.y));
}

TEST(MassProperties, OctahedronVolumeIsExact)
{
    // ε1 = ε2 = 2 is the octahedron |x|/a + |y|/b + |z|/c ≤ 1 with volume 4abc/3.
    const sm::MassProperties mp = sm::compute_mass_properties(superquadric({1, 2, 3}, 2, 2), 1.0);
    EXPECT_NEAR(mp.volume, 4.0 * 6.0 / 3.0, k_closed_form_rel * 8);
}

struct QuadratureCase {
    double e1, e2;
    double rel; ///< Allowed relative gap between closed form and the 120³ grid.
};
class MassPropertiesQuadrature : public ::testing::TestWithParam<QuadratureCase>
{
};

TEST_P(MassPropertiesQuadrature, ClosedFormAgreesWithGridIntegration)
{
    // A 120³ midpoint grid misclassifies a boundary layer of cells, an error ~1/n: below 1.5% for convex
    // shapes. Concave ones (ε > 2) have thin cusps along the axes that a grid resolves poorly: at ε = 4 the
    // grid misses 2.6% of the volume and 7.8% of the inertia (the cusps sit far out); the closed form is
    // checked exactly against the Dirichlet integral below.
    constexpr int k_n = 120;
    const auto [e1, e2, k_grid_rel] = GetParam();
    const sm::ShapeDef s = superquadric({0.3, 0.6, 1.2}, e1, e2);
    const sm::MassProperties mp = sm::compute_mass_properties(s, 1.0);
    const Moments q = quadrature(s, k_n);
    EXPECT_NEAR(mp.volume, q.volume, k_grid_rel * q.volume);
    EXPECT_NEAR(mp.inertia_diagonal.x, q.syy + q.szz, k_grid_rel * (q.syy + q.szz));
    EXPECT_NEAR(mp.inertia_diagonal.y, q.sxx + q.szz, k_grid_rel * (q.sxx + q.szz));
    EXPECT_NEAR(mp.inertia_diagonal.z, q.sxx + q.syy, k_grid_rel * (q.sxx + q.syy));
}

INSTANTIATE_TEST_SUITE_P(Exponents, MassPropertiesQuadrature,
                         ::testing::Values(QuadratureCase{0.1, 0.1, 0.015}, QuadratureCase{0.5, 1.0, 0.015},
                                           QuadratureCase{1.0, 0.3, 0.015}, QuadratureCase{1.5, 1.5, 0.015},
                                           QuadratureCase{2.0, 0.7, 0.015}, QuadratureCase{3.0, 3.0, 0.05},
                                           QuadratureCase{4.0, 4.0, 0.09}));

TEST(MassProperties, ConcaveStarVolumeMatchesDirichletIntegral)
{
    // ε1 = ε2 = 4 is |x/a|^½ + |y/b|^½ + |z/c|^½ ≤ 1; Dirichlet: V = 8·Γ(3)³/Γ(7)·abc = abc/90·8.
    const sm::MassProperties mp = sm::compute_mass_properties(superquadric({0.3, 0.6, 1.2}, 4, 4), 1.0);
    const double v = 8.0 * 8.0 / 720.0 * 0.3 * 0.6 * 1.2;
    EXPECT_NEAR(mp.volume, v, k_closed_form_rel * v);
    // ∫x² = 8·Γ(6)Γ(2)²/(p³Γ(11))·a³bc with p = ½ (Dirichlet), and I_zz = ∫x² + ∫y².
    const double sxx_unit = 8.0 * 120.0 / (0.125 * 3628800.0);
    const double izz = sxx_unit * 0.3 * 0.6 * 1.2 * (0.3 * 0.3 + 0.6 * 0.6);
    EXPECT_NEAR(mp.inertia_diagonal.z, izz, k_closed_form_rel * izz);
}

TEST(ShapeValidate, RejectsOutOfRangeParameters)
{
    EXPECT_TRUE(sm::validate(sm::default_shape_def()).ok());
    EXPECT_FALSE(sm::validate(superquadric({1, -1, 1}, 1, 1)).ok());
    EXPECT_FALSE(sm::validate(superquadric({1, 1, 1}, 0, 1)).ok());
    EXPECT_FALSE(sm::validate(superquadric({1, 1, 1}, 1, 4.5)).ok());
    EXPECT_FALSE(sm::validate(superquadric({1, NAN, 1}, 1, 1)).ok());
    sm::ShapeDef plane{.type = sm::ShapeType::Plane, .plane_normal = {0, 0, 0}};
    EXPECT_FALSE(sm::validate(plane).ok());
}
