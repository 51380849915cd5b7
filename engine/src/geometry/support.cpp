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
#include "geometry/support_internal.h"

#include <algorithm>
#include <cmath>

namespace supermodal
{
namespace
{

struct DualResult {
    double norm = 0.0;        // ‖(c0, c1)‖_q [-]
    double v[2] = {0.0, 0.0}; // maximiser of (c0, c1)·v over the unit ℓp ball (the convex hull's for ε > 2)
    // Hessian of ‖(c0, c1)‖_q: ∂v_i/∂c_j, symmetric (h01 = h10); filled only when asked for.
    double h00 = 0.0, h01 = 0.0, h11 = 0.0;
};

// Where a face is flat (ε < 1) the dual norm's curvature grows without bound towards the face's
// normal; capped at this many times 1/m, a radius of curvature 1e12 times the body's [-].
constexpr double k_hessian_cap = 1e12;

// The Hessian of the ℓq norm at (c0, c1) is rank one along the tangent (c1, −c0) (the norm is
// 1-homogeneous): (q − 1)|c0 c1|^(q−2) ‖c‖^(1−2q) [c1², −c0c1; −c0c1, c0²]. In the ratios of dual_level,
// with r_k = 1, t = r_o^q and sum = 1 + t (‖c‖^(1−2q) = m^(1−2q)·w/sum):
//   h_kk = (q−1)/m · t · w/sum,  h_oo = (q−1)/m · r_o^(q−2) · w/sum,  h_ko = −(q−1)/m · s_k s_o r_o^(q−1) ·
//   w/sum.
// r^(q−2) from t = r^q, as t / r²; at r = 0 it is 0 (q > 2), 1 (q = 2) or unbounded (q < 2, the flat
// face), and it is capped at k_hessian_cap.
double capped_power(double r, double t, double q)
{
    const double p = r > 0.0 ? t / (r * r) : (q > 2.0 ? 0.0 : (q == 2.0 ? 1.0 : k_hessian_cap));
    return std::min(p, k_hessian_cap);
}

void dual_hessian(DualResult& out, double q, int k, double m, double r_o, double t, double w, double sum,
                  const double sign[2])
{
    const double scale = (q - 1.0) * w / (sum * m);
    const double h_kk = scale * t, h_oo = scale * capped_power(r_o, t, q);
    const double h_ko = r_o > 0.0 ? -scale * sign[0] * sign[1] * (t / r_o) : 0.0;
    out.h00 = k == 0 ? h_kk : h_oo;
    out.h11 = k == 0 ? h_oo : h_kk;
    out.h01 = h_ko;
}

// One level of the nested norm: exponent eps of the primal, q = 2/(2 − eps) of the dual. With
// `hessian`, also the norm's Hessian (zero for eps ≥ 2, where the norm is piecewise linear).
DualResult dual_level(double c0, double c1, double eps, bool hessian = false)
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
        if (hessian) { // [c1², −c0c1; −c0c1, c0²] / ‖c‖³
            const double inv = 1.0 / (m * root * root * root);
            out.h00 = r[1] * r[1] * inv;
            out.h11 = r[0] * r[0] * inv;
            out.h01 = -sign[0] * sign[1] * r[0] * r[1] * inv;
        }
        return out;
    }
    // Two powers instead of five (the support map of flat-faced bodies spent half the rounded-box
    // pile's time in pow): the largest ratio r_k is exactly 1, so with t = r_o^q (o the other),
    // sum = 1 + t ∈ [1, 2] and w = sum^(−ε/2):
    //   ‖c‖_q = m·sum^(1/q) = m·sum·w                        (1/q = 1 − ε/2),
    //   v_i = (r_i^q / sum)^((q−1)/q) = r_i^(q·ε/2)·w = (t/r_o)·w  ((q−1)/q = ε/2, q·ε/2 = q − 1).
    const double q = 2.0 / (2.0 - eps);
    const int k = r[0] >= r[1] ? 0 : 1, o = 1 - k;
    const double t = std::pow(r[o], q);
    const double sum = 1.0 + t;
    const double w = std::pow(sum, -0.5 * eps);
    out.norm = m * sum * w;
    out.v[k] = sign[k] * w;
    // r_o^(qε/2) = r_o^(q−1) = t / r_o: no power of its own.
    out.v[o] = r[o] > 0.0 ? sign[o] * (t / r[o]) * w : 0.0;
    if (hessian)
        dual_hessian(out, q, k, m, r[o], t, w, sum, sign);
    return out;
}

