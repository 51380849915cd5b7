// Tests for ContactStiffness::Material (engine/src/contact/penalty.cpp): Hertz contact from the bodies'
// Young's moduli, against the static Hertz indentation δ = (3F / (4·E*·√R))^(2/3).
#include "supermodal/body.h"
#include "supermodal/contact.h"
#include "supermodal/world.h"
#include "support/world_fixture.h"

#include <algorithm>
#include <cmath>
#include <gtest/gtest.h>
#include <numbers>

namespace sm = supermodal;
using sm::test::run_steps;

namespace
{

constexpr double k_g = 9.81;
constexpr double k_radius = 0.05; // [m]

sm::World make_world(double dt, sm::ContactStiffness stiffness)
{
    sm::WorldDef def = sm::default_world_def();
    def.dt = dt;
    def.contact.solver = sm::ContactSolver::Penalty; // Hertz stiffness is the penalty solver's
    def.contact.stiffness = stiffness;
    def.contact.path = sm::ContactPath::SupportMap; // one point: the sphere–plane Hertz case exactly
    return sm::World(def);
}

void add_floor(sm::World& w, double young)
{
    sm::BodyDef d = sm::default_body_def();
    d.motion = sm::MotionType::Static;
    d.shape.type = sm::ShapeType::Plane;
    d.young = young;
    (void)sm::create_body(w, d);
}

// The ball starts at rest sunk `depth` into the floor, with restitution 1 (no dashpot): where the
// spring carries its weight exactly it stays; a wrong stiffness makes it oscillate about another depth.
// (With a dashpot the explicit step shifts the rest depth: it sees each substep's gravity kick as an
// approach speed g·h and carries c·g·h of the weight, so the dashpot is off to test the spring alone.)
sm::Entity add_ball(sm::World& w, double young, double poisson, double depth)
{
    sm::BodyDef d = sm::default_body_def();
    d.shape.radii = {k_radius, k_radius, k_radius};
    d.position = {0, k_radius - depth, 0};
    d.young = young;
    d.poisson = poisson;
    d.restitution = 1.0;
    return sm::create_body(w, d);
}

// Mean and largest deviation from `depth` of the ball's depth over n steps [m].
struct DepthStats {
    double mean = 0.0, max_deviation = 0.0;
};
DepthStats depth_over(sm::World& w, sm::Entity b, int n, double depth)
{
    DepthStats s;
    for (int i = 0; i < n; ++i) {
        w.step();
        const double d = k_radius - sm::body_position(w, b).y;
        s.mean += d / n;
        s.max_deviation = std::max(s.max_deviation, std::abs(d - depth));
    }
    return s;
}

double sphere_mass()
{
    return 1000.0 * 4.0 / 3.0 * std::numbers::pi * k_radius * k_radius * k_radius;
}

} // namespace

TEST(MaterialStiffness, SoftBallRestsAtTheHertzIndentation)
{
    // A rubber-like ball (E = 5 MPa, ν = 0.49, r = 5 cm, 0.524 kg) on a steel floor (E = 210 GPa):
    // E* = 6.58 MPa, δ = (3mg / (4E*·√r))^(2/3) = 0.190 mm, whose tangent rate √(1.5k/m) = 280 rad/s
    // is under the cap at 1 ms (628 rad/s), so nothing is clamped. Started there it stays: the
    // equilibrium is exact up to rounding (measured 2026-11-26: deviations of 1e-17 m), asserted to
    // 1e-6 of δ; a stiffness off by any factor makes the ball oscillate by that share of δ.
    sm::World w = make_world(0.001, sm::ContactStiffness::Material);
    add_floor(w, 210e9);
    const double e_star = 1.0 / ((1.0 - 0.49 * 0.49) / 5e6 + (1.0 - 0.09) / 210e9);
    const double hertz =
        std::pow(3.0 * sphere_mass() * k_g / (4.0 * e_star * std::sqrt(k_radius)), 2.0 / 3.0);
    const sm::Entity b = add_ball(w, 5e6, 0.49, hertz);
    const DepthStats s = depth_over(w, b, 1000, hertz);
    EXPECT_NEAR(s.mean, hertz, 1e-6 * hertz);
    EXPECT_LT(s.max_deviation, 1e-6 * hertz);
    EXPECT_EQ(w.warnings().contact_frequency_clamps, 0u);
}

