// Tests for engine/src/modal/integrator.cpp: the per-mode exact step against an independent matrix
// exponential, energy conservation, and central difference's stability limit.
#include "modal/integrator.h"

#include <array>
#include <cmath>
#include <gtest/gtest.h>

namespace sm = supermodal;
using sm::modal::ModeStep;

namespace
{

using Mat = std::array<std::array<long double, 3>, 3>;

Mat multiply(const Mat& a, const Mat& b)
{
    Mat c{};
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            for (int k = 0; k < 3; ++k)
                c[i][j] += a[i][k] * b[k][j];
    return c;
}

// Reference: exp(A h) of the augmented system d/dt (q, v, F) = (v, F − 2ζω v − ω² q, 0) by scaling and
// squaring a 30-term Taylor series in long double: a different method from the closed forms under test.
ModeStep reference_step(double omega, double zeta, double h)
{
    Mat a{};
    a[0][1] = h;
    a[1][0] = -static_cast<long double>(omega) * omega * h;
    a[1][1] = -2.0L * zeta * omega * h;
    a[1][2] = h;
    const long double norm = std::abs(a[1][0]) + std::abs(a[1][1]) + h + h;
    int squarings = 0;
    long double scale = 1.0L;
    while (norm * scale > 0.05L) {
        scale /= 2.0L;
        ++squarings;
    }
    Mat term{}, sum{};
    for (int i = 0; i < 3; ++i)
        term[i][i] = sum[i][i] = 1.0L;
    for (int k = 1; k < 30; ++k) {
        Mat scaled = a;
        for (auto& row : scaled)
            for (auto& x : row)
                x *= scale / k;
        term = multiply(term, scaled);
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j)
                sum[i][j] += term[i][j];
    }
    for (int s = 0; s < squarings; ++s)
        sum = multiply(sum, sum);
    return {static_cast<double>(sum[0][0]), static_cast<double>(sum[0][1]), static_cast<double>(sum[1][0]),
            static_cast<double>(sum[1][1]), static_cast<double>(sum[0][2]), static_cast<double>(sum[1][2])};
}

} // namespace

TEST(ModalIntegrator, ExactStepMatchesMatrixExponentialInEveryRegime)
{
    // ζ: undamped, light, critical and ±1e-7 around it (the near-critical series), overdamped, heavy.
    // ωh: the ω → 0 limit, the series branch and both sides of its 0.5 edge, stiff steps.
    const double h = 1e-3;
    for (double zeta : {0.0, 0.05, 0.7, 1.0 - 1e-7, 1.0, 1.0 + 1e-7, 1.3, 3.0, 40.0})
        for (double wh : {0.0, 1e-9, 1e-4, 0.1, 0.2499, 0.2501, 0.4999, 0.5001, 1.0, 3.0, 30.0}) {
            const double omega = wh / h;
            const ModeStep s = sm::modal::exact_mode_step(omega, zeta, h);
            const ModeStep ref = reference_step(omega, zeta, h);
            // Each coefficient against its natural scale (a12, b2 ≤ h; a21 ≤ ω²h; b1 ≤ h²/2): the
            // reference carries ~1e-15 relative error after up to 16 squarings, the closed forms lose at
            // most a few digits to cancellation at branch edges; 1e-11 leaves room for both.
            const double tol = 1e-11;
            SCOPED_TRACE(testing::Message() << "zeta " << zeta << " omega*h " << wh);
            EXPECT_NEAR(s.a11, ref.a11, tol);
            EXPECT_NEAR(s.a22, ref.a22, tol);
            EXPECT_NEAR(s.a12 / h, ref.a12 / h, tol);
            EXPECT_NEAR(s.b2 / h, ref.b2 / h, tol);
            EXPECT_NEAR(s.b1 / (h * h), ref.b1 / (h * h), tol);
            EXPECT_NEAR(s.a21 / (omega * omega * h + 1e-300), ref.a21 / (omega * omega * h + 1e-300), tol);
        }
}

