// Helpers shared by tests: small worlds built in code.
#pragma once

#include "supermodal/assert.h"
#include "supermodal/body.h"
#include "supermodal/modal.h"
#include "supermodal/world.h"

#include <array>
#include <cmath>

namespace supermodal::test
{

/// A dynamic superquadric body with the given radii [m], density [kg/m³] and pose.
inline BodyDef ellipsoid_def(Vec3 radii, Vec3 position = {}, double density = 1000.0)
{
    BodyDef def = default_body_def();
    def.shape.radii = radii;
    def.position = position;
    def.density = density;
    return def;
}

/// A static ground: the plane y = 0, normal +y.
inline Entity add_ground(World& world)
{
    BodyDef def = default_body_def();
    def.motion = MotionType::Static;
    def.shape.type = ShapeType::Plane;
    def.shape.plane_normal = {0, 1, 0};
    return create_body(world, def);
}

/// The soft modal ball of the modal tests and benchmarks: radius 0.3 m, density 1000 kg/m³, E = 200 kPa
/// (first mode 11.6 Hz), the given damping ratio [-], position [m] and otherwise default modal settings.
inline BodyDef soft_ball_def(Vec3 position, double damping_ratio)
{
    BodyDef def = default_body_def();
    def.shape.radii = {0.3, 0.3, 0.3};
    def.position = position;
    def.modal.enabled = true;
    def.young = 2e5;
    def.modal.damping_ratio = damping_ratio;
    return def;
}

/// The soft ellipsoid of the modal trade (docs/modal.md): 0.6 × 0.4 × 0.3 m, E 1 MPa, ν 0.3, ρ 1000 kg/m³,
/// r modes of a lattice of 20-node cells (6×4×3: 1335 dofs), damping ratio zeta [-], with or without the
/// static correction.
inline BodyDef soft_ellipsoid_def(int modes, double zeta, bool correction,
                                  std::array<int, 3> cells = {6, 4, 3})
{
    BodyDef def = default_body_def();
    def.shape.radii = {0.3, 0.2, 0.15};
    def.density = 1000.0;
    def.young = 1e6;
    def.poisson = 0.3;
    def.modal.enabled = true;
    def.modal.mode_count = modes;
    def.modal.lattice = cells;
    def.modal.damping_ratio = zeta;
    def.modal.static_correction = correction;
    return def;
}

/// Body-frame displacement [m] of a rest point (shape frame) of a body whose shape origin is its centre
/// of mass: where body_deformed_point puts it, back in the body frame, less where it was.
inline Vec3 body_frame_displacement(const World& world, Entity body, const Vec3& rest)
{
    const Vec3 p = body_deformed_point(world, body, rest);
    return inv_rotate(body_orientation(world, body), p - body_position(world, body)) - rest;
}

/// A static plane through offset·normal [m] with the given friction coefficient [-].
inline Entity add_plane(World& world, Vec3 normal, double offset = 0.0, double friction = 0.5)
{
    BodyDef def = default_body_def();
    def.motion = MotionType::Static;
    def.shape.type = ShapeType::Plane;
    def.shape.plane_normal = normal;
    def.shape.plane_offset = offset;
    def.friction = friction;
    return create_body(world, def);
}

/// A dynamic superquadric with both exponents eps [-], radii [m], pose, friction and restitution [-].
inline Entity add_superquadric(World& world, Vec3 radii, double eps, Vec3 position, Quat orientation,
                               double friction, double restitution, double density = 1000.0)
{
    BodyDef def = default_body_def();
    def.shape.radii = radii;
    def.shape.epsilon1 = def.shape.epsilon2 = eps;
    def.position = position;
    def.orientation = orientation;
    def.friction = friction;
    def.restitution = restitution;
    def.density = density;
    return create_body(world, def);
}

/// Rotation about z by angle [rad].
inline Quat about_z(double angle)
{
    return {std::cos(0.5 * angle), 0, 0, std::sin(0.5 * angle)};
}

/// Runs n fixed steps.
inline void run_steps(World& world, int n)
{
    for (int i = 0; i < n; ++i)
        world.step();
}

/// Counts assertion failures instead of aborting, while in scope.
class AssertCounter
{
  public:
    AssertCounter()
    {
        m_previous = set_assert_handler(&count);
        s_count = 0;
    }
    ~AssertCounter() { set_assert_handler(m_previous); }
    [[nodiscard]] int count() const { return s_count; }

  private:
    static bool count(const char*, const char*, const char*, int)
    {
        ++s_count;
        return false;
    }
    static inline int s_count = 0;
    AssertHandler m_previous = nullptr;
};

} // namespace supermodal::test
