// Shape builders shared by tests.
#pragma once

#include "supermodal/shape.h"

namespace supermodal::test
{

/// An undeformed superquadric with radii [m] and exponents ε1, ε2 [-].
inline ShapeDef superquadric(Vec3 radii, double e1, double e2)
{
    ShapeDef s = default_shape_def();
    s.radii = radii;
    s.epsilon1 = e1;
    s.epsilon2 = e2;
    return s;
}

} // namespace supermodal::test