TEST(ModalIntegrator, ZeroFrequencyIsFreeFlight)
{
    // q̈ = F exactly: q₁ = q₀ + v₀h + Fh²/2, v₁ = v₀ + Fh (exact in binary for these values).
    const ModeStep s = sm::modal::exact_mode_step(0.0, 0.3, 0.5);
    double q = 1.0, v = 2.0;
    sm::modal::apply_mode_step(s, 4.0, q, v);
    EXPECT_DOUBLE_EQ(q, 1.0 + 2.0 * 0.5 + 4.0 * 0.125);
    EXPECT_DOUBLE_EQ(v, 2.0 + 4.0 * 0.5);
}

TEST(ModalIntegrator, ExactStepConservesUndampedEnergy)
{
    // The map is a rotation in (ωq, v): energy changes only by round-off. The same map every step
    // makes that error systematic, |det| − 1 of a few ulps (cos² + sin² of a rounded angle), so 1e4 steps
    // may drift by 1e4 × a few × 1.1e-16: 1e-11 (measured: 1.07e-12 at ωh = 100).
    for (double wh : {0.01, 0.3, 1.9, 2.5, 100.0}) {
        const double omega = 1000.0, h = wh / omega;
        const ModeStep s = sm::modal::exact_mode_step(omega, 0.0, h);
        double q = 1e-3, v = 0.5;
        const double e0 = 0.5 * (v * v + omega * omega * q * q);
        for (int i = 0; i < 10000; ++i)
            sm::modal::apply_mode_step(s, 0.0, q, v);
        EXPECT_NEAR(0.5 * (v * v + omega * omega * q * q) / e0, 1.0, 1e-11) << "omega*h " << wh;
    }
}

TEST(ModalIntegrator, ConstantForceSettlesOnStaticDeflection)
{
    // q → F/ω² for any step size; after 200 steps of e^(−ζωh) = e^(−0.35) the transient is e^(−70).
    for (double zeta : {0.5, 1.0, 2.0}) {
        const double omega = 50.0, h = 0.01, force = 3.0;
        const ModeStep s = sm::modal::exact_mode_step(omega, zeta, h);
        double q = 0.0, v = 0.0;
        for (int i = 0; i < 200; ++i)
            sm::modal::apply_mode_step(s, force, q, v);
        EXPECT_NEAR(q, force / (omega * omega), 1e-14) << "zeta " << zeta;
        EXPECT_NEAR(v, 0.0, 1e-12);
    }
}

TEST(ModalIntegrator, CentralDifferenceShadowEnergyAndStabilityLimit)
{
    // Undamped leapfrog conserves H = ½v² + ½ω² q_n q_{n+1} = ½v² + ½ω²q² − ½ω²h q v (state after the
    // step: q = q_{n+1}, v = v_{n+1/2}) exactly in exact arithmetic: round-off only over 1e4 steps.
    const double omega = 1000.0;
    for (double wh : {0.1, 1.0, 1.99}) {
        const double h = wh / omega;
        double q = 1e-3, v = 0.0;
        auto shadow = [&] { return 0.5 * v * v + 0.5 * omega * omega * q * (q - h * v); };
        sm::modal::central_difference_step(omega, 0.0, h, 0.0, q, v);
        const double h0 = shadow();
        double q_max = 0.0;
        for (int i = 0; i < 10000; ++i) {
            sm::modal::central_difference_step(omega, 0.0, h, 0.0, q, v);
            q_max = std::max(q_max, std::abs(q));
        }
        EXPECT_NEAR(shadow() / h0, 1.0, 1e-9) << "omega*h " << wh;
        // Bounded: |q| ≤ √(2H/ω²) / √(1 − (ωh/2)²), the semi-axis of the invariant ellipse.
        EXPECT_LE(q_max, std::sqrt(2.0 * h0) / omega / std::sqrt(1.0 - wh * wh / 4.0) * (1.0 + 1e-9));
    }
    // Past the limit the amplification factor exceeds 1: at ωh = 2.01 it is about 1.105 per step.
    double q = 1e-3, v = 0.0;
    for (int i = 0; i < 200; ++i)
        sm::modal::central_difference_step(omega, 0.0, 2.01 / omega, 0.0, q, v);
    EXPECT_GT(std::abs(q), 1e3);
}

