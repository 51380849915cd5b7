// SPDX-License-Identifier: MIT
// Moving, turning and resizing a body as one undoable edit (the gizmo and the script's "transform").
// It is made of set() edits of the body's position, orientation and radii, joined in the history, so
// undo, redo, refusals and the world's rebuild behave exactly as for any other edit.
#include "session.h"
#include "supermodal/body.h"

#include <cmath>

namespace supermodal::editor
{
namespace
{

double round_to(double value, double step)
{
    return step > 0.0 ? std::round(value / step) * step : value;
}

/// Turn about world X, then Y, then Z [°].
Quat world_turn(const Vec3& degrees)
{
    const double k = M_PI / 180.0;
    const Quat qx = quat_from_rotation_vector({degrees.x * k, 0.0, 0.0});
    const Quat qy = quat_from_rotation_vector({0.0, degrees.y * k, 0.0});
    const Quat qz = quat_from_rotation_vector({0.0, 0.0, degrees.z * k});
    return qz * qy * qx;
}

Json vec_json(const Vec3& v)
{
    return Json::array({v.x, v.y, v.z});
}

Json quat_json(const Quat& q)
{
    return Json::array({q.w, q.x, q.y, q.z});
}

} // namespace

TransformDef snapped(const TransformDef& def, const SnapDef& steps)
{
    if (!def.snap)
        return def;
    TransformDef out = def;
    for (int i = 0; i < 3; ++i) {
        out.translate[i] = round_to(def.translate[i], steps.move_step);
        out.rotate_deg[i] = round_to(def.rotate_deg[i], steps.rotate_step_deg);
        // A scale never snaps to 0: the smallest is one step.
        out.scale[i] = std::max(round_to(def.scale[i], steps.scale_step), steps.scale_step);
    }
    return out;
}

Status EditorSession::transform(std::string_view body, const TransformDef& def, const SnapDef& steps)
{
    if (!m_world)
        return Error{"", "", "no scene is loaded"};
    const std::string name(body);
    const Entity e = find_body(*m_world, name);
    size_t index = m_scene.bodies.size();
    for (size_t i = 0; i < m_scene.bodies.size(); ++i)
        if (m_scene.bodies[i].def.name == name)
            index = i;
    if (e.is_null() || index == m_scene.bodies.size())
        return Error{"", "body", "no body named \"" + name + "\""};
    const SceneBody& sb = m_scene.bodies[index];
    if (sb.def.shape.type == ShapeType::Plane)
        return Error{"", "body", "\"" + name + "\" is a plane: it has no pose or radii to transform"};
    if (!(steps.move_step > 0.0 && steps.rotate_step_deg > 0.0 && steps.scale_step > 0.0 &&
          std::isfinite(steps.move_step + steps.rotate_step_deg + steps.scale_step)))
        return Error{"", "snap", "expected snapping steps > 0 and finite"};
    const TransformDef t = snapped(def, steps);
    if (t.scale != Vec3{1.0, 1.0, 1.0} && sb.def.shape.type != ShapeType::Superquadric)
        return Error{"", "scale", "\"" + name + "\" is a hyperquadric: edit its terms in the scene file"};
    if (!is_finite(t.translate) || !is_finite(t.rotate_deg))
        return Error{"", "translate", "expected finite numbers"};
    for (int i = 0; i < 3; ++i)
        if (!(t.scale[i] > 0.0 && std::isfinite(t.scale[i])))
            return Error{"", "scale/" + std::to_string(i),
                         "expected a factor > 0, found " + std::to_string(t.scale[i])};

    // The new pose from the one in the world now, written in the parent's frame for a part.
    const Vec3 position = body_position(*m_world, e) + t.translate;
    const Quat orientation = normalized(world_turn(t.rotate_deg) * body_orientation(*m_world, e));
    Vec3 local_position = position;
    Quat local_orientation = orientation;
    if (!sb.parent.empty()) {
        const Entity p = find_body(*m_world, sb.parent);
        const Quat qp = body_orientation(*m_world, p);
        local_position = inv_rotate(qp, position - body_position(*m_world, p));
        local_orientation = normalized(conjugate(qp) * orientation);
    }
    const std::string at = "/bodies/" + std::to_string(index);
    std::vector<std::pair<std::string, Json>> parts;
    if (t.scale != Vec3{1.0, 1.0, 1.0}) {
        const Vec3& r = sb.def.shape.radii;
        parts.emplace_back(at + "/shape/radii",
                           vec_json({r.x * t.scale.x, r.y * t.scale.y, r.z * t.scale.z}));
    }
    if (t.translate != Vec3{})
        parts.emplace_back(at + "/position", vec_json(local_position));
    if (t.rotate_deg != Vec3{})
        parts.emplace_back(at + "/orientation", quat_json(local_orientation));
    return set_joined(parts); // nothing to do records no edit
}

Status EditorSession::set_joined(const std::vector<std::pair<std::string, Json>>& edits)
{
    const size_t start = m_history_position;
    for (size_t k = 0; k < edits.size(); ++k) {
        if (Status status = set(edits[k].first, edits[k].second); !status) {
            // All or nothing: take back the parts already applied and forget them.
            while (m_history_position > start)
                (void)undo();
            m_history.resize(start);
            return status;
        }
        m_history.back().joined = k > 0;
    }
    return {};
}

} // namespace supermodal::editor
