// SPDX-License-Identifier: MIT
// Soft constraints (Catto's "soft step"): a constraint C with a spring of natural frequency ω and
// damping ratio ζ, integrated implicitly (backward Euler on C) over a step h, becomes a velocity
// constraint whose impulse is
//     Δλ = −m_eff·mass_scale·(Ċ + bias_rate·C) − impulse_scale·λ,
// with λ the impulse accumulated so far in the step. Stable for any ω·h: a stiff spring tends to a
// rigid constraint with full position correction, never to a blow-up.
#pragma once

namespace supermodal
{

struct SoftCoefficients {
    double bias_rate = 0.0;     ///< [1/s].
    double mass_scale = 0.0;    ///< [-].
    double impulse_scale = 0.0; ///< [-].
};

/// Coefficients for natural frequency omega [rad/s] and damping ratio zeta [-] over step h [s].
[[nodiscard]] inline SoftCoefficients make_soft(double omega, double zeta, double h)
{
    const double a1 = 2.0 * zeta + h * omega;
    const double a2 = h * omega * a1;
    const double a3 = 1.0 / (1.0 + a2);
    return {omega / a1, a2 * a3, a3};
}

} // namespace supermodal
