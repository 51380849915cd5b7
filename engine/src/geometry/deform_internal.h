// SPDX-License-Identifier: MIT
// Barr taper and bend, taken apart for callers that evaluate the map at many points (mass quadrature):
// the parameters are unpacked once and the z-only bend factors are shared between ±z. The formulas
// are the ones in deform.cpp's header comment.
#pragma once

#include "supermodal/math.h"
#include "supermodal/shape.h"

namespace supermodal
{

/// Taper and bend parameters of a shape, unpacked.
struct Deformation {
    double kx = 0.0, ky = 0.0; ///< Taper factors [-].
    double a3 = 1.0;           ///< Polar radius the taper is relative to [m].
    double k = 0.0;            ///< Bend curvature [1/m]; 0 when has_bend is false.
    double c = 1.0, s = 0.0;   ///< cos α, sin α of the bending plane.
    bool has_bend = false;
};
[[nodiscard]] Deformation deformation_of(const ShapeDef& shape);

/// The bend's factors that depend on z alone: lift = (1 − cos kz)/k, rise = sin(kz)/k [m]; both finite
/// and free of cancellation as k → 0. lift is even in z, rise odd.
struct BendArc {
    double lift = 0.0;
    double rise = 0.0;
};
[[nodiscard]] BendArc bend_arc(const Deformation& d, double z);

/// Taper, then bend with the arc factors of p.z [m].
[[nodiscard]] inline Vec3 deform_with(const Deformation& d, const Vec3& p, const BendArc& arc)
{
    const Vec3 t{(1.0 + d.kx * p.z / d.a3) * p.x, (1.0 + d.ky * p.z / d.a3) * p.y, p.z};
    if (!d.has_bend)
        return t;
    const double sigma = 1.0 - d.k * (d.c * t.x + d.s * t.y);
    const double shift = sigma * arc.lift;
    return {t.x + d.c * shift, t.y + d.s * shift, sigma * arc.rise};
}

/// det ∂deform/∂p = (1 + kx·z/a3)(1 + ky·z/a3)·(1 − k·u) at p [-]; u is the tapered point's coordinate
/// along the bending direction.
[[nodiscard]] inline double deform_determinant(const Deformation& d, const Vec3& p)
{
    const double fx = 1.0 + d.kx * p.z / d.a3, fy = 1.0 + d.ky * p.z / d.a3;
    return fx * fy * (d.has_bend ? 1.0 - d.k * (d.c * fx * p.x + d.s * fy * p.y) : 1.0);
}

} // namespace supermodal
