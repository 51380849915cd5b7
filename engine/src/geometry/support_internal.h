// SPDX-License-Identifier: MIT
// The support map with its derivative (support.cpp), for the contact's Newton search of the
// penetration normal: how far the support point moves when the direction turns.
#pragma once

#include "supermodal/geometry.h"

namespace supermodal
{

/// A support point and its Jacobian along the direction, shape frame.
struct SupportJet {
    Vec3 point{}; ///< support_point(shape, direction) [m], bit for bit.
    /// ∂point/∂direction at `direction` [m per unit of direction]: symmetric, positive semi-definite,
    /// with the direction in its null space; at a unit direction the shape's radius-of-curvature
    /// tensor at the point. Scales as 1/|direction|. Capped where a flat face makes it unbounded (its
    /// normal direction, ε < 1); zero where the support map is piecewise constant (ε ≥ 2).
    Mat3 jacobian{};
};

/// Support point and Jacobian of an undeformed superquadric (the convex hull's for ε > 2).
[[nodiscard]] SupportJet support_jet(const ShapeDef& shape, const Vec3& direction);

} // namespace supermodal