TEST(ModalIntegrator, DampedCentralDifferenceDecaysAtZetaOmega)
{
    // ζ = 0.02, ωh = 0.02: central difference's decay rate is ζω up to O((ωh)²) ≈ 4e-4 relative.
    const double omega = 100.0, zeta = 0.02, h = 2e-4;
    double q = 1.0, v = 0.0;
    const int steps = 50000; // t = 10 s, ζωt = 20
    for (int i = 0; i < steps; ++i)
        sm::modal::central_difference_step(omega, zeta, h, 0.0, q, v);
    const double energy = 0.5 * (v * v + omega * omega * q * q);
    const double rate = -std::log(energy / (0.5 * omega * omega)) / (2.0 * steps * h);
    // The energy oscillates within about ±ζ about its envelope, which shifts the fitted rate by
    // ζ/(2ζωt) = 0.05%; the scheme's own error is O((ωh)²) = 4e-4. 0.5% covers both (measured −2.6e-4).
    EXPECT_NEAR(rate, zeta * omega, 0.005 * zeta * omega);
}

TEST(ContactKick, SymplecticAgainstASpringWithTheHeldMapsEnergyPerKick)
{
    // Kick q̇ += λhQ then the exact flow, with Q = −κq taken at q_n: the one-step matrix must have
    // det 1 at ζ = 0 (symplectic; the held map's is 1 + κ(1 − cos ωh)/ω², the stability map's energy
    // gain); from rest, a unit Q must give the held map's energy ½(v² + ω²q²); a constant Q must have
    // the fixed point cos(ωh/2)/ω². Tolerances: round-off of a few O(1) products, 1e-12 (1e-6 for the
    // fixed point, whose I − Φ is ill-conditioned as ωh → 0).
    const double h = 1e-3;
    for (const double wh : {1e-6, 1e-3, 0.2, 1.0, 1.9}) {
        const double omega = wh / h, kappa = 3.0 * omega * omega + 1e4;
        const ModeStep s = sm::modal::exact_mode_step(omega, 0.0, h);
        const double lambda = sm::modal::contact_kick_gain(omega, h);
        ASSERT_GT(lambda, 0.0);
        // Column j: the step from unit q (j = 0) or unit v (j = 1), kick first.
        double m[2][2];
        for (int j = 0; j < 2; ++j) {
            double q = j == 0 ? 1.0 : 0.0, v = j == 1 ? 1.0 : 0.0;
            v += lambda * h * (-kappa * q);
            sm::modal::apply_mode_step(s, 0.0, q, v);
            m[0][j] = q;
            m[1][j] = v;
        }
        const double det = m[0][0] * m[1][1] - m[0][1] * m[1][0];
        EXPECT_NEAR(det, 1.0, 1e-12) << wh;
        const double held_det = 1.0 + kappa * (1.0 - std::cos(wh)) / (omega * omega);
        if (wh >= 0.2) { // the flaw the kick removes, visible at these ωh
            EXPECT_GT(held_det - 1.0, 1e-3);
        }
        // Fixed point under constant Q = 1: x = Φ(x + (0, λh)) ⇔ (I − Φ)x = Φ(0, λh).
        const double a = lambda * h;
        const double r0 = s.a12 * a, r1 = s.a22 * a;
        const double i00 = 1.0 - s.a11, i01 = -s.a12, i10 = -s.a21, i11 = 1.0 - s.a22;
        const double d = i00 * i11 - i01 * i10;
        const double q_fixed = (r0 * i11 - i01 * r1) / d;
        EXPECT_NEAR(q_fixed * omega * omega, std::cos(0.5 * wh), 1e-6) << wh;
        // Energy from rest under a unit Q: the kick's ½(λh)² (the flow keeps it) against the held map's.
        double hq = 0.0, hv = 0.0;
        sm::modal::apply_mode_step(s, 1.0, hq, hv);
        const double held_energy = 0.5 * (hv * hv + omega * omega * hq * hq);
        EXPECT_NEAR(0.5 * a * a / held_energy, 1.0, 1e-9) << wh;
    }
    // Past the limit: not kicked (the held map), and bad input refused.
    EXPECT_EQ(sm::modal::contact_kick_gain(2.0 / 1e-3, 1e-3), 0.0);
    EXPECT_EQ(sm::modal::contact_kick_gain(std::nan(""), 1e-3), 0.0);
}
