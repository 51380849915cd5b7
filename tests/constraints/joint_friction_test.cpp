// Joint friction (ConstraintDef::angular_damping): a limb swinging on a ball joint slows at the rate
// asked for, whatever its inertia about its centre of mass (engine/src/constraints/solve.cpp).
#include "supermodal/body.h"
#include "supermodal/constraint.h"
#include "supermodal/world.h"
#include "support/world_fixture.h"

#include <cmath>
#include <gtest/gtest.h>

namespace sm = supermodal;
using sm::test::ellipsoid_def;

namespace
{

// Largest |ω| of the limb over the next `seconds`.
double peak_spin(sm::World& w, sm::Entity limb, double seconds)
{
    double peak = 0.0;
    const int steps = static_cast<int>(std::lround(seconds / w.settings().dt));
    for (int i = 0; i < steps; ++i) {
        w.step();
        peak = std::max(peak, sm::length(sm::body_angular_velocity(w, limb)));
    }
    return peak;
}

} // namespace

// A limb (radii 0.045 × 0.15 × 0.045 m) hangs from a static base by a ball joint at its top end and
// swings 0.1 rad. With friction torque −C·ω, C = γ·I_pivot, it is a damped pendulum
// θ'' + γθ' + ω0²θ = 0 (ω0 = √(m g d / I_pivot) = 7.3 rad/s, ζ = γ/2ω0 = 0.14 for γ = 2/s): the swing's
// envelope falls as e^(−γt/2), so peak spins two damped periods apart differ by e^(−γ·T_d). Tolerance
// 10%: the 60 Hz joint spring and the discrete step shift the period by under 1%, and a one-period
// window samples the peak to ~1% at 4 substeps. Friction computed on the limb's inertia about its own
// centre (I_com = 0.18·I_pivot here) decayed about five times slower.
TEST(JointFriction, SwingingLimbSlowsAtTheRateAsked)
{
    sm::WorldDef def = sm::default_world_def();
    def.dt = 1e-3;
    def.substep_count = 4;
    def.contact.enabled = false;
    sm::World w(def);
    sm::BodyDef base = ellipsoid_def({0.05, 0.05, 0.05}, {0, 2, 0});
    base.motion = sm::MotionType::Static;
    const sm::Entity b = sm::create_body(w, base);
    const sm::Entity limb = sm::create_body(w, ellipsoid_def({0.045, 0.15, 0.045}, {0, 1.7, 0}));
    sm::ConstraintDef c = sm::default_constraint_def();
    c.a = b;
    c.b = limb;
    c.anchor_a.point = {0, -0.15, 0}; // at y = 1.85, the limb's top end
    c.anchor_b.point = {0, 0.15, 0};
    c.frequency_hz = 60.0;
    c.damping_ratio = 1.0;
    const double gamma = 2.0;
    c.angular_damping = gamma;
    (void)sm::create_constraint(w, c);
    // Swing it: 0.1 rad about z at the bottom of the arc, as an angular speed θ0·ω0 about the top end.
    const double mass = sm::body_mass_properties(w, limb).mass;
    const double i_pivot = sm::body_mass_properties(w, limb).inertia_diagonal.x + mass * 0.15 * 0.15;
    const double w0 = std::sqrt(mass * 9.81 * 0.15 / i_pivot);
    const double wd = w0 * std::sqrt(1.0 - (gamma / (2.0 * w0)) * (gamma / (2.0 * w0)));
    const double period = 2.0 * M_PI / wd;
    const sm::Vec3 spin{0, 0, 0.1 * w0};
    sm::set_body_angular_velocity(w, limb, spin);
    sm::set_body_linear_velocity(w, limb, sm::cross(spin, sm::Vec3{0, -0.15, 0}));
    const double first = peak_spin(w, limb, period);
    (void)peak_spin(w, limb, period);
    const double third = peak_spin(w, limb, period);
    const double expected = std::exp(-gamma * period);
    EXPECT_NEAR(third / first, expected, 0.1 * expected) << "first " << first << " third " << third;
}
