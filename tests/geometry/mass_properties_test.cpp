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

TEST(MassProperties, OctahedronVolumeIsExact)
{
    // ε1 = ε2 = 2 is the octahedron |x|/a + |y|/b + |z|/c ≤ 1 with volume 4abc/3.
    const sm::MassProperties mp = sm::compute_mass_properties(superquadric({1, 2, 3}, 2, 2), 1.0);
    EXPECT_NEAR(mp.volume, 4.0 * 6.0 / 3.0, k_closed_form_rel * 8);
}

// Quadrature over the ε × aspect grid, box and cylinder limits: mass_quadrature_test.cpp.

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