// Equal exponents (ε1 = ε2 = ε, a rounded box's usual case): the nested norm is one ℓq norm of all three
// components, so its maximiser takes three powers instead of the two levels' four. Same steps as
// dual_level with two other components: with r_k = 1 the largest ratio, t_i = r_i^q, sum = 1 + Σ t_i and
// w = sum^(−ε/2), v_k = s_k·w and v_i = s_i·(t_i/r_i)·w. For ε in (0, 2), ε ≠ 1; c as scaled_direction
// gives it (largest |c_i| exactly 1).
struct FlatDual {
    Vec3 v{};          // maximiser of c·v over the unit ℓp ball
    double q = 0.0;    // dual exponent [-]
    double w = 0.0;    // sum^(−ε/2) = ‖c‖_q^(1−q) [-]
    double norm = 0.0; // ‖c‖_q = sum·w [-]
    Vec3 r{}, t{};     // |c_i| and |c_i|^q
};

FlatDual flat_dual(const Vec3& c, double eps)
{
    FlatDual out;
    out.q = 2.0 / (2.0 - eps);
    out.r = {std::abs(c.x), std::abs(c.y), std::abs(c.z)};
    const int k = out.r.x >= out.r.y ? (out.r.x >= out.r.z ? 0 : 2) : (out.r.y >= out.r.z ? 1 : 2);
    double sum = 1.0;
    for (int i = 0; i < 3; ++i) {
        out.t[i] = i == k ? 1.0 : std::pow(out.r[i], out.q);
        sum += i == k ? 0.0 : out.t[i];
    }
    out.w = std::pow(sum, -0.5 * eps);
    out.norm = sum * out.w;
    for (int i = 0; i < 3; ++i) {
        const double sign = c[i] > 0.0 ? 1.0 : (c[i] < 0.0 ? -1.0 : 0.0);
        out.v[i] = i == k ? sign * out.w : (out.r[i] > 0.0 ? sign * (out.t[i] / out.r[i]) * out.w : 0.0);
    }
    return out;
}

// Its Hessian ∂v_i/∂c_j = (q − 1)·(r_i^(q−2)·w·δ_ij − v_i v_j / ‖c‖_q), r_i^(q−2) capped (capped_power).
Mat3 flat_hessian(const FlatDual& f)
{
    Mat3 h{};
    for (int i = 0; i < 3; ++i) {
        const double diag = capped_power(f.r[i], f.t[i], f.q);
        for (int j = 0; j < 3; ++j)
            h.m[i][j] = (f.q - 1.0) * ((i == j ? diag * f.w : 0.0) - f.v[i] * f.v[j] / f.norm);
    }
    return h;
}

// Whether the shape takes flat_dual.
bool flat_exponents(const ShapeDef& shape)
{
    return shape.epsilon1 == shape.epsilon2 && shape.epsilon1 < 2.0 && shape.epsilon1 != 1.0;
}

