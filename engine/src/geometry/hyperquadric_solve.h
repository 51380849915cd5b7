// SPDX-License-Identifier: MIT
// Hyperquadric helpers shared by deform.cpp (contact measure), hyperquadric_mesh.cpp (meshes, samples),
// mass_deformed.cpp (quadrature) and the scene loader (boundedness checks). Method:
// docs/geometry.md.
#pragma once

#include "supermodal/api.h"
#include "supermodal/math.h"
#include "supermodal/shape.h"

namespace supermodal
{

/// Natural log of H(p) = Σ |n_i·p + d_i|^γ_i, computed as a log-sum-exp so it never overflows; −1e300
/// where every term vanishes.
[[nodiscard]] double hyperquadric_log_value(const ShapeDef& shape, const Vec3& p);

/// Well-scaled contact measure H^(1/γ_max) − 1 [-]: −1 where H = 0, 0 on the surface, and about the
/// distance from the surface in units of the slab half-widths 1/|n_i| outside. Finite everywhere.
[[nodiscard]] double hyperquadric_measure(const ShapeDef& shape, const Vec3& p);

/// A point well inside a hyperquadric, found by minimising H.
struct HyperquadricCenter {
    Vec3 point{};              ///< The minimiser found [m], shape frame.
    double log_value = 0.0;    ///< ln H there [-]; < 0 means the body is non-empty.
    bool is_bounded = false;   ///< The term normals span 3-D, so H grows without bound in every direction.
    bool is_non_empty = false; ///< H < 1 somewhere (at `point`).
};
/// Minimises H by damped Newton steps from the least-squares zero of the terms. Exported (SM_API) though
/// internal: the scene loader in supermodal::assets checks boundedness with it.
[[nodiscard]] SM_API HyperquadricCenter hyperquadric_center(const ShapeDef& shape);

/// Distance [m] from `center` (with H(center) < 1) along the unit `direction` to the surface H = 1: the
/// first crossing, exact for convex bodies (every γ ≥ 1). Bracketed by the slabs |n_i·x + d_i| ≤ 1 that
/// contain the body, then safeguarded Newton on ln H.
[[nodiscard]] double hyperquadric_ray_exit(const ShapeDef& shape, const Vec3& center, const Vec3& direction);

} // namespace supermodal
