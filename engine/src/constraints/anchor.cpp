// SPDX-License-Identifier: MIT
// Anchors on surfaces: resolved in the shape frame, so a resized or reshaped part carries them along.
#include "constraints/constraint_world.h"
#include "supermodal/geometry.h"

#include <algorithm>
#include <cmath>

namespace supermodal
{
namespace
{

// Where the ray from the origin along unit d leaves a hyperquadric: H grows along a ray from an inside
// origin, so bisection on H = 1 converges; 60 halvings reach round-off of any body size.
Vec3 hyperquadric_ray_exit(const ShapeDef& shape, const Vec3& d)
{
    if (!(hyperquadric_value(shape, Vec3{}) < 1.0))
        return Vec3{};
    double lo = 0.0, hi = 1.0;
    for (int i = 0; i < 200 && hyperquadric_value(shape, hi * d) < 1.0; ++i)
        hi *= 2.0;
    for (int i = 0; i < 60; ++i) {
        const double mid = 0.5 * (lo + hi);
        (hyperquadric_value(shape, mid * d) < 1.0 ? lo : hi) = mid;
    }
    return lo * d;
}

Vec3 superquadric_ray_exit(const ShapeDef& shape, const Vec3& d)
{
    // radial_distance(d) = |d| − r with r the surface radius along the ray.
    const Vec3 p = (1.0 - radial_distance(shape, d)) * d;
    return is_deformed(shape) ? deform_point(shape, p) : p;
}

} // namespace

Vec3 resolve_anchor(const ShapeDef& shape, const AnchorDef& anchor)
{
    Vec3 p{};
    switch (anchor.kind) {
    case AnchorKind::Point:
        p = anchor.point;
        break;
    case AnchorKind::Direction: {
        const double len = length(anchor.direction);
        if (!(len > 0.0) || !std::isfinite(len) || shape.type == ShapeType::Plane)
            return Vec3{};
        const Vec3 d = anchor.direction / len;
        p = shape.type == ShapeType::Hyperquadric ? hyperquadric_ray_exit(shape, d)
                                                  : superquadric_ray_exit(shape, d);
        break;
    }
    case AnchorKind::Surface:
        if (shape.type != ShapeType::Superquadric)
            return Vec3{};
        p = surface_point(shape, std::clamp(anchor.eta, -0.5 * M_PI, 0.5 * M_PI), anchor.omega);
        if (is_deformed(shape))
            p = deform_point(shape, p);
        break;
    }
    return is_finite(p) ? p : Vec3{};
}

Vec3 world_point(const BodyModel& m, const Pose& p, const Vec3& local)
{
    return p.position + rotate(p.orientation, local - m.mass.center_of_mass);
}

void refresh_anchors(ConstraintWorld& cw, Entity body, const ShapeDef& shape)
{
    cw.reg.each<ConstraintModel>([&](Entity, ConstraintModel& c) {
        if (c.def.a == body)
            c.local_a = resolve_anchor(shape, c.def.anchor_a);
        if (c.def.b == body)
            c.local_b = resolve_anchor(shape, c.def.anchor_b);
    });
}

void drop_constraints_of(ConstraintWorld& cw, Entity body)
{
    std::vector<Entity> doomed;
    cw.reg.each<ConstraintModel>([&](Entity e, const ConstraintModel& c) {
        if (c.def.a == body || c.def.b == body)
            doomed.push_back(e);
    });
    for (Entity e : doomed)
        cw.reg.destroy(e);
    for (Entity& p : cw.parent)
        if (p == body)
            p = Entity{};
    if (body.index < cw.parent.size())
        cw.parent[body.index] = Entity{};
}

void non_colliding_pairs(const ConstraintWorld& cw, std::vector<uint64_t>& out_keys)
{
    out_keys.clear();
    const auto& models = cw.reg.store<ConstraintModel>();
    for (size_t i = 0; i < models.entities().size(); ++i) {
        const ConstraintModel& c = models.get(models.entities()[i]);
        if (c.def.collide_connected || c.def.b.is_null())
            continue;
        const uint32_t lo = std::min(c.def.a.index, c.def.b.index),
                       hi = std::max(c.def.a.index, c.def.b.index);
        out_keys.push_back((uint64_t{lo} << 32) | hi);
    }
    for (uint32_t child = 0; child < cw.parent.size(); ++child) {
        const Entity p = cw.parent[child];
        if (!p.is_null())
            out_keys.push_back((uint64_t{std::min(child, p.index)} << 32) | std::max(child, p.index));
    }
    std::sort(out_keys.begin(), out_keys.end());
    out_keys.erase(std::unique(out_keys.begin(), out_keys.end()), out_keys.end());
}

} // namespace supermodal
