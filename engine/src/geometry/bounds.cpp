// SPDX-License-Identifier: MIT
// World-space bounding boxes. An undeformed superquadric is centrally symmetric, so its extent along
// world axis i is ± h(Rᵀe_i) with h the support function: exact for any pose, convex or not (the
// support map gives the convex hull's for concave shapes, which has the same extents). Deformed
// superquadrics and hyperquadrics have no closed-form support: their box bounds a tessellation plus a
// margin for the surface bulging between vertices.
#include "supermodal/geometry.h"

#include <algorithm>
#include <cmath>

namespace supermodal
{
namespace
{

constexpr double k_unbounded = 1e300;
// Segments around the equator of the tessellation that bounds deformed shapes and hyperquadrics.
constexpr int k_bound_resolution = 64;
// Margin for the surface between tessellation vertices, as a fraction of the mesh's largest half
// extent. A circle cut into 64 chords bulges by (1 − cos(π/64)) ≈ 1.2e-3 of its radius beyond them;
// 2e-2 leaves an order of magnitude for uneven vertex spacing, aspect ratios and bending.
constexpr double k_mesh_margin_rel = 2e-2;

Aabb unbounded()
{
    return {{-k_unbounded, -k_unbounded, -k_unbounded}, {k_unbounded, k_unbounded, k_unbounded}};
}

Aabb mesh_aabb(const ShapeDef& shape, const Vec3& position, const Quat& q)
{
    const TriangleMesh mesh = tessellate(shape, k_bound_resolution);
    if (mesh.positions.empty())
        return unbounded();
    Vec3 lo{INFINITY, INFINITY, INFINITY}, hi{-INFINITY, -INFINITY, -INFINITY};
    Vec3 shape_lo = lo, shape_hi = hi;
    for (const Vec3& v : mesh.positions) {
        const Vec3 w = rotate(q, v);
        for (int i = 0; i < 3; ++i) {
            lo[i] = std::min(lo[i], w[i]);
            hi[i] = std::max(hi[i], w[i]);
            shape_lo[i] = std::min(shape_lo[i], v[i]);
            shape_hi[i] = std::max(shape_hi[i], v[i]);
        }
    }
    double extent = 0.0;
    for (int i = 0; i < 3; ++i)
        extent = std::max(extent, 0.5 * (shape_hi[i] - shape_lo[i]));
    const double margin = k_mesh_margin_rel * extent;
    const Vec3 pad{margin, margin, margin};
    const Aabb box{position + lo - pad, position + hi + pad};
    return is_finite(box.min) && is_finite(box.max) ? box : unbounded();
}

} // namespace

Aabb world_aabb(const ShapeDef& shape, const Vec3& position, const Quat& orientation)
{
    if (shape.type == ShapeType::Plane)
        return unbounded();
    const Quat q = normalized(orientation);
    if (shape.type == ShapeType::Hyperquadric || is_deformed(shape))
        return mesh_aabb(shape, position, q);
    const Mat3 r = to_mat3(q);
    Vec3 half;
    for (int i = 0; i < 3; ++i) {
        // Row i of R is Rᵀe_i, world axis i seen in the shape frame.
        const Vec3 axis_shape = r.row(i);
        half[i] = dot(axis_shape, support_point(shape, axis_shape));
    }
    return {position - half, position + half};
}

} // namespace supermodal
