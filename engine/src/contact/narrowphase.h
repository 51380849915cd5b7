// SPDX-License-Identifier: MIT
// Narrowphase: contact points of one pair. Two paths (docs/contact.md):
//  - sampling (the paper's): surface samples of one body tested with the other's inside-outside
//    function, both ways; works for concave, tapered, bent bodies; each point carries a weight
//    (its share of the touching surface area), so forces do not depend on the sample count;
//  - support map (libccd MPR) for convex, undeformed pairs, with a small persistent manifold.
#pragma once

#include "contact/collider.h"
#include "supermodal/contact.h"
#include "supermodal/geometry.h"

#include <vector>

namespace supermodal
{

/// Point of a shape-frame query: the contact measure and, when inside, depth and outward normal.
struct InsideTest {
    bool inside = false;
    double depth = 0.0; ///< Approximate distance to the surface [m] (measure / |gradient|).
    Vec3 normal{};      ///< Unit outward normal, shape frame.
};

/// A body's own inside-outside test in place of its collider's shape: a deformable body's deformed shape
/// (a modal body through its inverse deformation). Shape-frame point in, shape-frame result out.
struct DeformedTest {
    InsideTest (*test)(const void* ctx, const Collider& c, const Vec3& p_shape) = nullptr; ///< Null: rest.
    const void* ctx = nullptr; ///< What `test` reads (the body's deformation), unchanged during the query.
};

/// A body as the narrowphase sees it.
struct BodyView {
    const Collider* collider = nullptr;
    Vec3 position{};         ///< Centre of mass [m], world.
    Quat orientation{};      ///< world_from_body.
    Aabb box{};              ///< World box [m].
    DeformedTest deformed{}; ///< Sampled points of the other body test against this; default: the rest shape.
};

/// One contact point of a pair: push A along +normal, B along −normal.
struct ContactPoint {
    Vec3 point{};        ///< [m], world.
    Vec3 normal{};       ///< Unit, from B towards A, world.
    double depth = 0.0;  ///< Penetration [m], > 0.
    double weight = 0.0; ///< Share of the pair's penalty force [-]; a pair's weights sum to 1.
    double area = 0.0;   ///< The point's own surface area before the shares [m²] (a manifold point: 1).
};

/// Work of one pair's support-map query, for the step profile (StepProfile::support_calls).
struct QueryCost {
    int support_calls = 0; ///< Support-map evaluations, one body each [-] (a Minkowski support is two).
};

/// Appends the points of A against B by surface sampling (both directions, weights summing to 1).
/// Returns the number appended.
int collide_sampled(const BodyView& a, const BodyView& b, std::vector<ContactPoint>& out_points);

/// Appends the points of a body against a plane (normal from the plane towards the body when the
/// body is A; flipped when body_is_a is false). Returns the number appended.
int collide_plane(const BodyView& body, const BodyView& plane, bool body_is_a,
                  std::vector<ContactPoint>& out_points);

/// Whether a pair goes through the support map (MPR and manifold) rather than sampling: not when the
/// path is Sampling; otherwise when both are convex (undeformed superquadrics, ε ≤ 2) or one is a
/// plane and the other convex.
[[nodiscard]] bool use_support_map(ContactPath path, const Collider& a, const Collider& b);

/// Tests a shape-frame point against a collider's shape (deformed shapes through the inverse map).
[[nodiscard]] InsideTest test_point(const Collider& c, const Vec3& p_shape);

} // namespace supermodal
