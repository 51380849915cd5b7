// SPDX-License-Identifier: MIT
// The contact measure and its gradient at one point from one evaluation of the inside-outside terms, for
// the narrowphase's Newton steps, which ask for the value and then, unless it has converged, the slope.
#pragma once

#include "geometry/superquadric.h"

namespace supermodal
{

/// contact_measure() and contact_measure_gradient() of an undeformed superquadric at one point, bit for
/// bit as those two calls; the log-space terms are evaluated once, on construction.
class MeasurePoint
{
  public:
    MeasurePoint(const ShapeDef& shape, const Vec3& p);
    [[nodiscard]] double value() const { return m_value; }
    [[nodiscard]] Vec3 gradient() const;

  private:
    const ShapeDef* m_shape;
    Vec3 m_p;                ///< The point, or u = p ⊘ a on the ellipsoid's shortcut.
    sq::LogTerms m_terms;    ///< Unset on the ellipsoid's shortcut (m_shortcut).
    bool m_shortcut = false; ///< An ellipsoid in the range where F is summed directly.
    double m_value = 0.0;
};

} // namespace supermodal
