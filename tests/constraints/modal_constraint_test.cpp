// Constraints on modal bodies act through the modes at the anchor (engine/src/constraints/side.cpp,
// engine/src/modal/constraint_coupling.cpp): a welded 2x4 board bends like a cantilever, a joint at its
// tip drags its modes, energy does not grow, and the result does not depend on the thread count.
#include "modal/modal_scenes.h"
#include "supermodal/body.h"
#include "supermodal/constraint.h"
#include "supermodal/modal.h"
#include "supermodal/world.h"

#include <cmath>
#include <cstdio>
#include <gtest/gtest.h>
#include <utility>
#include <vector>

namespace sm = supermodal;
using sm::test::k_board_length;
using sm::test::k_board_thickness;
using sm::test::k_board_width;

namespace
{

constexpr double k_young = 11e9;
const sm::Vec3 k_root{-k_board_length / 2, 0, 0}, k_tip{k_board_length / 2, 0, 0};

sm::World make_world(double dt, int threads = 1)
{
    sm::WorldDef def = sm::default_world_def();
    def.dt = dt;
    def.gravity = {};
    def.contact.enabled = false; // the springs and the modes alone
    def.thread_count = threads;
    return sm::World(def);
}

// The 2x4 board of tests/modal/modal_scenes.h (length along x, thickness along y), free, at the origin.
sm::Entity add_board(sm::World& w, int modes, double zeta)
{
    sm::BodyDef def = sm::default_body_def();
    def.shape = sm::test::board_def({0, 0, 0}).shape;
    def.density = 450.0;
    def.modal.enabled = true;
    def.modal.mode_count = modes;
    // The lattice these tests' figures were measured on (16 × 3 × 3, the default, has more torsion and
    // edgewise modes among the lowest 24: a free-free Ritz cantilever 11% short of Euler–Bernoulli).
    def.modal.lattice = {8, 1, 1};
    def.young = k_young;
    def.poisson = 0.3;
    def.modal.damping_ratio = zeta;
    return sm::create_body(w, def);
}

std::vector<double> unit(int r, int k)
{
    std::vector<double> u(static_cast<size_t>(r), 0.0);
    u[static_cast<size_t>(k)] = 1.0;
    return u;
}

// ψ_k = ½∇×φ_k at p by central differences of the public field (independent of the engine's own).
sm::Vec3 rotation_of_mode(const sm::ModalBasis& basis, const sm::Vec3& p, int k)
{
    const std::vector<double> q = unit(basis.mode_count, k);
    const double d = 1e-5;
    sm::Vec3 g[3];
    for (int j = 0; j < 3; ++j) {
        sm::Vec3 lo = p, hi = p;
        hi[j] += d;
        // One-sided along x at the board's ends (outside the lattice the field is clamped), central else.
        if (j != 0 || std::abs(p.x) < k_board_length / 2 - d)
            lo[j] -= d;
        else if (p.x > 0)
            std::swap(lo, hi), lo[j] -= d;
        g[j] =
            (sm::modal_displacement(basis, hi, q) - sm::modal_displacement(basis, lo, q)) / (hi[j] - lo[j]);
    }
    return 0.5 * sm::Vec3{g[1].z - g[2].y, g[2].x - g[0].z, g[0].y - g[1].x};
}

// Static tip deflection of the board clamped at the root in the space the world can represent (rigid
// motion plus the retained modes): the Ritz solution. With λ = −f and μ = −(tip − root) × f the
// clamp's reactions, ω_k² q_k = φ_k(tip)·f + φ_k(root)·λ + ψ_k(root)·μ; the tip then moves by
// θ × (tip − root) + Φ(tip)q − Φ(root)q with θ = −Ψ(root)q the rigid rotation that holds the root.
double ritz_tip_deflection(const sm::ModalBasis& basis, const sm::Vec3& f)
{
    const sm::Vec3 lambda = -1.0 * f, mu = -1.0 * sm::cross(k_tip - k_root, f);
    std::vector<double> q(static_cast<size_t>(basis.mode_count));
    sm::Vec3 theta{};
    for (int k = 0; k < basis.mode_count; ++k) {
        const double w = 2.0 * M_PI * basis.frequencies_hz[static_cast<size_t>(k)];
        const std::vector<double> e = unit(basis.mode_count, k);
        const sm::Vec3 psi = rotation_of_mode(basis, k_root, k);
        q[static_cast<size_t>(k)] = (dot(sm::modal_displacement(basis, k_tip, e), f) +
                                     dot(sm::modal_displacement(basis, k_root, e), lambda) + dot(psi, mu)) /
                                    (w * w);
        theta += -q[static_cast<size_t>(k)] * psi;
    }
    const sm::Vec3 u = sm::cross(theta, k_tip - k_root) + sm::modal_displacement(basis, k_tip, q) -
                       sm::modal_displacement(basis, k_root, q);
    return u.y;
}

sm::ConstraintDef weld_root_to_world(sm::Entity board, double hz)
{
    sm::ConstraintDef c = sm::default_constraint_def();
    c.type = sm::ConstraintType::Weld;
    c.a = board;
    c.anchor_a.point = k_root;
    c.anchor_b.point = k_root; // the world point where the root is now
    c.frequency_hz = hz;
    c.damping_ratio = 1.0;
    return c;
}

// Pulls the board's tip with `force` [N], ramped over the first 500 steps and held to step 10000 (1 s
// at 0.1 ms); returns the tip's height 1000 steps before the end [m], to tell whether it settled.
double pull_tip(sm::World& w, sm::Entity board, const sm::Vec3& force)
{
    double tip_before = 0.0;
    for (int i = 0; i < 10000; ++i) {
        const double ramp = std::min(1.0, i / 500.0);
        sm::apply_force(w, board, ramp * force,
                        sm::body_position(w, board) + sm::rotate(sm::body_orientation(w, board), k_tip));
        w.step();
        if (i == 8999)
            tip_before = sm::body_deformed_point(w, board, k_tip).y;
    }
    return tip_before;
}

// Rigid kinetic energy plus the modes' elastic and kinetic energy [J].
double energy(const sm::World& w, sm::Entity board)
{
    return sm::body_kinetic_energy(w, board) + sm::body_modal_energy(w, board);
}

} // namespace

