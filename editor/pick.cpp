// SPDX-License-Identifier: MIT
// Mouse picking: where a ray first enters a body, found with the shape's inside-outside measure
// (shape_measure: superquadrics, tapered and bent ones, hyperquadrics), and the drag and push tools
// that act at that point.
#include "session.h"
#include "supermodal/body.h"
#include "supermodal/geometry.h"

#include <algorithm>
#include <cmath>

namespace supermodal::editor
{
namespace
{

/// Samples per smallest box extent while marching: a body thinner than this along the ray could be
/// stepped over, so the step is an eighth of the thinnest side of the shape's box.
constexpr double k_steps_per_thickness = 8.0;
constexpr int k_min_march_steps = 16;
constexpr int k_max_march_steps = 8192;
/// Bisection halvings after the first inside sample: 60 takes any bracket below a double's resolution.
constexpr int k_bisections = 60;

/// Parameter t ≥ 0 where the unit ray (origin o, direction d) enters the shape, shape frame; negative
/// when it misses or starts inside.
double enter_shape(const ShapeDef& shape, const Vec3& o, const Vec3& d)
{
    const Aabb box = world_aabb(shape, Vec3{}, Quat::identity());
    double t0 = 0.0, t1 = std::numeric_limits<double>::infinity();
    for (int axis = 0; axis < 3; ++axis) {
        if (std::abs(d[axis]) < 1e-300) {
            if (o[axis] < box.min[axis] || o[axis] > box.max[axis])
                return -1.0;
            continue;
        }
        double a = (box.min[axis] - o[axis]) / d[axis], b = (box.max[axis] - o[axis]) / d[axis];
        if (a > b)
            std::swap(a, b);
        t0 = std::max(t0, a);
        t1 = std::min(t1, b);
    }
    if (!(t0 <= t1))
        return -1.0;
    if (shape_measure(shape, o) <= 0.0)
        return -1.0; // the eye is inside this body: it is not what the user points at
    const Vec3 extent = box.max - box.min;
    const double h = std::min({extent.x, extent.y, extent.z}) / k_steps_per_thickness;
    const int steps =
        std::clamp(static_cast<int>(std::ceil((t1 - t0) / h)), k_min_march_steps, k_max_march_steps);
    double previous = t0;
    for (int k = 0; k <= steps; ++k) {
        const double t = t0 + (t1 - t0) * static_cast<double>(k) / steps;
        if (shape_measure(shape, o + t * d) > 0.0) {
            previous = t;
            continue;
        }
        double outside = previous, inside = t;
        for (int i = 0; i < k_bisections && outside < inside; ++i) {
            const double mid = 0.5 * (outside + inside);
            (shape_measure(shape, o + mid * d) > 0.0 ? outside : inside) = mid;
        }
        return inside;
    }
    return -1.0;
}

} // namespace

std::optional<PickHit> EditorSession::pick(const Ray& ray) const
{
    const double length_d = length(ray.direction);
    if (!m_world || !(length_d > 0.0) || !std::isfinite(length_d) || !is_finite(ray.origin))
        return std::nullopt;
    const Vec3 d = ray.direction / length_d;
    std::optional<PickHit> best;
    for (const Entity e : world_bodies(*m_world)) {
        const ShapeDef& shape = body_shape(*m_world, e);
        const Vec3 position = body_position(*m_world, e);
        const Quat q = body_orientation(*m_world, e);
        double t = -1.0;
        if (shape.type == ShapeType::Plane) {
            // Half-space n·x ≤ offset, world frame: entered only from the outside.
            const Vec3 n = normalized(shape.plane_normal);
            const double facing = dot(n, d), height = dot(n, ray.origin) - shape.plane_offset;
            if (facing < 0.0 && height >= 0.0)
                t = -height / facing;
        } else {
            t = enter_shape(shape, inv_rotate(q, ray.origin - position), inv_rotate(q, d));
        }
        if (t < 0.0 || (best && t >= best->distance))
            continue;
        PickHit hit;
        hit.body = e;
        hit.name = body_name(*m_world, e);
        hit.distance = t;
        hit.point = ray.origin + t * d;
        hit.point_shape = shape.type == ShapeType::Plane ? hit.point : inv_rotate(q, hit.point - position);
        best = hit;
    }
    return best;
}

Status EditorSession::drag_begin(const Ray& ray)
{
    end_mode_animation();
    const std::optional<PickHit> hit = pick(ray);
    if (!hit)
        return Error{"", "", "the ray hits no body"};
    if (body_motion(*m_world, hit->body) != MotionType::Dynamic)
        return Error{"", "", "\"" + hit->name + "\" is not dynamic and cannot be dragged"};
    DragSpring spring;
    spring.body = hit->body;
    spring.point_shape = hit->point_shape;
    spring.target = hit->point;
    m_drag = spring;
    return {};
}

void EditorSession::drag_to(const Vec3& target)
{
    if (m_drag && is_finite(target))
        m_drag->target = target;
}

Status EditorSession::push(const Ray& ray, double force, int steps)
{
    end_mode_animation();
    if (!(std::isfinite(force) && force >= 0.0) || steps < 1)
        return Error{"", "", "a push needs a finite force >= 0 N and at least one step"};
    const std::optional<PickHit> hit = pick(ray);
    if (!hit)
        return Error{"", "", "the ray hits no body"};
    if (body_motion(*m_world, hit->body) != MotionType::Dynamic)
        return Error{"", "", "\"" + hit->name + "\" is not dynamic and cannot be pushed"};
    m_push = PushLoad{hit->body, hit->point_shape, force * normalized(ray.direction), steps};
    return {};
}

} // namespace supermodal::editor
