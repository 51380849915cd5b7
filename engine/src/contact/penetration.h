// SPDX-License-Identifier: MIT
// Penetration normal of two overlapping convex bodies, found by Newton from the pair's last normal. In
// the Minkowski difference M = B − A (points b − a, with the origin inside when the bodies overlap),
// w(n) = s_B(n) − s_A(−n) is M's support point and f(n) = n·w(n) the overlap along n (n from B towards
// A). MPR follows the ray from the interior point c_B − c_A (the shape centres) through the origin to
// where it leaves M and reports the normal there: the n whose w(n) lies on that ray (RayExit). The
// least overlap, min over n of f(n), is the penetration depth's own definition (LeastOverlap; at it
// w(n) is parallel to n). Newton solves either on the unit sphere with the support maps' curvature
// (support_jet: ∂w/∂n = J_A + J_B). Started from the pair's normal of the last substep (state), a
// slowly moving pair converges in one to three evaluations (two support-map calls each) instead of
// MPR's dozens. MPR (libccd) gives the start when there is none or Newton does not converge.
#pragma once

#include "contact/mpr.h"
#include "contact/narrowphase.h"

namespace supermodal
{

/// Which normal the search finds: MPR's (the ray from the shape centres leaves B − A through the point
/// whose normal it is), or the least overlap, min over n of h_B(n) + h_A(−n), the penetration depth's
/// own definition (at its minimum, w(n) is parallel to n).
enum class PenetrationTarget : uint8_t { RayExit, LeastOverlap };

/// What the search found.
struct Penetration {
    bool hit = false;       ///< The bodies overlap (depth > 0).
    bool converged = false; ///< Newton met the tolerance (else the normal is MPR's own).
    double depth = 0.0;     ///< Overlap along normal [m].
    Vec3 normal{};          ///< Unit, from B towards A, world.
    Vec3 on_a{};            ///< A's support point along −normal [m], world: its deepest point.
    Vec3 on_b{};            ///< B's support point along +normal [m], world.
    Vec3 point{}; ///< Between the two surfaces [m], world: MPR's position, else on_a and on_b's middle.
    int support_calls = 0; ///< Support-map evaluations, one body each [-].
};

/// Newton stops when its next step would turn the normal by less than this [rad]: the normal then lags
/// the exact one by ~1e-6 rad, the depth by ~(curvature radius) · 1e-12, far below MPR's tolerance.
inline constexpr double k_penetration_angle_tolerance = 1e-6;
/// The least-overlap search also stops when Newton's model of the overlap says its next step would
/// lower it by less than this [m]: the depth is then within about that of the minimum (an overlap along any
/// direction bounds the depth from above), and each point is still an exact support point.
inline constexpr double k_penetration_depth_tolerance = 1e-9;
/// Evaluations (two support-map calls each) one Newton search may make [-].
inline constexpr int k_penetration_max_evaluations = 12;

/// Newton from `start` (unit, from B towards A). Not hit when an evaluated direction separates the
/// bodies (an exact answer); not converged when the budget ran out or the model broke down.
[[nodiscard]] Penetration refine_penetration(const BodyView& a, const BodyView& b, const Vec3& start,
                                             PenetrationTarget target = PenetrationTarget::RayExit,
                                             int max_evaluations = k_penetration_max_evaluations);

/// The pair's penetration: Newton from `warm` (the pair's last normal, world; zero for none); else
/// from MPR's normal; MPR's own answer when neither converges.
/// MPR's answer as a Penetration (not converged), with the deepest points along its normal: the two
/// support-map evaluations they take are its support_calls.
[[nodiscard]] Penetration penetration_from_mpr(const BodyView& a, const BodyView& b, const MprResult& mpr);

[[nodiscard]] Penetration find_penetration(const BodyView& a, const BodyView& b, const Vec3& warm,
                                           PenetrationTarget target = PenetrationTarget::RayExit);

} // namespace supermodal