// A 2x4 board welded to the world at one end and pulled down by 10 N at the other bends like a
// cantilever: F L³/(3EI) = 0.745 mm by Euler–Bernoulli. The rigid board held by the same weld would
// not bend at all; a weld that held only the host's orientation would let the modes pivot at the root.
TEST(ModalConstraint, WeldedBoardBendsLikeACantilever)
{
    sm::World w = make_world(1e-4);
    const sm::Entity board = add_board(w, 24, 0.7);
    const sm::Constraint weld = sm::create_constraint(w, weld_root_to_world(board, 20000.0));
    const sm::Vec3 force{0, -10.0, 0};
    // Ramp the load over 50 ms, hold it to 1 s: the first cantilever mode (31 Hz, measured; 30.4 Hz by
    // Euler–Bernoulli) is damped only through the modes' ζ = 0.7 and settles within that (measured change
    // over the last 0.1 s: 1e-6 relative).
    const double tip_before = pull_tip(w, board, force);
    const double tip = sm::body_deformed_point(w, board, k_tip).y;
    const double root = sm::body_deformed_point(w, board, k_root).y;
    EXPECT_NEAR(tip, tip_before, 1e-4 * std::abs(tip)); // settled
    const sm::BodyModalState s = sm::body_modal_state(w, board);
    double q_norm = 0.0;
    for (double q : s.amplitudes)
        q_norm = std::max(q_norm, std::abs(q));
    EXPECT_GT(q_norm, 1e-5); // the modes carry the bending (measured 5e-5 √kg·m)

    // The weld holds the root: its spring stretches by F/(m_eff ω²) ≈ 1e-7 m at 20 kHz (stable at any
    // frequency: implicit).
    EXPECT_LT(std::abs(root), 1e-6);
    EXPECT_LT(sm::constraint_error(w, weld).linear, 1e-6);

    // Against the Ritz solution of the same modes (what the world can represent), which checks the
    // coupling itself: the weld's compliance (angular error 1e-6 rad, so 1 µm at the tip) and the
    // co-rotational frame's small rotation make up the difference (measured 0.5%): 1%.
    const sm::ModalBasis& basis = *sm::body_modal_basis(w, board);
    const double ritz = ritz_tip_deflection(basis, force);
    EXPECT_NEAR(tip - root, ritz, 0.01 * std::abs(ritz));

    // Against Euler–Bernoulli: free-free modes represent a clamped root only approximately and a Ritz
    // solution is stiffer than the beam: with these 24 modes the Ritz value is 4.3% short (12 modes:
    // 15%). Shear adds 0.1% (F L/(κGA)). Tolerance 6%.
    const double i_flat = k_board_width * std::pow(k_board_thickness, 3) / 12.0;
    const double beam = force.y * std::pow(k_board_length, 3) / (3.0 * k_young * i_flat);
    EXPECT_NEAR(tip - root, beam, 0.06 * std::abs(beam));
    std::printf("tip %.6e m, ritz %.6e m, Euler-Bernoulli %.6e m, max |q| %.3e\n", tip - root, ritz, beam,
                q_norm);
}

