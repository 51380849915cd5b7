// SPDX-License-Identifier: MIT
// Moulding a modal body with a finger: a point load driven by how deep the pressed point has sunk.
#include "session.h"
#include "supermodal/body.h"
#include "supermodal/modal.h"

#include <algorithm>
#include <cmath>

namespace supermodal::editor
{
namespace
{

// Per-step gains of the finger's force: up 5% while too shallow, down 10% while too deep. Geometric, so
// any stiffness is reached in a few hundred steps whatever the material (1.05^300 ≈ 2e6).
constexpr double k_grow = 1.05, k_shrink = 0.9;
// Force limits in body weights [-]: no runaway on a body that cannot sink (a stiff steel block).
constexpr double k_min_weights = 1e-3, k_max_weights = 1e6;

} // namespace

double EditorSession::sink_along(Entity body, const Vec3& point_shape, const Vec3& direction_shape) const
{
    const World& w = *m_world;
    const Vec3 local = rotate(conjugate(body_orientation(w, body)),
                              body_deformed_point(w, body, point_shape) - body_position(w, body));
    return dot(local - point_shape, direction_shape);
}

Status EditorSession::mould(const Ray& ray, double depth, int steps)
{
    end_mode_animation();
    if (!(std::isfinite(depth) && depth > 0.0 && depth <= 1.0) || steps < 1)
        return Error{"", "", "moulding needs a depth in (0, 1] m and at least one step"};
    const std::optional<PickHit> hit = pick(ray);
    if (!hit)
        return Error{"", "", "the ray hits no body"};
    if (body_motion(*m_world, hit->body) != MotionType::Dynamic ||
        body_modal_basis(*m_world, hit->body) == nullptr)
        return Error{"", "",
                     "\"" + hit->name +
                         "\" is not a modal dynamic body and cannot be moulded (set its "
                         "dynamics to modal, with a material that has a yield_stress)"};
    const double g = length(m_world->settings().gravity);
    MouldFinger f;
    f.body = hit->body;
    f.point_shape = hit->point_shape;
    f.direction_shape = rotate(conjugate(body_orientation(*m_world, hit->body)), normalized(ray.direction));
    f.start_sink = sink_along(f.body, f.point_shape, f.direction_shape);
    f.depth = depth;
    f.weight = body_mass_properties(*m_world, hit->body).mass * (g > 0.0 ? g : 9.81);
    f.force = f.weight;
    f.steps_left = steps;
    m_mould = f;
    m_mould_reached = 0.0;
    return {};
}

void EditorSession::apply_mould()
{
    if (!m_mould || m_mould->steps_left <= 0 || !world_valid(*m_world, m_mould->body)) {
        m_mould.reset();
        return;
    }
    MouldFinger& f = *m_mould;
    World& w = *m_world;
    const double sunk = sink_along(f.body, f.point_shape, f.direction_shape) - f.start_sink;
    m_mould_reached = std::max(m_mould_reached, sunk);
    f.force = std::clamp(f.force * (sunk < f.depth ? k_grow : k_shrink), k_min_weights * f.weight,
                         k_max_weights * f.weight);
    const Quat q = body_orientation(w, f.body);
    apply_force(w, f.body, f.force * rotate(q, f.direction_shape),
                body_deformed_point(w, f.body, f.point_shape));
    if (--f.steps_left == 0)
        m_mould.reset();
}

} // namespace supermodal::editor
