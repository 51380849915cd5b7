// SPDX-License-Identifier: MIT
// Analytic support map of superquadrics through the dual superquadric.
//
// In scaled coordinates X = x / a the gauge F^(ε1/2) is a nested ℓp norm, ‖(‖(X, Y)‖_p2, Z)‖_p1 with
// p = 2/ε, and a support point maximises D·X with D = a ∘ d over its unit ball. The dual of a nested
// ℓp norm is the nested ℓq norm with 1/p + 1/q = 1, i.e. exponents 2 − ε (the dual superquadric), and
// the maximiser of D·X over an ℓp ball is X_i = sign(D_i)(|D_i| / ‖D‖_q)^(q−1); we apply it to the
// inner pair and then to (‖(D_x, D_y)‖_q2, D_z). Every ratio is taken against the largest component
// first, so the powers q → ∞ (ε → 2) only ever underflow harmlessly, and ε → 0 tends to the box's
// sign(D). For ε > 2 (concave, ℓp with p < 1) the convex hull of the unit ball is the ℓ1 ball, so the
// hull's support is the same formula with ε clamped to 2 and a vertex chosen on ties: both ε ≥ 2 give
// the octahedron with vertices at the axis tips.
#include "supermodal/geometry.h"

#include <algorithm>
#include <cmath>

namespace supermodal
{
namespace
{

struct DualResult {
    double norm = 0.0;        // ‖(c0, c1)‖_q [-]
    double v[2] = {0.0, 0.0}; // maximiser of (c0, c1)·v over the unit ℓp ball (the convex hull's for ε > 2)
};

// One level of the nested norm: exponent eps of the primal, q = 2/(2 − eps) of the dual.
DualResult dual_level(double c0, double c1, double eps)
{
    DualResult out;
    const double m = std::max(std::abs(c0), std::abs(c1));
    if (m == 0.0)
        return out;
    const double r[2] = {std::abs(c0) / m, std::abs(c1) / m};
    const double sign[2] = {c0 > 0.0 ? 1.0 : (c0 < 0.0 ? -1.0 : 0.0),
                            c1 > 0.0 ? 1.0 : (c1 < 0.0 ? -1.0 : 0.0)};
    if (eps >= 2.0) {
        // ℓ∞ dual: the maximiser is a vertex of the ℓ1 ball; on an exact tie the octahedron (ε = 2)
        // takes the middle of its edge, the hull of a concave shape (ε > 2) a vertex, which is a
        // point of the shape itself.
        out.norm = m;
        if (eps == 2.0 && r[0] == r[1]) {
            out.v[0] = 0.5 * sign[0];
            out.v[1] = 0.5 * sign[1];
        } else {
            const int k = r[0] >= r[1] ? 0 : 1;
            out.v[k] = sign[k];
        }
        return out;
    }
    if (eps == 1.0) { // the ellipsoid, q = 2: a square root instead of five powers
        const double root = std::sqrt(r[0] * r[0] + r[1] * r[1]);
        out.norm = m * root;
        out.v[0] = sign[0] * r[0] / root;
        out.v[1] = sign[1] * r[1] / root;
        return out;
    }
    // Three powers instead of five (the support map of flat-faced bodies spent half the rounded-box
    // pile's time in pow): the largest ratio r_k is exactly 1, so with t = r_o^q (o the other),
    // sum = 1 + t ∈ [1, 2] and w = sum^(−ε/2):
    //   ‖c‖_q = m·sum^(1/q) = m·sum·w                (1/q = 1 − ε/2),
    //   v_i = (r_i^q / sum)^((q−1)/q) = r_i^(q·ε/2)·w  ((q−1)/q = ε/2).
    const double q = 2.0 / (2.0 - eps);
    const int k = r[0] >= r[1] ? 0 : 1, o = 1 - k;
    const double t = std::pow(r[o], q);
    const double sum = 1.0 + t;
    const double w = std::pow(sum, -0.5 * eps);
    out.norm = m * sum * w;
    out.v[k] = sign[k] * w;
    out.v[o] = sign[o] * std::pow(r[o], 0.5 * q * eps) * w;
    return out;
}

} // namespace

Vec3 support_point(const ShapeDef& shape, const Vec3& direction)
{
    const Vec3& a = shape.radii;
    if (shape.epsilon1 == 1.0 && shape.epsilon2 == 1.0) {
        // The ellipsoid: a ∘ D / ‖D‖ with D = a ∘ d, one square root and one division (the nested
        // levels below were 61% of the ellipsoid pile's step). Where ‖D‖² could overflow or lose
        // precision to underflow, the rescaled path below takes over. The clamp keeps an axis tip's
        // rounding (√(D_z²) ≠ |D_z| by an ulp) from leaving the box ±a.
        const Vec3 big = hadamard(a, direction);
        const double norm2 = dot(big, big);
        if (norm2 > 1e-280 && norm2 < 1e280) {
            const Vec3 p = hadamard(a, big) * (1.0 / std::sqrt(norm2));
            return {std::clamp(p.x, -a.x, a.x), std::clamp(p.y, -a.y, a.y), std::clamp(p.z, -a.z, a.z)};
        }
    }
    const Vec3 pole{0.0, 0.0, a.z};
    const double m = std::max({std::abs(direction.x), std::abs(direction.y), std::abs(direction.z)});
    if (!(m > 0.0) || !std::isfinite(m))
        return pole;
    // Two rescalings: the first so that a ∘ d cannot overflow, the second so the largest is exactly 1.
    Vec3 c = hadamard(a, direction / m);
    c = c / std::max({std::abs(c.x), std::abs(c.y), std::abs(c.z)});
    if (shape.epsilon1 == 1.0 && shape.epsilon2 == 1.0) {
        // The ellipsoid whose ‖a ∘ d‖² left the fast path's range above: the same a ∘ c / ‖c‖ on the
        // rescaled c, where ‖c‖ ∈ [1, √3] (the largest component is exactly 1).
        const double len = length(c);
        return {a.x * (c.x / len), a.y * (c.y / len), a.z * (c.z / len)};
    }
    const DualResult inner = dual_level(c.x, c.y, shape.epsilon2);
    const DualResult outer = dual_level(inner.norm, c.z, shape.epsilon1);
    const double rho = outer.v[0];
    return {a.x * rho * inner.v[0], a.y * rho * inner.v[1], a.z * outer.v[1]};
}

} // namespace supermodal