// The direction scaled to c = a ∘ d / max|a ∘ d| (largest component exactly 1, so no level overflows),
// and that scale, max|a ∘ d| [m]. False for a zero or non-finite direction.
bool scaled_direction(const Vec3& a, const Vec3& direction, Vec3& out_c, double& out_scale)
{
    const double m = std::max({std::abs(direction.x), std::abs(direction.y), std::abs(direction.z)});
    if (!(m > 0.0) || !std::isfinite(m))
        return false;
    // Two rescalings: the first so that a ∘ d cannot overflow, the second so the largest is exactly 1.
    const Vec3 c = hadamard(a, direction / m);
    const double big = std::max({std::abs(c.x), std::abs(c.y), std::abs(c.z)});
    out_c = c / big;
    out_scale = m * big;
    return true;
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
    Vec3 c;
    double scale = 0.0;
    if (!scaled_direction(a, direction, c, scale))
        return {0.0, 0.0, a.z}; // the pole
    if (shape.epsilon1 == 1.0 && shape.epsilon2 == 1.0) {
        // The ellipsoid whose ‖a ∘ d‖² left the fast path's range above: the same a ∘ c / ‖c‖ on the
        // rescaled c, where ‖c‖ ∈ [1, √3] (the largest component is exactly 1).
        const double len = length(c);
        return {a.x * (c.x / len), a.y * (c.y / len), a.z * (c.z / len)};
    }
    if (flat_exponents(shape))
        return hadamard(a, flat_dual(c, shape.epsilon1).v);
    const DualResult inner = dual_level(c.x, c.y, shape.epsilon2);
    const DualResult outer = dual_level(inner.norm, c.z, shape.epsilon1);
    const double rho = outer.v[0];
    return {a.x * rho * inner.v[0], a.y * rho * inner.v[1], a.z * outer.v[1]};
}

} // namespace supermodal

namespace supermodal
{

// x = a ∘ ∇N(a ∘ d) with N the nested dual norm ‖(‖(D_x, D_y)‖_q2, D_z)‖_q1, so ∂x/∂d = diag(a) ∇²N diag(a),
// and ∇²N(a ∘ d) = ∇²N(c) / scale (N is 1-homogeneous). With M the inner norm and (v_M, v_z) the outer
// gradient: ∇²N = [H_MM ∇M∇Mᵀ + v_M ∇²M, H_Mz ∇M; H_Mz ∇Mᵀ, H_zz].
SupportJet support_jet(const ShapeDef& shape, const Vec3& direction)
{
    SupportJet jet;
    const Vec3& a = shape.radii;
    Vec3 c;
    double scale = 0.0;
    if (!scaled_direction(a, direction, c, scale)) {
        jet.point = {0.0, 0.0, a.z};
        return jet;
    }
    if (shape.epsilon1 == 1.0 && shape.epsilon2 == 1.0) {
        // The ellipsoid: x = E d / |a ∘ d| with E = diag(a²), so ∂x/∂d = (E − x xᵀ) / |a ∘ d|; the point
        // from support_point's own closed form.
        jet.point = support_point(shape, direction);
        const double h = scale * length(c);
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j)
                jet.jacobian.m[i][j] = ((i == j ? a[i] * a[i] : 0.0) - jet.point[i] * jet.point[j]) / h;
        return jet;
    }
    if (flat_exponents(shape)) {
        const FlatDual f = flat_dual(c, shape.epsilon1);
        jet.point = hadamard(a, f.v);
        const Mat3 n = flat_hessian(f);
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j)
                jet.jacobian.m[i][j] = a[i] * n.m[i][j] * a[j] / scale;
        return jet;
    }
    const DualResult inner = dual_level(c.x, c.y, shape.epsilon2, true);
    const DualResult outer = dual_level(inner.norm, c.z, shape.epsilon1, true);
    const double rho = outer.v[0];
    jet.point = {a.x * rho * inner.v[0], a.y * rho * inner.v[1], a.z * outer.v[1]};
    const double gx = inner.v[0], gy = inner.v[1];
    const double n[3][3] = {
        {outer.h00 * gx * gx + rho * inner.h00, outer.h00 * gx * gy + rho * inner.h01, outer.h01 * gx},
        {outer.h00 * gx * gy + rho * inner.h01, outer.h00 * gy * gy + rho * inner.h11, outer.h01 * gy},
        {outer.h01 * gx, outer.h01 * gy, outer.h11}};
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            jet.jacobian.m[i][j] = a[i] * n[i][j] * a[j] / scale;
    return jet;
}

} // namespace supermodal
