// SPDX-License-Identifier: MIT
#include "session.h"

#include "supermodal/body.h"

#include <numeric>
#include <utility>

namespace supermodal::editor
{

Status EditorSession::load(const std::string& path)
{
    Result<Scene> scene = supermodal::load_scene(path);
    if (!scene)
        return scene.error();
    return load_scene(std::move(*scene));
}

void EditorSession::share_bases(Scene& scene) const
{
    // An edited scene comes back from JSON without the cache; every world the editor builds shares it.
    if (!scene.world.modal_basis_cache)
        scene.world.modal_basis_cache = m_basis_cache;
}

Status EditorSession::load_scene(Scene scene)
{
    end_mode_animation();
    Status status = install(std::move(scene));
    if (status) {
        ++m_loads;
        m_history.clear(); // a new scene: the old one's edits mean nothing here
        m_history_position = 0;
    }
    return status;
}

Status EditorSession::install(Scene scene)
{
    end_mode_animation();
    share_bases(scene);
    Result<World> world = build_world(scene);
    if (!world)
        return world.error();
    m_scene = std::move(scene);
    m_world.emplace(std::move(*world));
    attach_step_listener();
    m_drag.reset();
    m_push.reset();
    m_mould.reset();
    m_step_ms.clear();
    m_steps_run = 0;
    ++m_generation;
    m_step_pending = false;
    m_last_effect = SetEffect::Rebuilt;
    return {};
}

Status EditorSession::reset()
{
    end_mode_animation();
    const bool was_playing = m_playing;
    Status status = install(m_scene);
    m_playing = was_playing;
    return status;
}

void EditorSession::apply_loads()
{
    World& w = *m_world;
    if (m_drag && world_valid(w, m_drag->body) && body_motion(w, m_drag->body) == MotionType::Dynamic) {
        // A spring–damper tuned like the engine's constraints: k = m(2πf)², c = 2ζm(2πf), so the pull
        // feels the same for a pebble and a chair.
        const DragSpring& d = *m_drag;
        const double mass = body_mass_properties(w, d.body).mass;
        const double omega = 2.0 * M_PI * d.frequency_hz;
        const Quat q = body_orientation(w, d.body);
        const Vec3 grabbed = body_position(w, d.body) + rotate(q, d.point_shape);
        const Vec3 arm = grabbed - body_center_of_mass(w, d.body);
        const Vec3 velocity = body_linear_velocity(w, d.body) + cross(body_angular_velocity(w, d.body), arm);
        const Vec3 force =
            mass * omega * omega * (d.target - grabbed) - 2.0 * d.damping_ratio * mass * omega * velocity;
        apply_force(w, d.body, force, grabbed);
    }
    if (m_push && m_push->steps_left > 0 && world_valid(w, m_push->body)) {
        const Vec3 point =
            body_position(w, m_push->body) + rotate(body_orientation(w, m_push->body), m_push->point_shape);
        apply_force(w, m_push->body, m_push->force, point);
        if (--m_push->steps_left == 0)
            m_push.reset();
    }
    apply_mould();
}

void EditorSession::step(int count)
{
    if (!m_world)
        return;
    end_mode_animation();
    for (int i = 0; i < count; ++i)
        m_world->step(); // the step listener applies the loads
    record_last_step();
}

int EditorSession::frame(double real_seconds)
{
    if (m_animation && real_seconds > 0.0) {
        m_animation->time += real_seconds; // the world holds still: no step runs
        apply_mode_animation();
        return 0;
    }
    if (!m_world || !m_playing || !(real_seconds > 0.0))
        return 0;
    const int steps = m_world->advance(real_seconds);
    record_last_step();
    return steps;
}

EditorSession::EditorSession(EditorSession&& other) noexcept
{
    *this = std::move(other);
}

// Every member moves; only the world's step listener is pointed at the new session.
EditorSession& EditorSession::operator=(EditorSession&& other) noexcept
{
    if (this == &other)
        return *this;
    m_scene = std::move(other.m_scene);
    m_world = std::move(other.m_world);
    other.m_world.reset();
    m_drag = std::move(other.m_drag);
    m_push = std::move(other.m_push);
    m_mould = std::move(other.m_mould);
    m_mould_reached = other.m_mould_reached;
    m_step_ms = std::move(other.m_step_ms);
    m_step_pending = other.m_step_pending;
    m_steps_run = other.m_steps_run;
    m_playing = other.m_playing;
    m_generation = other.m_generation;
    m_loads = other.m_loads;
    m_history = std::move(other.m_history);
    m_history_position = other.m_history_position;
    m_last_effect = other.m_last_effect;
    m_animation = std::move(other.m_animation);
    m_animation_start = std::move(other.m_animation_start);
    m_animation_q = std::move(other.m_animation_q);
    m_animation_v = std::move(other.m_animation_v);
    m_animation_was_playing = other.m_animation_was_playing;
    other.m_animation.reset();
    if (m_world)
        attach_step_listener();
    return *this;
}

void EditorSession::attach_step_listener()
{
    world_set_step_listener(
        *m_world, [](World&, void* session) { static_cast<EditorSession*>(session)->before_step(); }, this);
}

// Before each step, however it is run (Step, a played frame, a script): the drag spring, pushes and
// moulding act on every step, and the last step's time joins the window.
void EditorSession::before_step()
{
    record_last_step();
    apply_loads();
    ++m_steps_run;
    m_step_pending = true;
}

void EditorSession::record_last_step()
{
    if (!m_step_pending || !m_world)
        return;
    m_step_pending = false;
    m_step_ms.push_back(m_world->profile().total_ms);
    if (m_step_ms.size() > k_timing_window)
        m_step_ms.pop_front();
}

double EditorSession::ms_per_step() const
{
    if (m_step_ms.empty())
        return 0.0;
    return std::accumulate(m_step_ms.begin(), m_step_ms.end(), 0.0) / static_cast<double>(m_step_ms.size());
}

Status EditorSession::save(const std::string& path, bool current_state) const
{
    Scene out = m_scene;
    if (current_state && m_world)
        if (Status status = refresh_scene_from_world(out, *m_world); !status)
            return status;
    return save_scene(out, path);
}

Status EditorSession::rebuild_keeping_state(const Scene& edited, const std::vector<size_t>& moved)
{
    end_mode_animation();
    Scene running = edited;
    // Bodies keep where they are and how they move; a renamed body starts from its scene pose.
    if (m_world)
        (void)refresh_scene_from_world(running, *m_world, /*include_shapes=*/false);
    // A moved body goes where the edit put it (in its parent's frame for a part); its own parts keep
    // their poses relative to it, so they come along, and its joints are made at the new pose.
    for (size_t i : moved) {
        running.bodies[i].def.position = edited.bodies[i].def.position;
        running.bodies[i].def.orientation = edited.bodies[i].def.orientation;
    }
    share_bases(running);
    Result<World> world = build_world(running);
    if (!world)
        return world.error();
    m_world.emplace(std::move(*world));
    attach_step_listener();
    m_drag.reset();
    m_push.reset();
    m_mould.reset();
    return {};
}

} // namespace supermodal::editor
