// SPDX-License-Identifier: MIT
// Penetration of two convex bodies by Minkowski Portal Refinement (libccd's ccdMPRPenetration) on the
// analytic superquadric support map: one normal and depth per pair, from which the manifold builds
// its points (manifold.h).
#pragma once

#include "contact/narrowphase.h"

namespace supermodal
{

/// Result of one MPR query of A against B.
struct MprResult {
    bool hit = false;      ///< The bodies overlap (depth > 0).
    double depth = 0.0;    ///< Penetration along normal [m].
    Vec3 normal{};         ///< Unit, from B towards A, world.
    Vec3 point{};          ///< libccd's contact position [m], world (between the two surfaces).
    int support_calls = 0; ///< Minkowski support evaluations the query used [-].
    bool gave_up =
        false; ///< Unresolvable (too far out for doubles) or the support budget ran out; no overlap.
};

/// Portal tolerance relative to the smaller body's smallest radius [-]: the depth is found to this
/// fraction of a radius (1e-5 m on a 0.1 m body), well below the resting sink g/ω² ≈ 1e-4 m.
inline constexpr double k_mpr_tolerance_rel = 1e-4;
/// Cap on portal refinement iterations [-]; a smooth superquadric pair converges in ~10–30.
inline constexpr unsigned long k_mpr_max_iterations = 100;

/// A query runs only where machine epsilon × (k_position × its largest coordinate + k_extent × the
/// larger body's reach) stays under the tolerance [-]. A far position only offsets every Minkowski
/// point by its rounding; a long body's reach enters libccd's cross products (portal normals) and is
/// amplified. Measured: a 0.04 × 0.06 m rod 1e8 m long beside a 6 cm body at 200 random poses reported
/// 5× the overlaps of 1e4 m; at 1e7 m none extra. k_extent = 1024 refuses past 1.3e7 m for 3 cm bodies;
/// k_position = 8 past 1.7e9 m.
inline constexpr double k_mpr_rounding_position = 8.0;
inline constexpr double k_mpr_rounding_extent = 1024.0;

/// Budget of Minkowski support evaluations per query [-]: three phases of at most
/// k_mpr_max_iterations each, plus the start. Normal queries use far fewer (MprQuery tests).
inline constexpr int k_mpr_max_support_calls = 3 * static_cast<int>(k_mpr_max_iterations) + 8;

/// Support point of a body (convex collider) along a world direction [m], world.
[[nodiscard]] Vec3 body_support(const BodyView& body, const Vec3& direction);
/// Centre of the body's shape [m], world: an interior point for MPR's portal origin.
[[nodiscard]] Vec3 body_shape_centre(const BodyView& body);

/// MPR penetration of two convex bodies (both colliders convex).
[[nodiscard]] MprResult mpr_penetration(const BodyView& a, const BodyView& b,
                                        int support_budget = k_mpr_max_support_calls);

} // namespace supermodal
