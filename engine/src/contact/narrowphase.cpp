// SPDX-License-Identifier: MIT
#include "contact/narrowphase.h"

#include "geometry/measure_internal.h"

#include <algorithm>
#include <cmath>

namespace supermodal
{
namespace
{

// Finite-difference step for the gradient of deformed shapes and hyperquadrics, relative to the body's
// size: small against curvature, large against the measure's round-off (~1e-15).
constexpr double k_gradient_step_rel = 1e-6;

void normalize_weights(std::vector<ContactPoint>& points, size_t first, double weight_sum)
{
    for (size_t i = first; i < points.size(); ++i) {
        points[i].area = points[i].weight;
        points[i].weight = weight_sum > 0.0 ? points[i].weight / weight_sum : 0.0;
    }
}

// Box of the OBB {centre ± half} seen from a frame rotated by q about `origin` (world → local).
Aabb local_box_of(const Aabb& world_box, const Vec3& origin, const Quat& q)
{
    const Vec3 c = inv_rotate(q, 0.5 * (world_box.min + world_box.max) - origin);
    const Vec3 h = 0.5 * (world_box.max - world_box.min);
    const Mat3 r = to_mat3(conjugate(q));
    Vec3 e;
    for (int i = 0; i < 3; ++i)
        e[i] = std::abs(r.m[i][0]) * h.x + std::abs(r.m[i][1]) * h.y + std::abs(r.m[i][2]) * h.z;
    return {c - e, c + e};
}

bool boxes_overlap(const Aabb& a, const Aabb& b)
{
    return a.min.x <= b.max.x && b.min.x <= a.max.x && a.min.y <= b.max.y && b.min.y <= a.max.y &&
           a.min.z <= b.max.z && b.min.z <= a.max.z;
}

bool contains(const Aabb& box, const Vec3& p)
{
    return p.x >= box.min.x && p.x <= box.max.x && p.y >= box.min.y && p.y <= box.max.y && p.z >= box.min.z &&
           p.z <= box.max.z;
}

Vec3 measure_gradient(const Collider& c, const Vec3& p)
{
    if (!c.deformed && c.shape.type == ShapeType::Superquadric)
        return contact_measure_gradient(c.shape, p);
    const Vec3 size = c.local_box.max - c.local_box.min;
    const double h = k_gradient_step_rel * std::max({size.x, size.y, size.z});
    Vec3 g;
    for (int i = 0; i < 3; ++i) {
        Vec3 lo = p, hi = p;
        lo[i] -= h;
        hi[i] += h;
        g[i] = (shape_measure(c.shape, hi) - shape_measure(c.shape, lo)) / (2.0 * h);
    }
    return g;
}

// A point inside (measure m < 0) with the measure's gradient g there: depth and normal to first order.
InsideTest inside_along(double m, const Vec3& g)
{
    InsideTest t;
    const double gn = length(g);
    if (!(gn > 0.0) || !std::isfinite(gn))
        return t; // at the exact centre there is no direction to push: leave it to the other points
    t.inside = true;
    t.depth = -m / gn;
    t.normal = g / gn;
    return t;
}

// Samples of `from` tested against `against`; points and normals as seen by A (flip when `from` is B).
// Weights are area fractions within this direction.
int one_direction(const BodyView& from, const BodyView& against, bool from_is_a,
                  std::vector<ContactPoint>& out)
{
    const size_t first = out.size();
    const Collider& cf = *from.collider;
    const Collider& ca = *against.collider;
    const Aabb overlap{
        {std::max(from.box.min.x, against.box.min.x), std::max(from.box.min.y, against.box.min.y),
         std::max(from.box.min.z, against.box.min.z)},
        {std::min(from.box.max.x, against.box.max.x), std::min(from.box.max.y, against.box.max.y),
         std::min(from.box.max.z, against.box.max.z)}};
    const Aabb region = local_box_of(overlap, from.position, from.orientation);
    const Aabb against_shape_box{ca.local_box.min + ca.com_shape, ca.local_box.max + ca.com_shape};
    double area = 0.0;
    for_samples_where(
        *cf.samples, [&](const Aabb& box) { return boxes_overlap(box, region); },
        [&](const SurfaceSample& s) {
            const Vec3 p_world = from.position + rotate(from.orientation, s.point);
            const Vec3 q = inv_rotate(against.orientation, p_world - against.position) + ca.com_shape;
            if (!contains(against_shape_box, q))
                return;
            const InsideTest t = against.deformed.test != nullptr
                                     ? against.deformed.test(against.deformed.ctx, ca, q)
                                     : test_point(ca, q);
            if (!t.inside)
                return;
            const Vec3 n = rotate(against.orientation, t.normal);
            out.push_back({p_world, from_is_a ? n : -n, t.depth, s.area});
            area += s.area;
        });
    normalize_weights(out, first, area);
    return static_cast<int>(out.size() - first);
}

} // namespace

bool use_support_map(ContactPath path, const Collider& a, const Collider& b)
{
    if (path == ContactPath::Sampling)
        return false;
    const bool plane_a = a.shape.type == ShapeType::Plane, plane_b = b.shape.type == ShapeType::Plane;
    return (a.convex || plane_a) && (b.convex || plane_b) && !(plane_a && plane_b);
}

InsideTest test_point(const Collider& c, const Vec3& p)
{
    InsideTest t;
    if (!c.deformed && c.shape.type == ShapeType::Superquadric) {
        const MeasurePoint at(c.shape, p); // the gradient reuses the value's terms
        return at.value() < 0.0 ? inside_along(at.value(), at.gradient()) : t;
    }
    const double m = shape_measure(c.shape, p);
    if (!(m < 0.0))
        return t;
    return inside_along(m, measure_gradient(c, p));
}

int collide_sampled(const BodyView& a, const BodyView& b, std::vector<ContactPoint>& out)
{
    const size_t first = out.size();
    const int from_a = one_direction(a, b, true, out);
    const int from_b = one_direction(b, a, false, out);
    // Each direction's weights sum to 1; with both present, each carries half the pair's force.
    if (from_a > 0 && from_b > 0)
        for (size_t i = first; i < out.size(); ++i)
            out[i].weight *= 0.5;
    return from_a + from_b;
}

int collide_plane(const BodyView& body, const BodyView& plane, bool body_is_a, std::vector<ContactPoint>& out)
{
    const Collider& c = *body.collider;
    const Vec3 n = normalized(plane.collider->shape.plane_normal);
    const double offset = plane.collider->shape.plane_offset;
    // The plane in the body frame: points with dot(n_local, p) < offset_local are below it.
    const Vec3 n_local = inv_rotate(body.orientation, n);
    const double offset_local = offset - dot(n, body.position);
    const size_t first = out.size();
    for_samples_where(
        *c.samples,
        [&](const Aabb& box) {
            const Vec3 centre = 0.5 * (box.min + box.max), half = 0.5 * (box.max - box.min);
            const double reach =
                std::abs(n_local.x) * half.x + std::abs(n_local.y) * half.y + std::abs(n_local.z) * half.z;
            return dot(n_local, centre) - reach < offset_local;
        },
        [&](const SurfaceSample& s) {
            const double depth = offset_local - dot(n_local, s.point);
            if (!(depth > 0.0))
                return;
            out.push_back(
                {body.position + rotate(body.orientation, s.point), body_is_a ? n : -n, depth, s.area});
        });
    // A convex body's deepest point is exact from its support map; samples alone would miss it by up
    // to spacing²/(8·radius) on a curved body. It joins as one more sample of typical sample area.
    if (c.convex) {
        const Vec3 deepest = support_point(c.shape, inv_rotate(body.orientation, -n)) - c.com_shape;
        const double depth = offset_local - dot(n_local, deepest);
        if (depth > 0.0)
            out.push_back({body.position + rotate(body.orientation, deepest), body_is_a ? n : -n, depth,
                           c.samples->spacing * c.samples->spacing});
    }
    double area = 0.0;
    for (size_t i = first; i < out.size(); ++i)
        area += out[i].weight;
    normalize_weights(out, first, area);
    return static_cast<int>(out.size() - first);
}

} // namespace supermodal
