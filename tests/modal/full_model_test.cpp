// Tests for engine/src/modal/full_model.cpp: the full lattice integrated by Newmark average
// acceleration, against its own static solution and against the modal path on the same lattice.
#include "modal/full_model.h"
#include "modal/integrator.h"
#include "modal_scenes.h"

#include <algorithm>
#include <cmath>
#include <gtest/gtest.h>
#include <limits>
#include <numbers>
#include <span>
#include <vector>

namespace sm = supermodal;
namespace mo = supermodal::modal;

namespace
{

// The board on a 4×1×1 lattice of 20-node cells: 168 dofs, so all 162 elastic modes fit in a basis.
constexpr int k_all_modes = 162;
// An off-centre, oblique load on the top face, so bending in both planes, torsion and axial are loaded.
const sm::Vec3 k_point{0.31, sm::test::k_board_thickness / 2, 0.02};
const sm::Vec3 k_force{10.0, -100.0, 30.0};
const sm::Vec3 k_far_end{-0.45, 0.0, 0.0};

const sm::ModalBasis& all_mode_basis()
{
    static const sm::ModalBasis basis = [] {
        auto built = sm::build_modal_basis(sm::test::board_def({4, 1, 1}, k_all_modes));
        EXPECT_TRUE(bool(built));
        return *built;
    }();
    return basis;
}

double omega(const sm::ModalBasis& b, int k)
{
    return 2.0 * std::numbers::pi * b.frequencies_hz[k];
}

// A half-sine pulse of duration tau [s], sampled at the middle of each step and held over it.
double pulse(double t_mid, double tau)
{
    return t_mid < tau ? std::sin(std::numbers::pi * t_mid / tau) : 0.0;
}

double norm3(const sm::Vec3& v)
{
    return std::sqrt(v.x * v.x + v.y * v.y + v.z * v.z);
}
sm::Vec3 minus(const sm::Vec3& a, const sm::Vec3& b)
{
    return {a.x - b.x, a.y - b.y, a.z - b.z};
}

// Displacement history at `probe` of the modal path with the lowest r modes, each integrated exactly with
// the Rayleigh damping ratio of its frequency (so it solves the same damped model as the full lattice).
std::vector<sm::Vec3> modal_history(int r, const mo::RayleighDamping& damping, double h, int steps,
                                    double tau, const sm::Vec3& probe)
{
    const sm::ModalBasis& b = all_mode_basis();
    const sm::LatticeWeights at_load = sm::modal_weights(b, k_point);
    const sm::LatticeWeights at_probe = sm::modal_weights(b, probe);
    std::vector<double> phi_f(static_cast<size_t>(r), 0.0); // φ_kᵀ f for the unit pulse
    for (int a = 0; a < at_load.count; ++a)
        for (int k = 0; k < r; ++k) {
            const size_t node = static_cast<size_t>(at_load.nodes[a]) * 3;
            const size_t n = static_cast<size_t>(b.mode_count);
            phi_f[k] += at_load.weights[a] * (b.mode_shapes[(node + 0) * n + k] * k_force.x +
                                              b.mode_shapes[(node + 1) * n + k] * k_force.y +
                                              b.mode_shapes[(node + 2) * n + k] * k_force.z);
        }
    std::vector<mo::ModeStep> maps;
    for (int k = 0; k < r; ++k)
        maps.push_back(mo::exact_mode_step(omega(b, k), mo::rayleigh_zeta(damping, omega(b, k)), h));
    std::vector<double> q(static_cast<size_t>(r), 0.0), v(q);
    std::vector<sm::Vec3> out;
    for (int s = 0; s < steps; ++s) {
        const double p = pulse((s + 0.5) * h, tau);
        for (int k = 0; k < r; ++k)
            mo::apply_mode_step(maps[k], p * phi_f[k], q[k], v[k]);
        out.push_back(sm::modal_displacement(b, at_probe, q));
    }
    return out;
}

std::vector<sm::Vec3> full_history(mo::FullModel& full, double h, int steps, double tau,
                                   const sm::Vec3& probe)
{
    std::vector<sm::Vec3> out;
    for (int s = 0; s < steps; ++s) {
        const double p = pulse((s + 0.5) * h, tau);
        const mo::PointLoad load{k_point, {p * k_force.x, p * k_force.y, p * k_force.z}};
        EXPECT_TRUE(full.step(h, {&load, 1}).ok());
        out.push_back(full.displacement(probe));
    }
    return out;
}

// max_t |a − b| / max_t |b|.
double relative_error(const std::vector<sm::Vec3>& a, const std::vector<sm::Vec3>& b)
{
    double diff = 0.0, peak = 0.0;
    for (size_t i = 0; i < a.size(); ++i) {
        diff = std::max(diff, norm3(minus(a[i], b[i])));
        peak = std::max(peak, norm3(b[i]));
    }
    return diff / peak;
}

std::unique_ptr<mo::FullModel> board_model(const mo::RayleighDamping& damping)
{
    auto built = mo::FullModel::build(sm::test::board_def({4, 1, 1}), damping);
    EXPECT_TRUE(bool(built));
    return built ? std::move(*built) : nullptr;
}

} // namespace

