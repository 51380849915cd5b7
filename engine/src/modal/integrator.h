// SPDX-License-Identifier: MIT
// Time stepping of one vibration mode, q̈ + 2ζω q̇ + ω² q = F, over a step h with the generalized force
// F [√kg·m/s² = N/√kg] held constant over the step (docs/modal.md).
#pragma once

namespace supermodal::modal
{

/// One mode's step as a linear map: q₁ = a11 q₀ + a12 v₀ + b1 F, v₁ = a21 q₀ + a22 v₀ + b2 F.
struct ModeStep {
    double a11 = 1.0, a12 = 0.0, a21 = 0.0, a22 = 1.0;
    double b1 = 0.0, b2 = 0.0;
};

/// The exact solution over h [s] for constant F, for ω ≥ 0 [rad/s], ζ ≥ 0 [-]: under-, critically and
/// over-damped, and the ω → 0 limit (q̈ = F), all without cancellation (see integrator.cpp).
/// Unconditionally stable: |eigenvalues| = exp(−ζωh) ≤ 1 for ζ < 1.
[[nodiscard]] ModeStep exact_mode_step(double omega, double zeta, double h);

/// Applies a step map to one mode's state (q [√kg·m], v [√kg·m/s]) under force F.
void apply_mode_step(const ModeStep& s, double force, double& io_q, double& io_v);

/// Below this ωh a contact load (it depends on q: a penalty spring) is stepped as a kick before the exact
/// flow instead of being held over the step; at and past it, held (as the central-difference guard).
inline constexpr double k_contact_kick_limit = 2.0;

/// sin(ωh/2)/(ωh/2) [-]: how far a mode moves under a force held over h relative to a free mass.
[[nodiscard]] double half_step_sinc(double omega, double h);

/// The gain λ of that kick, q̇ += λ·h·Q, then the exact free flow over h (ωh < k_contact_kick_limit;
/// 0 past it): λ = sin(ωh/2)/(ωh/2) [-]. Any λ makes kick-then-flow symplectic against a spring
/// Q = −κq (det = 1 at ζ = 0, where the held map's is 1 + κ(1 − cos ωh)/ω²); this one gives a mode at
/// rest the held map's energy, 2 sin²(ωh/2)·Q²/ω², the mobility sinc²(ωh/2) contact springs are tuned
/// on (modal_inverse_mass), and λ → 1 (the plain kick) as ωh → 0. Its fixed point under a constant Q
/// is cos(ωh/2)·Q/ω² (ζ = 0): the static deflection to 1 − (ωh)²/8, 0.54 of it at ωh → 2.
[[nodiscard]] double contact_kick_gain(double omega, double h);

/// Largest ωh for which central difference is stable: 2 (for any ζ ≥ 0).
inline constexpr double k_central_difference_limit = 2.0;

/// Central difference (leapfrog) for one mode, the paper's explicit scheme: v is the velocity half a
/// step behind q (v_{n−1/2} → v_{n+1/2}); damping uses the average of the two half-step velocities,
///   v_{n+1/2} (1 + ζωh) = v_{n−1/2} (1 − ζωh) + h (F − ω² q_n),   q_{n+1} = q_n + h v_{n+1/2}.
/// Stable for ωh < 2 whatever ζ; the caller checks that and switches a mode past it to exact_mode_step.
void central_difference_step(double omega, double zeta, double h, double force, double& io_q, double& io_v);

} // namespace supermodal::modal
