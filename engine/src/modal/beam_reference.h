// SPDX-License-Identifier: MIT
// Reference frequencies of a free-free prismatic beam, for validating modal bases (tests, bench,
// docs): Euler–Bernoulli in closed form and Timoshenko (shear + rotary inertia) by a transfer matrix.
#pragma once

namespace supermodal::modal
{

/// A uniform beam, SI units.
struct BeamSection {
    double length = 1.0;          ///< L [m].
    double area = 0.0;            ///< A [m²].
    double second_moment = 0.0;   ///< I about the bending axis [m⁴].
    double density = 0.0;         ///< ρ [kg/m³].
    double young = 0.0;           ///< E [Pa].
    double poisson = 0.3;         ///< ν [-] (shear modulus G = E / 2(1 + ν)).
    double shear_coefficient = 0; ///< κ [-]; 10(1 + ν)/(12 + 11ν) for a rectangle (Cowper).
};

/// Cowper's shear coefficient of a rectangular section: κ = 10(1 + ν)/(12 + 11ν).
[[nodiscard]] double rectangle_shear_coefficient(double poisson);

/// β_n L of the free-free Euler–Bernoulli beam, the n-th positive root (n ≥ 1) of cos x cosh x = 1
/// (4.7300408 for n = 1).
[[nodiscard]] double free_free_beta_l(int n);

/// n-th (n ≥ 1) elastic bending frequency of the free-free Euler–Bernoulli beam,
/// f = (β_n L)² / (2π L²) · √(EI / ρA) [Hz].
[[nodiscard]] double euler_bernoulli_free_free_hz(const BeamSection& beam, int n);

/// n-th (n ≥ 1) elastic bending frequency of the free-free Timoshenko beam [Hz]: the n-th root of the
/// 2×2 free-end block of the transfer matrix exp(A L) of (w, ψ, M, V), found by bracketing and
/// bisection to 1e-12 relative. Needs shear_coefficient > 0.
[[nodiscard]] double timoshenko_free_free_hz(const BeamSection& beam, int n);

} // namespace supermodal::modal
