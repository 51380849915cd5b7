// SPDX-License-Identifier: MIT
#include "supermodal/body.h"

#include "core/assert.h"
#include "supermodal/modal.h"
#include "supermodal/world.h"
#include "world/modal_system.h"
#include "world/world_impl.h"

#include <algorithm>
#include <cmath>

namespace supermodal
{
namespace
{

const std::string k_no_name;
const ShapeDef k_no_shape{};
const MassProperties k_no_mass{};

bool same_shape(const ShapeDef& a, const ShapeDef& b)
{
    auto same_terms = [&] {
        for (size_t i = 0; i < a.terms.size(); ++i)
            if (!(a.terms[i].normal == b.terms[i].normal && a.terms[i].offset == b.terms[i].offset &&
                  a.terms[i].exponent == b.terms[i].exponent))
                return false;
        return true;
    };
    return a.type == b.type && a.radii == b.radii && a.epsilon1 == b.epsilon1 && a.epsilon2 == b.epsilon2 &&
           a.taper.kx == b.taper.kx && a.taper.ky == b.taper.ky && a.bend.curvature == b.bend.curvature &&
           a.bend.angle == b.bend.angle && a.plane_normal == b.plane_normal &&
           a.plane_offset == b.plane_offset && a.terms.size() == b.terms.size() && same_terms();
}

// Looks up a live body; asserts (and returns null) on a stale or foreign handle.
const World::Impl* live(const World& world, Entity e)
{
    const World::Impl& w = impl_of(world);
    const bool ok = w.reg.valid(e) && w.reg.has<BodyModel>(e);
    SM_ASSERT(ok, "stale or null body handle");
    return ok ? &w : nullptr;
}
World::Impl* live_mut(World& world, Entity e)
{
    World::Impl& w = impl_of(world);
    const bool ok = w.reg.valid(e) && w.reg.has<BodyModel>(e);
    SM_ASSERT(ok, "stale or null body handle");
    SM_ASSERT(!w.locked, "bodies cannot change while the world steps");
    if (!ok || w.locked)
        return nullptr;
    // Every edit of a body wakes its island: a sleeping body would ignore it.
    wake_island_of(w.reg, w.contact, e);
    return &w;
}

bool finite_def(const BodyDef& d)
{
    return is_finite(d.position) && is_finite(d.orientation) && is_finite(d.linear_velocity) &&
           is_finite(d.angular_velocity) && std::isfinite(d.gravity_scale);
}

} // namespace

void set_mass_model(BodyModel& model, const ShapeDef& shape, double density)
{
    model.mass = compute_mass_properties(shape, density);
    model.inv_mass = 0.0;
    model.inertia_body = model.inv_inertia_body = Vec3{};
    model.principal = Quat::identity();
    if (model.motion == MotionType::Dynamic) {
        model.inv_mass = 1.0 / model.mass.mass;
        model.inertia_body = model.mass.inertia_diagonal;
        const Vec3& i = model.inertia_body;
        model.inv_inertia_body = {1.0 / i.x, 1.0 / i.y, 1.0 / i.z};
        // The pose stays the shape frame the user placed; inertia lives in the principal frame.
        model.principal = normalized(model.mass.principal_axes);
    }
}

// Colliders are built once per distinct shape and shared: a pile of identical bodies holds one sample set.
// An auto body (sampling_tolerance > 0) whose scene leaves the spacing automatic gets the coarsest
// spacing whose measured sampling gap stays within the tolerance (measured once per shape: 16-33 ms in
// Release).
std::shared_ptr<const Collider> collider_for(World::Impl& w, const ShapeDef& shape, const Vec3& com,
                                             double sampling_tolerance)
{
    const int max_samples = w.def.contact.max_samples_per_body;
    if (w.def.contact.sample_spacing > 0.0 || shape.type == ShapeType::Plane)
        sampling_tolerance = 0.0;
    for (const auto& c : w.colliders)
        if (same_shape(c->shape, shape) && c->com_shape == com && c->sampling_tolerance == sampling_tolerance)
            return c;
    std::shared_ptr<const Collider> c;
    if (sampling_tolerance > 0.0) {
        const SampleDensityChoice choice = choose_sample_spacing(shape, sampling_tolerance, max_samples);
        Collider made = make_collider(shape, com, choice.spacing, max_samples);
        made.sampling_tolerance = sampling_tolerance;
        made.sampling = choice;
        c = std::make_shared<const Collider>(std::move(made));
    } else {
        c = std::make_shared<const Collider>(
            make_collider(shape, com, w.def.contact.sample_spacing, max_samples));
    }
    w.colliders.push_back(c);
    return c;
}

BodyDef default_body_def()
{
    return BodyDef{};
}

Status validate(const BodyDef& def)
{
    if (Status s = validate(def.shape); !s)
        return s;
    if (def.shape.type == ShapeType::Plane && def.motion != MotionType::Static)
        return Error{"", "motion", "a plane must be static"};
    if (def.motion == MotionType::Dynamic && (!(def.density > 0.0) || !std::isfinite(def.density)))
        return Error{"", "density", "expected a finite density > 0 kg/m^3"};
    if (!(def.friction >= 0.0) || !std::isfinite(def.friction))
        return Error{"", "friction", "expected a finite friction coefficient >= 0"};
    if (!(def.restitution >= 0.0 && def.restitution <= 1.0))
        return Error{"", "restitution", "expected a restitution in [0, 1]"};
    if (!(def.young > 0.0) || !std::isfinite(def.young))
        return Error{"", "young", "expected a finite Young's modulus > 0 Pa"};
    if (!(def.poisson > -1.0 && def.poisson < 0.5))
        return Error{"", "poisson", "expected a Poisson's ratio in (-1, 0.5)"};
    if (!(def.rolling_resistance >= 0.0) || !std::isfinite(def.rolling_resistance))
        return Error{"", "rolling_resistance", "expected a finite rolling resistance >= 0 m"};
    if (!finite_def(def))
        return Error{"", "pose", "expected finite position, orientation, velocities and gravity scale"};
    if (norm(def.orientation) == 0.0)
        return Error{"", "orientation", "orientation quaternion has zero length"};
    if (def.modal.enabled) {
        if (def.motion != MotionType::Dynamic)
            return Error{"", "modal", "modal dynamics need a dynamic body"};
        if (!(def.modal.damping_ratio >= 0.0) || !std::isfinite(def.modal.damping_ratio))
            return Error{"", "modal/damping_ratio", "expected a finite damping ratio >= 0"};
        if (!(def.modal.yield_stress > 0.0)) // NaN fails too; +∞ means elastic
            return Error{"", "modal/yield_stress", "expected a yield stress > 0 Pa (infinity: elastic)"};
        if (!(def.modal.hardening >= 0.0) || !std::isfinite(def.modal.hardening))
            return Error{"", "modal/hardening", "expected a finite hardening modulus >= 0 Pa"};
        if (!(def.modal.max_plastic_strain > 0.0))
            return Error{"", "modal/max_plastic_strain",
                         "expected a plastic strain limit > 0 (infinity: none)"};
        if (!(def.modal.adaptive_tolerance >= 0.0) || !std::isfinite(def.modal.adaptive_tolerance))
            return Error{"", "modal/adaptive_tolerance", "expected a finite displacement tolerance >= 0 m"};
        if (!(def.modal.remould_threshold >= 0.0) || !std::isfinite(def.modal.remould_threshold))
            return Error{"", "modal/remould_threshold",
                         "expected a finite rest-shape change >= 0 (0: never)"};
        if (def.modal.remould_delay_steps < 1 || def.modal.remould_delay_steps > 1000)
            return Error{"", "modal/remould_delay_steps", "expected a step count in [1, 1000]"};
        if (def.modal.adaptive_tolerance > 0.0 && def.modal.mode_count == k_all_modes)
            return Error{"", "modal/mode_count",
                         "adaptive modes need a mode count in [1, 256], not every mode"};
        if (Status s = validate(modal_basis_def(def)); !s)
            return Error{"", "modal" + s.error().where, s.error().what};
    }
    return {};
}

Entity create_body(World& world, const BodyDef& def)
{
    World::Impl& w = impl_of(world);
    const Status status = validate(def);
    SM_ASSERT(status.ok(), "invalid BodyDef (call validate() for the reason)");
    SM_ASSERT(!w.locked, "bodies cannot be created while the world steps");
    if (!status || w.locked)
        return Entity{};
    modal::LatticeChoice lattice;
    if (def.modal.enabled) {
        Result<modal::LatticeChoice> built = find_or_build_modal_basis(w, def);
        SM_ASSERT(built.has_value(), "modal basis build failed (modal_basis_for() gives the reason)");
        if (!built)
            return Entity{};
        lattice = std::move(*built);
    }
    const Entity e = w.reg.create();
    BodyModel model;
    model.name = def.name;
    model.motion = def.motion;
    model.shape = def.shape;
    model.gravity_scale = def.gravity_scale;
    set_mass_model(model, def.shape, def.density);
    model.friction = def.friction;
    model.restitution = def.restitution;
    model.rolling_resistance = def.rolling_resistance;
    model.allow_sleep = def.allow_sleep;
    model.contact_compliance = (1.0 - def.poisson * def.poisson) / def.young;
    // Hertz needs the curvature at the contact; the smallest radius bounds it for convex bodies (exact
    // for spheres, and the stiffer choice elsewhere).
    model.curvature = def.shape.type == ShapeType::Plane
                          ? 0.0
                          : 1.0 / std::min({def.shape.radii.x, def.shape.radii.y, def.shape.radii.z});
    // An auto body's samples get a share of its displacement budget, as its left-out modes do.
    const double sampling_tolerance =
        def.modal.enabled ? k_sampling_share_of_budget * def.modal.adaptive_tolerance : 0.0;
    model.collider = collider_for(w, def.shape, model.mass.center_of_mass, sampling_tolerance);
    const Quat q = normalized(def.orientation);
    w.reg.emplace(e, std::move(model));
    const BodyModel& placed = w.reg.get<BodyModel>(e);
    // Pose tracks the centre of mass; the public position is the shape origin (they differ when a
    // taper or bend moves the centre of mass off the shape's origin).
    const Vec3 com = def.position + rotate(q, placed.mass.center_of_mass);
    w.reg.emplace(e, Pose{com, q, com, q});
    w.reg.emplace(e, Velocity{def.motion == MotionType::Static ? Vec3{} : def.linear_velocity,
                              def.motion == MotionType::Static ? Vec3{} : def.angular_velocity});
    w.reg.emplace(e, ForceAccumulator{});
    w.reg.emplace(e, Sleep{});
    if (lattice.basis)
        attach_modal_body(w, e, lattice, def);
    return e;
}

void destroy_body(World& world, Entity body)
{
    if (World::Impl* w = live_mut(world, body)) {
        drop_constraints_of(w->constraints, body); // a joint to nothing would pull towards a stale pose
        w->reg.destroy(body);
    }
}

bool world_valid(const World& world, Entity body)
{
    return impl_of(world).reg.valid(body) && impl_of(world).reg.has<BodyModel>(body);
}

std::vector<Entity> world_bodies(const World& world)
{
    std::vector<Entity> out;
    const Registry& reg = impl_of(world).reg;
    reg.pool().for_each_alive([&](Entity e) {
        if (reg.has<BodyModel>(e))
            out.push_back(e);
    });
    return out;
}

Entity find_body(const World& world, std::string_view name)
{
    for (Entity e : world_bodies(world))
        if (impl_of(world).reg.get<BodyModel>(e).name == name)
            return e;
    return Entity{};
}

const std::string& body_name(const World& world, Entity e)
{
    const World::Impl* w = live(world, e);
    return w ? w->reg.get<BodyModel>(e).name : k_no_name;
}
MotionType body_motion(const World& world, Entity e)
{
    const World::Impl* w = live(world, e);
    return w ? w->reg.get<BodyModel>(e).motion : MotionType::Static;
}
const ShapeDef& body_shape(const World& world, Entity e)
{
    const World::Impl* w = live(world, e);
    return w ? w->reg.get<BodyModel>(e).shape : k_no_shape;
}
const MassProperties& body_mass_properties(const World& world, Entity e)
{
    const World::Impl* w = live(world, e);
    return w ? w->reg.get<BodyModel>(e).mass : k_no_mass;
}
Vec3 body_position(const World& world, Entity e)
{
    const World::Impl* w = live(world, e);
    if (!w)
        return {};
    const Pose& p = w->reg.get<Pose>(e);
    return p.position - rotate(p.orientation, w->reg.get<BodyModel>(e).mass.center_of_mass);
}
Vec3 body_center_of_mass(const World& world, Entity e)
{
    const World::Impl* w = live(world, e);
    return w ? w->reg.get<Pose>(e).position : Vec3{};
}
Quat body_orientation(const World& world, Entity e)
{
    const World::Impl* w = live(world, e);
    return w ? w->reg.get<Pose>(e).orientation : Quat{};
}
Vec3 body_linear_velocity(const World& world, Entity e)
{
    const World::Impl* w = live(world, e);
    return w ? w->reg.get<Velocity>(e).linear : Vec3{};
}
Vec3 body_angular_velocity(const World& world, Entity e)
{
    const World::Impl* w = live(world, e);
    return w ? w->reg.get<Velocity>(e).angular : Vec3{};
}
Vec3 body_angular_momentum(const World& world, Entity e)
{
    const World::Impl* w = live(world, e);
    if (!w)
        return {};
    const BodyModel& m = w->reg.get<BodyModel>(e);
    const Quat q = principal_orientation(m, w->reg.get<Pose>(e).orientation);
    const Vec3 w_body = inv_rotate(q, w->reg.get<Velocity>(e).angular);
    return rotate(q, hadamard(m.inertia_body, w_body));
}
double body_kinetic_energy(const World& world, Entity e)
{
    const World::Impl* w = live(world, e);
    if (!w || w->reg.get<BodyModel>(e).motion != MotionType::Dynamic)
        return 0.0;
    const BodyModel& m = w->reg.get<BodyModel>(e);
    const Velocity& v = w->reg.get<Velocity>(e);
    const Vec3 w_body = inv_rotate(principal_orientation(m, w->reg.get<Pose>(e).orientation), v.angular);
    return 0.5 * m.mass.mass * dot(v.linear, v.linear) + 0.5 * dot(w_body, hadamard(m.inertia_body, w_body));
}
double body_potential_energy(const World& world, Entity e)
{
    const World::Impl* w = live(world, e);
    if (!w || w->reg.get<BodyModel>(e).motion != MotionType::Dynamic)
        return 0.0;
    const BodyModel& m = w->reg.get<BodyModel>(e);
    return -m.mass.mass * m.gravity_scale * dot(w->def.gravity, w->reg.get<Pose>(e).position);
}
Vec3 body_interpolated_position(const World& world, Entity e)
{
    const World::Impl* w = live(world, e);
    if (!w)
        return {};
    const Pose& p = w->reg.get<Pose>(e);
    const double a = world.interpolation_alpha();
    const Vec3 com = w->reg.get<BodyModel>(e).mass.center_of_mass;
    return (1.0 - a) * (p.prev_position - rotate(p.prev_orientation, com)) +
           a * (p.position - rotate(p.orientation, com));
}
Quat body_interpolated_orientation(const World& world, Entity e)
{
    const World::Impl* w = live(world, e);
    if (!w)
        return {};
    const Pose& p = w->reg.get<Pose>(e);
    const double a = world.interpolation_alpha();
    // Normalised lerp along the shorter arc: close enough to slerp for one step's rotation.
    const Quat& q0 = p.prev_orientation;
    const Quat& q1 = p.orientation;
    const double sign = (q0.w * q1.w + q0.x * q1.x + q0.y * q1.y + q0.z * q1.z) < 0.0 ? -1.0 : 1.0;
    return normalized(Quat{(1 - a) * q0.w + a * sign * q1.w, (1 - a) * q0.x + a * sign * q1.x,
                           (1 - a) * q0.y + a * sign * q1.y, (1 - a) * q0.z + a * sign * q1.z});
}

void set_body_position(World& world, Entity e, const Vec3& position)
{
    SM_ASSERT(is_finite(position), "position must be finite");
    if (World::Impl* w = live_mut(world, e); w && is_finite(position)) {
        Pose& p = w->reg.get<Pose>(e);
        // A teleport: nothing to interpolate across.
        p.position = p.prev_position =
            position + rotate(p.orientation, w->reg.get<BodyModel>(e).mass.center_of_mass);
    }
}
void set_body_orientation(World& world, Entity e, const Quat& orientation)
{
    SM_ASSERT(is_finite(orientation) && norm(orientation) > 0.0, "orientation must be finite and non-zero");
    if (World::Impl* w = live_mut(world, e); w && is_finite(orientation) && norm(orientation) > 0.0) {
        // Turns about the shape origin, which stays where it was.
        Pose& p = w->reg.get<Pose>(e);
        const Vec3 com = w->reg.get<BodyModel>(e).mass.center_of_mass;
        const Vec3 origin = p.position - rotate(p.orientation, com);
        p.orientation = p.prev_orientation = normalized(orientation);
        p.position = p.prev_position = origin + rotate(p.orientation, com);
    }
}
void set_body_linear_velocity(World& world, Entity e, const Vec3& velocity)
{
    SM_ASSERT(is_finite(velocity), "velocity must be finite");
    if (World::Impl* w = live_mut(world, e);
        w && is_finite(velocity) && w->reg.get<BodyModel>(e).motion != MotionType::Static)
        w->reg.get<Velocity>(e).linear = velocity;
}
void set_body_angular_velocity(World& world, Entity e, const Vec3& angular_velocity)
{
    SM_ASSERT(is_finite(angular_velocity), "angular velocity must be finite");
    if (World::Impl* w = live_mut(world, e);
        w && is_finite(angular_velocity) && w->reg.get<BodyModel>(e).motion != MotionType::Static)
        w->reg.get<Velocity>(e).angular = angular_velocity;
}

void apply_force(World& world, Entity e, const Vec3& force, const Vec3& point)
{
    if (World::Impl* w = live_mut(world, e)) {
        ForceAccumulator& acc = w->reg.get<ForceAccumulator>(e);
        acc.force += force;
        acc.torque += cross(point - w->reg.get<Pose>(e).position, force);
        modal_add_host_load(w->reg, e, point, force);
    }
}
void apply_force_at_center(World& world, Entity e, const Vec3& force)
{
    if (World::Impl* w = live_mut(world, e))
        w->reg.get<ForceAccumulator>(e).force += force;
}
void apply_torque(World& world, Entity e, const Vec3& torque)
{
    if (World::Impl* w = live_mut(world, e))
        w->reg.get<ForceAccumulator>(e).torque += torque;
}
void apply_linear_impulse(World& world, Entity e, const Vec3& impulse, const Vec3& point)
{
    World::Impl* w = live_mut(world, e);
    if (!w || w->reg.get<BodyModel>(e).motion != MotionType::Dynamic)
        return;
    w->reg.get<Velocity>(e).linear += w->reg.get<BodyModel>(e).inv_mass * impulse;
    apply_angular_impulse(world, e, cross(point - w->reg.get<Pose>(e).position, impulse));
    modal_add_point_impulse(w->reg, e, point, impulse);
}
void apply_angular_impulse(World& world, Entity e, const Vec3& impulse)
{
    World::Impl* w = live_mut(world, e);
    if (!w || w->reg.get<BodyModel>(e).motion != MotionType::Dynamic)
        return;
    const BodyModel& m = w->reg.get<BodyModel>(e);
    const Quat q = principal_orientation(m, w->reg.get<Pose>(e).orientation);
    w->reg.get<Velocity>(e).angular += rotate(q, hadamard(m.inv_inertia_body, inv_rotate(q, impulse)));
}

bool body_is_awake(const World& world, Entity e)
{
    const World::Impl* w = live(world, e);
    return w != nullptr && !is_asleep(w->reg, e);
}
void wake_body(World& world, Entity e)
{
    (void)live_mut(world, e); // wakes its island
}
size_t world_sleeping_count(const World& world)
{
    size_t n = 0;
    for (const Sleep& s : impl_of(world).reg.store<Sleep>().values())
        n += s.asleep ? 1 : 0;
    return n;
}

} // namespace supermodal