TEST(MaterialStiffness, HertzStiffnessIsNotLinear)
{
    // Twice the weight (a ball of twice the density) sinks 2^(2/3) = 1.587 times deeper under Hertz;
    // a linear spring would give 2. Started at the Hertz depth of the heavier ball, it stays (1e-6).
    sm::World w = make_world(0.001, sm::ContactStiffness::Material);
    add_floor(w, 210e9);
    const double e_star = 1.0 / ((1.0 - 0.49 * 0.49) / 5e6 + (1.0 - 0.09) / 210e9);
    const double hertz =
        std::pow(3.0 * 2.0 * sphere_mass() * k_g / (4.0 * e_star * std::sqrt(k_radius)), 2.0 / 3.0);
    sm::BodyDef d = sm::default_body_def();
    d.shape.radii = {k_radius, k_radius, k_radius};
    d.position = {0, k_radius - hertz, 0};
    d.density = 2000.0;
    d.young = 5e6;
    d.poisson = 0.49;
    d.restitution = 1.0;
    const sm::Entity b = sm::create_body(w, d);
    const DepthStats s = depth_over(w, b, 1000, hertz);
    EXPECT_NEAR(s.mean, hertz, 1e-6 * hertz);
    EXPECT_LT(s.max_deviation, 1e-6 * hertz);
}

TEST(MaterialStiffness, StiffBallIsClampedToTheStabilityCapAndCounted)
{
    // Steel on steel would need ω ≈ 2.4e4 rad/s; at 1 ms the explicit step allows 628 rad/s. The
    // spring is cut to the cap (tangent 1.5k = m·ω_cap²) and each cut counted: the ball rests at
    // δ = 1.5·g/ω_cap² = 0.0373 mm (secant k = m·ω_cap²/1.5), finite, not at Hertz's 2.6 µm.
    sm::World w = make_world(0.001, sm::ContactStiffness::Material);
    add_floor(w, 210e9);
    const double omega_cap = 2.0 * std::numbers::pi / (10.0 * 0.001);
    const double expected = 1.5 * k_g / (omega_cap * omega_cap);
    const sm::Entity b = add_ball(w, 210e9, 0.3, expected);
    const DepthStats s = depth_over(w, b, 1000, expected);
    EXPECT_NEAR(s.mean, expected, 1e-6 * expected);
    EXPECT_LT(s.max_deviation, 1e-6 * expected);
    EXPECT_GT(w.warnings().contact_frequency_clamps, 0u);
}

TEST(MaterialStiffness, FrequencyModeIgnoresTheMaterial)
{
    // The default mode: the ball sinks to the same depth whatever its Young modulus, bit for bit.

    double depths[2];
    const double youngs[2] = {5e6, 210e9};
    for (int i = 0; i < 2; ++i) {
        sm::World w = make_world(0.001, sm::ContactStiffness::Frequency);
        add_floor(w, 210e9);
        const sm::Entity b = add_ball(w, youngs[i], 0.3, 0.0);
        run_steps(w, 2000);
        depths[i] = k_radius - sm::body_position(w, b).y;
    }
    EXPECT_EQ(depths[0], depths[1]);
}

TEST(MaterialStiffness, BodyDefRefusesABadModulus)
{
    sm::BodyDef d = sm::default_body_def();
    d.young = 0.0;
    EXPECT_FALSE(sm::validate(d));
    d.young = 1e9;
    d.poisson = 0.5;
    EXPECT_FALSE(sm::validate(d));
}
