// SPDX-License-Identifier: MIT
#include "supermodal/shape.h"

#include <cmath>
#include <string>

namespace supermodal
{
namespace
{

// Barr's convention: below 0 the power is undefined, above 4 the surface folds into itself.
constexpr double k_max_exponent = 4.0;

Status fail(const char* where, const std::string& what)
{
    return Error{"", where, what};
}

} // namespace

ShapeDef default_shape_def()
{
    return ShapeDef{};
}

Status validate(const ShapeDef& def)
{
    if (def.type == ShapeType::Plane) {
        if (!is_finite(def.plane_normal) || length(def.plane_normal) == 0.0)
            return fail("shape.plane_normal", "expected a finite, non-zero vector");
        if (!std::isfinite(def.plane_offset))
            return fail("shape.plane_offset", "expected a finite number");
        return {};
    }
    for (int i = 0; i < 3; ++i)
        if (!(def.radii[i] > 0.0) || !std::isfinite(def.radii[i]))
            return fail("shape.radii", "expected finite radii > 0");
    for (double e : {def.epsilon1, def.epsilon2})
        if (!(e > 0.0 && e <= k_max_exponent))
            return fail("shape.exponents", "expected exponents in (0, 4]");
    for (double t : {def.taper.kx, def.taper.ky})
        if (!(t >= -1.0 && t <= 1.0))
            return fail("shape.taper", "expected taper factors in [-1, 1]");
    if (!(def.bend.curvature >= 0.0) || !std::isfinite(def.bend.curvature) || !std::isfinite(def.bend.angle))
        return fail("shape.bend", "expected a finite curvature >= 0 and a finite angle");
    return {};
}

} // namespace supermodal