TEST(FullModel, RayleighFitHitsTheRatioAtBothFrequencies)
{
    const mo::RayleighDamping d = mo::fit_rayleigh(0.05, 1000.0, 7000.0);
    EXPECT_NEAR(mo::rayleigh_zeta(d, 1000.0), 0.05, 1e-15);
    EXPECT_NEAR(mo::rayleigh_zeta(d, 7000.0), 0.05, 1e-15);
    EXPECT_LT(mo::rayleigh_zeta(d, 3000.0), 0.05); // below the ratio between the two
    const mo::RayleighDamping none = mo::fit_rayleigh(std::numeric_limits<double>::quiet_NaN(), 1.0, 2.0);
    EXPECT_EQ(none.mass_factor, 0.0);
    EXPECT_EQ(none.stiffness_factor, 0.0);
}

TEST(FullModel, RefusesBadStepsAndLoads)
{
    const double nan = std::numeric_limits<double>::quiet_NaN();
    EXPECT_FALSE(mo::FullModel::build(sm::test::board_def({4, 1, 1}), {nan, 0.0}));
    sm::ModalBasisDef soft = sm::test::board_def({4, 1, 1});
    soft.young = nan;
    EXPECT_FALSE(mo::FullModel::build(soft, {}));
    auto full = board_model({});
    ASSERT_TRUE(full);
    EXPECT_FALSE(full->step(0.0, {}).ok());
    EXPECT_FALSE(full->step(std::numeric_limits<double>::quiet_NaN(), {}).ok());
    const mo::PointLoad bad{k_point, {std::numeric_limits<double>::infinity(), 0, 0}};
    EXPECT_FALSE(full->step(1e-4, {&bad, 1}).ok());
    for (const double x : full->nodal_displacement())
        EXPECT_TRUE(std::isfinite(x));
}

// A constant load, ramped in so the stiffest lattice modes (whose Newmark factor tends to −1 for ωh ≫ 1:
// average acceleration is not L-stable) are not set ringing, under heavy damping (ζ = 1 at ω₁ and ω₆):
// the motion settles on the direct sparse solution of K u = f_e, the fixed point of the scheme.
TEST(FullModel, HeavilyDampedMotionSettlesOnTheStaticSolution)
{
    const sm::ModalBasis& b = all_mode_basis();
    auto full = board_model(mo::fit_rayleigh(1.0, omega(b, 0), omega(b, 5)));
    ASSERT_TRUE(full);
    const mo::PointLoad load{k_point, k_force};
    const std::vector<double> u_static = full->static_solution({&load, 1});
    const double h = 0.05 / omega(b, 0);
    const int ramp = 400, hold = 4000; // hold: 200/ω₁, e^(−200)·poly for the critically damped ω₁
    for (int s = 0; s < ramp + hold; ++s) {
        const double f = std::min(1.0, (s + 0.5) / ramp);
        const mo::PointLoad now{k_point, {f * k_force.x, f * k_force.y, f * k_force.z}};
        ASSERT_TRUE(full->step(h, {&now, 1}).ok());
    }
    const std::span<const double> u = full->nodal_displacement();
    ASSERT_EQ(u.size(), u_static.size());
    double diff = 0.0, norm = 0.0;
    for (size_t i = 0; i < u.size(); ++i) {
        diff += (u[i] - u_static[i]) * (u[i] - u_static[i]);
        norm += u_static[i] * u_static[i];
    }
    ASSERT_GT(norm, 0.0);
    const double error = std::sqrt(diff / norm);
    EXPECT_LT(error, 1e-6) << "relative distance from K u = f_e";
    // The static solution itself: K u = f_e with f_e self-equilibrated, u free of rigid motion.
    EXPECT_GT(norm3(full->displacement(k_point)), 0.0);
}

