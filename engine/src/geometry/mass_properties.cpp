// SPDX-License-Identifier: MIT
// Closed-form superquadric volume and inertia (Jaklič, Leonardis & Solina, "Segmentation and Recovery
// of Superquadrics", 2000, ch. 2), evaluated with log-Gamma so that ε down to 0.01 neither overflows
// nor loses precision: each Beta value alone grows like 1/ε, but ε·B(·) stays finite.
#include "geometry/mass_deformed.h"
#include "supermodal/geometry.h"
#include "supermodal/shape.h"

#include <cmath>

namespace supermodal
{
namespace
{

double beta(double x, double y)
{
    return std::exp(std::lgamma(x) + std::lgamma(y) - std::lgamma(x + y));
}

} // namespace

double superquadric_volume(const ShapeDef& def)
{
    if (def.type != ShapeType::Superquadric)
        return 0.0;
    const double e1 = def.epsilon1, e2 = def.epsilon2;
    const Vec3& a = def.radii;
    return 2.0 * a.x * a.y * a.z * e1 * e2 * beta(0.5 * e1 + 1.0, e1) * beta(0.5 * e2, 0.5 * e2);
}

MassProperties compute_mass_properties(const ShapeDef& def, double density)
{
    MassProperties mp;
    // Taper, bend and hyperquadrics have no closed form: quadrature (mass_deformed.cpp).
    if (def.type == ShapeType::Hyperquadric || (def.type == ShapeType::Superquadric && is_deformed(def)))
        return quadrature_mass(def, density, k_default_mass_order).properties;
    if (def.type != ShapeType::Superquadric)
        return mp;
    const double e1 = def.epsilon1, e2 = def.epsilon2;
    const Vec3& a = def.radii;
    mp.volume = superquadric_volume(def);
    mp.mass = density * mp.volume;
    // Second moments ∫x², ∫y², ∫z² over the solid (times ρ), then I_xx = ∫(y² + z²) and so on.
    const double common = 0.5 * density * a.x * a.y * a.z * e1 * e2;
    const double equatorial = beta(1.5 * e2, 0.5 * e2) * beta(0.5 * e1, 2.0 * e1 + 1.0);
    const double polar = 4.0 * beta(0.5 * e2, 0.5 * e2 + 1.0) * beta(1.5 * e1, e1 + 1.0);
    const double sxx = common * a.x * a.x * equatorial;
    const double syy = common * a.y * a.y * equatorial;
    const double szz = common * a.z * a.z * polar;
    mp.inertia_diagonal = {syy + szz, sxx + szz, sxx + syy};
    return mp;
}

} // namespace supermodal