// The same board held at its root by a ball joint whose swing and twist limits are zero: the limits hold
// the material's rotation at the root, as the weld does, so the board bends like the same cantilever.
// Limits that acted on the body's frame alone never loaded the modes with their moment: the board
// barely bent (measured before: 1.1e-5 m, 1.5% of the Ritz deflection).
TEST(ModalConstraint, ZeroJointLimitsClampTheMaterialLikeAWeld)
{
    sm::World w = make_world(1e-4);
    const sm::Entity board = add_board(w, 24, 0.7);
    sm::ConstraintDef c = weld_root_to_world(board, 20000.0);
    c.type = sm::ConstraintType::Point;
    c.swing_limit = 0.0;
    c.twist_limit = 0.0;
    const sm::Constraint joint = sm::create_constraint(w, c);
    const sm::Vec3 force{0, -10.0, 0};
    // Ramped over 50 ms and held to 1 s, as above (settled: the last 0.1 s moves the tip by 1e-4 of it).
    const double tip_before = pull_tip(w, board, force);
    const double tip = sm::body_deformed_point(w, board, k_tip).y;
    const double root = sm::body_deformed_point(w, board, k_root).y;
    EXPECT_NEAR(tip, tip_before, 1e-4 * std::abs(tip));
    EXPECT_LT(std::abs(root), 1e-6);
    EXPECT_LT(sm::constraint_error(w, joint).linear, 1e-6);
    // The limits' springs are one-sided and scalar: each acts through the mass along its own axis,
    // 1/(aᵀKa) of the anchor's rotational compliance K, softer than the weld's full 3×3 spring, so the root
    // turns by more than the weld's 1e-6 rad under the 10 N·m moment (measured 1.2e-5 rad); bound 2e-5.
    const double angle = sm::constraint_error(w, joint).angular;
    EXPECT_LT(angle, 2e-5);
    // Against the same Ritz solution as the weld, 1%, plus what that turn moves the tip (angle × length).
    const double ritz = ritz_tip_deflection(*sm::body_modal_basis(w, board), force);
    EXPECT_NEAR(tip - root, ritz, 0.01 * std::abs(ritz) + angle * k_board_length);
    std::printf("limits at zero: tip %.6e m, ritz %.6e m, root turned %.3e rad\n", tip - root, ritz, angle);
}

// A ball joint from the tip of a free board to a world point 1 cm above it: the spring pulls the tip up
// and the board bends (the tip leads the rest of it), and the anchor, given as a direction from the
// centre, stays on the deformed surface.
TEST(ModalConstraint, JointAtTheTipDragsTheModes)
{
    sm::World w = make_world(1e-4);
    const sm::Entity board = add_board(w, 12, 0.02);
    sm::ConstraintDef c = sm::default_constraint_def();
    c.a = board;
    c.anchor_a.kind = sm::AnchorKind::Direction;
    c.anchor_a.direction = {1, 0, 0};
    c.anchor_b.point = k_tip + sm::Vec3{0, 0.01, 0};
    c.frequency_hz = 200.0;
    const sm::Constraint joint = sm::create_constraint(w, c);
    const sm::ModalBasis& basis = *sm::body_modal_basis(w, board);
    // The flatwise bending modes' share of the tip's motion, largest over the first 20 ms.
    double tip_modal = 0.0;
    for (int i = 0; i < 200; ++i) {
        w.step();
        const sm::BodyModalState s = sm::body_modal_state(w, board);
        tip_modal = std::max(tip_modal, sm::modal_displacement(basis, k_tip, s.amplitudes).y);
        // The anchor is the deformed material point at the end of the board (the ray's exit, 1e-9).
        const sm::Vec3 anchor = sm::constraint_anchors(w, joint).first;
        ASSERT_LT(sm::length(anchor - sm::body_deformed_point(w, board, k_tip)), 1e-9) << "step " << i;
    }
    // The pull bends the board towards it: the tip's modal displacement is up, a sizeable part of the
    // 1 cm pull (measured 1.9 mm at the peak; a constraint on the host alone leaves it exactly 0).
    EXPECT_GT(tip_modal, 1e-5);
    std::printf("peak modal tip displacement %.3e m\n", tip_modal);
}