// All 162 elastic modes kept and damped with the full model's Rayleigh ratios: the modal path solves the
// same equations exactly (piecewise-constant load), so what differs is Newmark's time error alone: a
// period elongation ≈ (ωh)²/12, a phase lag ω t (ωh)²/12 after t. For the response, dominated by the
// lowest modes, that is ≈ ω₆ T (ω₆ h)²/12 relative at worst (ω₆: the highest of the six lowest
// modes that a smooth pulse excites); stiffer modes follow the smooth pulse quasi-statically.
// Second order: halving h divides the difference by ≈ 4.
TEST(FullModel, AgreesWithTheExactModalPathWithAllModes)
{
    const sm::ModalBasis& b = all_mode_basis();
    ASSERT_EQ(b.mode_count, k_all_modes);
    const mo::RayleighDamping damping = mo::fit_rayleigh(0.02, omega(b, 0), omega(b, 5));
    const double period = 1.0 / b.frequencies_hz[0];
    const double tau = period / 4.0, duration = period; // a struck board, one fundamental period
    double previous = 0.0;
    for (const int divisions : {400, 800}) {
        const double h = period / divisions;
        const int steps = divisions;
        auto full = board_model(damping);
        ASSERT_TRUE(full);
        for (const sm::Vec3& probe : {k_point, k_far_end}) {
            full->reset();
            const auto f = full_history(*full, h, steps, tau, probe);
            const auto m = modal_history(k_all_modes, damping, h, steps, tau, probe);
            const double w6 = omega(b, 5);
            const double bound = w6 * duration * (w6 * h) * (w6 * h) / 12.0;
            const double error = relative_error(m, f);
            EXPECT_LT(error, bound) << "h = " << h << ", probe x = " << probe.x;
            if (probe.x == k_point.x) {
                if (divisions == 800) {
                    EXPECT_NEAR(previous / error, 4.0, 1.0) << "second order in h";
                }
                previous = error;
            }
            std::printf("h = T1/%d, probe x = %.2f: error %.3e (bound %.3e)\n", divisions, probe.x, error,
                        bound);
        }
    }
}

// Truncation: at the struck point, 12 modes follow the full lattice better than 6, and 24 better still.
TEST(FullModel, TruncatedModalResponseApproachesTheFullOne)
{
    const sm::ModalBasis& b = all_mode_basis();
    const mo::RayleighDamping damping = mo::fit_rayleigh(0.02, omega(b, 0), omega(b, 5));
    const double period = 1.0 / b.frequencies_hz[0];
    const double h = period / 400, tau = period / 4.0;
    auto full = board_model(damping);
    ASSERT_TRUE(full);
    const auto reference = full_history(*full, h, 400, tau, k_point);
    std::vector<double> errors;
    for (const int r : {6, 12, 24, k_all_modes})
        errors.push_back(relative_error(modal_history(r, damping, h, 400, tau, k_point), reference));
    std::printf("truncation error at the struck point: r=6 %.3e, 12 %.3e, 24 %.3e, all %.3e\n", errors[0],
                errors[1], errors[2], errors[3]);
    EXPECT_LT(errors[1], errors[0]);
    EXPECT_LT(errors[2], errors[1]);
    EXPECT_LT(errors[3], errors[2]);
}
