// SPDX-License-Identifier: MIT
// The exact step of a damped mode in three regimes, each chosen where it loses no digits:
//  - small ωh and ζωh: the Taylor series of the solution (it holds the ω → 0 limit, q̈ = F, exactly);
//  - near critical damping, |1 − ζ²|(ωh)² small: cos/sin (or cosh/sinh) of ω_d h by their series, so the
//    formulas pass through ζ = 1 without dividing by ω_d → 0;
//  - otherwise the closed forms: e^(−ζωh)(cos, sin ω_d h / ω_d) underdamped; overdamped through the two
//    real roots s₁ = −ω/(ζ + √(ζ²−1)), s₂ = −ω(ζ + √(ζ²−1)) (no e^(−ζωh)·cosh overflow, no cancellation).
#include "modal/integrator.h"

#include <algorithm>
#include <cmath>

namespace supermodal::modal
{
namespace
{

// Below this max(ωh, 2ζωh) the Taylor series is used: its terms fall at least as 0.5^k / k!.
constexpr double k_series_limit = 0.5;
constexpr int k_series_terms = 30; // 0.5^30/30! ≈ 4e-42: far below round-off.
// Below this |1 − ζ²|(ωh)², cos and sin(x)/x of x = √z come from their series (error < z⁴/40320 ≈ 2e-17).
constexpr double k_near_critical_limit = 1e-3;

// Taylor series: with D_k = q⁽ᵏ⁾(0)·hᵏ, D_{k+2} = −2ζωh·D_{k+1} − (ωh)²·D_k (F is constant);
// q(h) = Σ D_k/k!, v(h) = Σ D_{k+1}/k! / h.
void series_response(double omega, double zeta, double h, double q0, double v0, double f, double& q1,
                     double& v1)
{
    const double c1 = 2.0 * zeta * omega * h, c2 = omega * h * omega * h;
    double d_prev = q0, d = v0 * h;                   // D_0, D_1
    double q = d_prev + d, v = d, inv_fact = 1.0;     // q: D_0/0! + D_1/1!; v: D_1/0!
    double d_next = f * h * h - c1 * d - c2 * d_prev; // D_2
    for (int k = 2; k < k_series_terms; ++k) {
        v += d_next * inv_fact; // D_k / (k−1)!
        inv_fact /= static_cast<double>(k);
        q += d_next * inv_fact; // D_k / k!
        const double d_after = -c1 * d_next - c2 * d;
        d = d_next;
        d_next = d_after;
    }
    q1 = q;
    v1 = v / h;
}

ModeStep series_step(double omega, double zeta, double h)
{
    ModeStep s;
    series_response(omega, zeta, h, 1.0, 0.0, 0.0, s.a11, s.a21);
    series_response(omega, zeta, h, 0.0, 1.0, 0.0, s.a12, s.a22);
    series_response(omega, zeta, h, 0.0, 0.0, 1.0, s.b1, s.b2);
    return s;
}

// From e·C and e·S, where e = e^(−ζωh), C = cos ω_d h, S = sin(ω_d h)/ω_d (or their hyperbolic
// continuations): the homogeneous map, and F's response v = e·S (the impulse response) and
// q = (1 − a11)/ω² (ωh > 0.25 on this path, so 1 − a11 keeps its digits).
ModeStep from_damped_trig(double omega, double zeta, double eC, double eS)
{
    ModeStep s;
    s.a11 = eC + zeta * omega * eS;
    s.a12 = eS;
    s.a21 = -omega * omega * eS;
    s.a22 = eC - zeta * omega * eS;
    s.b1 = (1.0 - s.a11) / (omega * omega);
    s.b2 = eS;
    return s;
}

// expm1(s·h)/s for s < 0, the response ∫₀ʰ e^(s t) dt.
double exp_integral(double s, double h)
{
    return std::expm1(s * h) / s;
}

ModeStep overdamped_step(double omega, double zeta, double h)
{
    const double root = std::sqrt((zeta - 1.0) * (zeta + 1.0));
    const double s1 = -omega / (zeta + root); // slow root
    const double s2 = -omega * (zeta + root); // fast root
    const double d = -2.0 * omega * root;     // s2 − s1, without cancellation
    const double e1 = std::exp(s1 * h), e2 = std::exp(s2 * h);
    ModeStep s;
    s.a11 = (s2 * e1 - s1 * e2) / d;
    s.a12 = (e2 - e1) / d;
    s.a21 = -omega * omega * s.a12;
    s.a22 = (s2 * e2 - s1 * e1) / d;
    // Step response: the divided difference of exp_integral; |s2|h > 0.25 here, so the two differ.
    s.b1 = (exp_integral(s2, h) - exp_integral(s1, h)) / d;
    s.b2 = s.a12;
    return s;
}

} // namespace

ModeStep exact_mode_step(double omega, double zeta, double h)
{
    if (!(h > 0.0) || !std::isfinite(h) || !(omega >= 0.0) || !std::isfinite(omega) || !(zeta >= 0.0) ||
        !std::isfinite(zeta))
        return {}; // identity: refuse to invent motion from a bad input
    const double wh = omega * h;
    if (std::max(wh, 2.0 * zeta * wh) <= k_series_limit)
        return series_step(omega, zeta, h);
    const double z = (1.0 - zeta) * (1.0 + zeta) * wh * wh; // (ω_d h)², negative when overdamped
    if (std::abs(z) < k_near_critical_limit) {
        const double e = std::exp(-zeta * wh);
        const double c = 1.0 - z / 2.0 + z * z / 24.0 - z * z * z / 720.0;
        const double s_over_h = 1.0 - z / 6.0 + z * z / 120.0 - z * z * z / 5040.0;
        return from_damped_trig(omega, zeta, e * c, e * s_over_h * h);
    }
    if (z > 0.0) {
        const double wd = omega * std::sqrt((1.0 - zeta) * (1.0 + zeta));
        const double e = std::exp(-zeta * wh);
        return from_damped_trig(omega, zeta, e * std::cos(wd * h), e * std::sin(wd * h) / wd);
    }
    return overdamped_step(omega, zeta, h);
}

void apply_mode_step(const ModeStep& s, double force, double& io_q, double& io_v)
{
    const double q = s.a11 * io_q + s.a12 * io_v + s.b1 * force;
    const double v = s.a21 * io_q + s.a22 * io_v + s.b2 * force;
    io_q = q;
    io_v = v;
}

double half_step_sinc(double omega, double h)
{
    const double x = 0.5 * omega * h;
    // sin(x)/x = 1 − x²/6 + x⁴/120 − …: the series below 1e-4 (next term < 1e-18).
    return x < 1e-4 ? 1.0 - x * x / 6.0 : std::sin(x) / x;
}

double contact_kick_gain(double omega, double h)
{
    const double x = 0.5 * omega * h;
    if (!(x >= 0.0) || !(x < 0.5 * k_contact_kick_limit))
        return 0.0; // not kicked (or a bad input: no motion invented)
    return half_step_sinc(omega, h);
}

void central_difference_step(double omega, double zeta, double h, double force, double& io_q, double& io_v)
{
    const double c = zeta * omega * h;
    io_v = (io_v * (1.0 - c) + h * (force - omega * omega * io_q)) / (1.0 + c);
    io_q += h * io_v;
}

} // namespace supermodal::modal
