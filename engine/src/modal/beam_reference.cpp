// SPDX-License-Identifier: MIT
// Free-free beam reference frequencies (see beam_reference.h).
//
// Timoshenko beam, harmonic at ω, in dimensionless form ξ = x/L, w̄ = w/L, M̄ = ML/EI, V̄ = VL²/EI:
//   dw̄/dξ = ψ + s² V̄,   dψ/dξ = M̄,   dM̄/dξ = −V̄ − b² r² ψ,   dV̄/dξ = −b² w̄,
// with b² = ρAω²L⁴/EI, r² = I/(AL²) (rotary inertia), s² = EI/(κGAL²) (shear). With r = s = 0 this
// is EI w'''' = ρAω² w. Free ends: M̄ = V̄ = 0 at ξ = 0 and 1, so the (M̄, V̄) rows and (w̄, ψ) columns
// of T = exp(A) must be singular.
#include "modal/beam_reference.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace supermodal::modal
{
namespace
{

using Mat4 = double[4][4];

void multiply(const Mat4 a, const Mat4 b, Mat4 out)
{
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) {
            double s = 0.0;
            for (int k = 0; k < 4; ++k)
                s += a[i][k] * b[k][j];
            out[i][j] = s;
        }
}

/// exp(A) by scaling and squaring with a 24-term Taylor series (A small after scaling: error ~1e-16).
void expm(const Mat4 a, Mat4 out)
{
    double norm = 0.0;
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j)
            norm = std::max(norm, std::abs(a[i][j]));
    int squarings = 0;
    while (norm > 0.125) {
        norm *= 0.5;
        ++squarings;
    }
    const double scale = std::ldexp(1.0, -squarings);
    Mat4 term, next;
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j)
            out[i][j] = term[i][j] = i == j ? 1.0 : 0.0;
    for (int k = 1; k <= 24; ++k) {
        Mat4 scaled;
        for (int i = 0; i < 4; ++i)
            for (int j = 0; j < 4; ++j)
                scaled[i][j] = a[i][j] * scale / k;
        multiply(term, scaled, next);
        for (int i = 0; i < 4; ++i)
            for (int j = 0; j < 4; ++j)
                out[i][j] += term[i][j] = next[i][j];
    }
    for (int s = 0; s < squarings; ++s) {
        multiply(out, out, next);
        for (int i = 0; i < 4; ++i)
            for (int j = 0; j < 4; ++j)
                out[i][j] = next[i][j];
    }
}

/// The free-free frequency determinant at b² (dimensionless).
double free_free_determinant(double b2, double r2, double s2)
{
    const Mat4 a = {{0, 1, 0, s2}, {0, 0, 1, 0}, {0, -b2 * r2, 0, -1}, {-b2, 0, 0, 0}};
    Mat4 t;
    expm(a, t);
    return t[2][0] * t[3][1] - t[2][1] * t[3][0];
}

double hz_from_b2(const BeamSection& beam, double b2)
{
    const double l2 = beam.length * beam.length;
    return std::sqrt(b2 * beam.young * beam.second_moment / (beam.density * beam.area)) /
           (2.0 * std::numbers::pi * l2);
}

} // namespace

double rectangle_shear_coefficient(double poisson)
{
    return 10.0 * (1.0 + poisson) / (12.0 + 11.0 * poisson);
}

double free_free_beta_l(int n)
{
    // The n-th root lies within 0.02 of (n + 1/2)π, where cos changes sign against the huge cosh.
    double lo = (n + 0.5) * std::numbers::pi - 0.5, hi = (n + 0.5) * std::numbers::pi + 0.5;
    const auto f = [](double x) { return std::cos(x) * std::cosh(x) - 1.0; };
    const bool lo_negative = f(lo) < 0.0;
    for (int i = 0; i < 200 && hi - lo > 1e-15 * hi; ++i) {
        const double mid = 0.5 * (lo + hi);
        ((f(mid) < 0.0) == lo_negative ? lo : hi) = mid;
    }
    return 0.5 * (lo + hi);
}

double euler_bernoulli_free_free_hz(const BeamSection& beam, int n)
{
    const double bl = free_free_beta_l(n);
    return hz_from_b2(beam, bl * bl * bl * bl);
}

double timoshenko_free_free_hz(const BeamSection& beam, int n)
{
    const double shear_modulus = beam.young / (2.0 * (1.0 + beam.poisson));
    const double l2 = beam.length * beam.length;
    const double r2 = beam.second_moment / (beam.area * l2);
    const double s2 =
        beam.young * beam.second_moment / (beam.shear_coefficient * shear_modulus * beam.area * l2);
    // Timoshenko roots lie below Euler–Bernoulli's: scan b = β² upward from well below the first root in
    // 0.1% steps, counting sign changes (the roots are simple), then bisect the n-th bracket.
    const double b_max = std::pow(free_free_beta_l(n), 2) * 1.001;
    double b_prev = 0.25 * std::pow(free_free_beta_l(1), 2);
    double d_prev = free_free_determinant(b_prev * b_prev, r2, s2);
    int found = 0;
    for (double b = b_prev * 1.001; b <= b_max; b *= 1.001) {
        const double d = free_free_determinant(b * b, r2, s2);
        if ((d < 0.0) != (d_prev < 0.0) && ++found == n) {
            double lo = b_prev, hi = b;
            for (int i = 0; i < 100 && hi - lo > 1e-13 * hi; ++i) {
                const double mid = 0.5 * (lo + hi);
                ((free_free_determinant(mid * mid, r2, s2) < 0.0) == (d_prev < 0.0) ? lo : hi) = mid;
            }
            const double b_root = 0.5 * (lo + hi);
            return hz_from_b2(beam, b_root * b_root);
        }
        b_prev = b;
        d_prev = d;
    }
    return 0.0;
}

} // namespace supermodal::modal