// Undamped springs and modes: a board swinging about a joint at its tip in zero gravity. The implicit
// springs may only lose energy, with every mode coupled (dt 0.1 ms) or only the soft ones (1 ms, where
// the stiff modes pass ω h ≈ π).
TEST(ModalConstraint, UndampedEnergyDoesNotGrow)
{
    for (double dt : {1e-4, 1e-3}) {
        sm::World w = make_world(dt);
        const sm::Entity board = add_board(w, 12, 0.0);
        sm::ConstraintDef c = sm::default_constraint_def();
        c.a = board;
        c.anchor_a.point = k_tip;
        c.anchor_b.point = k_tip;
        c.frequency_hz = 100.0;
        c.damping_ratio = 0.0;
        (void)sm::create_constraint(w, c);
        // Swinging about the tip at 2 rad/s, plus a 0.3 m/s jerk across the board.
        sm::set_body_linear_velocity(w, board, {0, 0.3, 1.0});
        sm::set_body_angular_velocity(w, board, {0, 2.0, 0});
        const double e0 = energy(w, board);
        double e_max = 0.0, e_late = 0.0;
        const int steps = static_cast<int>(std::lround(1.0 / dt));
        for (int i = 0; i < steps; ++i) {
            w.step();
            e_max = std::max(e_max, energy(w, board));
            e_late = energy(w, board);
        }
        // The spring's own potential energy is not counted: 0.5% headroom covers it (the stretch is
        // under 1 mm at 100 Hz for this swing).
        EXPECT_LT(e_max, 1.005 * e0) << "dt " << dt;
        EXPECT_TRUE(std::isfinite(e_late));
        EXPECT_GT(e_late, 0.1 * e0) << "dt " << dt; // not frozen either
        std::printf("dt %g: E0 %.4f J, max %.4f J, end %.4f J\n", dt, e0, e_max, e_late);
    }
}

// The same swinging board on a joint with swing and twist limits (0.3 rad) that it hits again and again,
// without and with joint friction: the limits, now pushing on the modes, add no energy, and the friction
// takes it out (the spring's own energy is not counted: the headroom as above).
TEST(ModalConstraint, LimitsAndJointFrictionOnAModalBodyAddNoEnergy)
{
    for (double friction : {0.0, 5.0}) {
        sm::World w = make_world(1e-3);
        const sm::Entity board = add_board(w, 12, 0.0);
        sm::ConstraintDef c = sm::default_constraint_def();
        c.a = board;
        c.anchor_a.point = k_tip;
        c.anchor_b.point = k_tip;
        c.frequency_hz = 100.0;
        c.damping_ratio = 0.0;
        c.swing_limit = 0.3;
        c.twist_limit = 0.3;
        c.angular_damping = friction;
        (void)sm::create_constraint(w, c);
        sm::set_body_linear_velocity(w, board, {0, 0.3, 1.0});
        sm::set_body_angular_velocity(w, board, {1.0, 2.0, 0});
        const double e0 = energy(w, board);
        double e_max = 0.0, e_late = 0.0;
        for (int i = 0; i < 1000; ++i) {
            w.step();
            e_max = std::max(e_max, energy(w, board));
            e_late = energy(w, board);
        }
        EXPECT_LT(e_max, 1.005 * e0) << "friction " << friction;
        EXPECT_TRUE(std::isfinite(e_late));
        if (friction > 0.0) {
            EXPECT_LT(e_late, 0.5 * e0); // e^(-rate t/2) of the swing's energy is 0.08 after 1 s
        }
        std::printf("friction %g: E0 %.4f J, max %.4f J, end %.4f J\n", friction, e0, e_max, e_late);
    }
}

// Same scene, same state hash with one and two threads.
TEST(ModalConstraint, SameHashWithOneAndTwoThreads)
{
    uint64_t hash[2] = {};
    for (int threads : {1, 2}) {
        sm::World w = make_world(1e-4, threads);
        const sm::Entity board = add_board(w, 12, 0.02);
        (void)sm::create_constraint(w, weld_root_to_world(board, 500.0));
        sm::set_body_linear_velocity(w, board, {0, 0.3, 0});
        sm::set_body_angular_velocity(w, board, {0, 0, 1.0});
        for (int i = 0; i < 500; ++i)
            w.step();
        hash[threads - 1] = w.state_hash();
    }
    EXPECT_EQ(hash[0], hash[1]);
}
