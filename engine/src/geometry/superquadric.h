// SPDX-License-Identifier: MIT
// Log-space evaluation of Barr's inside-outside function, shared by superquadric.cpp, support.cpp and
// bounds.cpp. Every power of a coordinate becomes a multiple of its logarithm and every sum a
// log-sum-exp, so ε down to 0.01 (powers of 200) and points 10^6 radii away neither overflow nor
// underflow; a zero coordinate is ln 0 = −∞, which the sums absorb exactly.
#pragma once

#include "supermodal/geometry.h"

#include <algorithm>
#include <array>
#include <cfloat>
#include <cmath>
#include <limits>

namespace supermodal::sq
{

inline constexpr double k_neg_inf = -std::numeric_limits<double>::infinity();
/// Largest value the public functions return instead of +∞ (and its logarithm) [-].
inline constexpr double k_huge = 1e300;
inline constexpr double k_log_huge = 690.77552789821368; // ln 1e300

/// ln(e^a + e^b), exact for −∞ operands and never overflowing (the larger term is factored out).
[[nodiscard]] inline double log_add(double a, double b)
{
    const double hi = std::max(a, b), lo = std::min(a, b);
    return hi == k_neg_inf ? k_neg_inf : hi + std::log1p(std::exp(lo - hi));
}

/// ln|x / a| for a > 0; −∞ for x = 0. Falls back to a difference of logs when x / a overflows.
[[nodiscard]] inline double log_ratio(double x, double a)
{
    const double u = std::abs(x) / a;
    if (u == 0.0)
        return k_neg_inf;
    return u <= DBL_MAX ? std::log(u) : std::log(std::abs(x)) - std::log(a);
}

/// The logarithms of every term of F at one point. With u_i = |p_i / a_i|:
/// U = u_x^(2/ε2), V = u_y^(2/ε2), G = U + V, T1 = G^(ε2/ε1), T2 = u_z^(2/ε1), F = T1 + T2.
struct LogTerms {
    double log_u[3] = {k_neg_inf, k_neg_inf, k_neg_inf}; ///< ln u_i.
    double log_g = k_neg_inf;                            ///< ln G.
    double log_t1 = k_neg_inf;                           ///< ln T1.
    double log_t2 = k_neg_inf;                           ///< ln T2.
    double log_f = k_neg_inf;                            ///< ln F; −∞ only at the exact centre.
};

[[nodiscard]] inline LogTerms log_terms(const ShapeDef& shape, const Vec3& p)
{
    const double p1 = 2.0 / shape.epsilon1, p2 = 2.0 / shape.epsilon2;
    LogTerms t;
    for (int i = 0; i < 3; ++i)
        t.log_u[i] = log_ratio(p[i], shape.radii[i]);
    t.log_g = log_add(p2 * t.log_u[0], p2 * t.log_u[1]);
    t.log_t1 = (shape.epsilon2 / shape.epsilon1) * t.log_g;
    t.log_t2 = p1 * t.log_u[2];
    t.log_f = log_add(t.log_t1, t.log_t2);
    return t;
}

/// Logarithms of the magnitudes of ∂F^(ε1/2)/∂p_i times a_i, up to the common factor F^(ε1/2), and the
/// signs; sign 0 marks a component taken as zero (coordinate exactly zero: on a smooth surface the
/// component vanishes there, on a ridge or cusp zero is the symmetric choice between its two sides).
/// From F^(ε1/2) = exp((ε1/2) ln F): ∂/∂x = F^(ε1/2)·(T1/F)·(U/G)/x and ∂/∂z = F^(ε1/2)·(T2/F)/z.
struct LogGradient {
    double log_mag[3] = {k_neg_inf, k_neg_inf, k_neg_inf};
    double sign[3] = {0.0, 0.0, 0.0};
};

[[nodiscard]] inline LogGradient log_gradient(const ShapeDef& shape, const Vec3& p, const LogTerms& t)
{
    LogGradient g;
    if (t.log_f == k_neg_inf)
        return g;
    const double p2 = 2.0 / shape.epsilon2;
    const double share_xy = t.log_t1 - t.log_f, share_z = t.log_t2 - t.log_f;
    for (int i = 0; i < 2; ++i) {
        if (p[i] == 0.0)
            continue;
        g.log_mag[i] = share_xy + (p2 - 1.0) * t.log_u[i] - t.log_g;
        g.sign[i] = p[i] > 0.0 ? 1.0 : -1.0;
    }
    if (p.z != 0.0) {
        g.log_mag[2] = share_z - t.log_u[2];
        g.sign[2] = p.z > 0.0 ? 1.0 : -1.0;
    }
    return g;
}

/// Unit vector along (sign_i·exp(log_mag_i) / a_i); the largest term is factored out first. Falls
/// back to +z when every component is zero.
[[nodiscard]] inline Vec3 unit_from_logs(const double log_mag[3], const double sign[3], const Vec3& radii)
{
    double top = k_neg_inf;
    for (int i = 0; i < 3; ++i)
        if (sign[i] != 0.0)
            top = std::max(top, log_mag[i]);
    if (top == k_neg_inf)
        return {0.0, 0.0, 1.0};
    Vec3 v;
    for (int i = 0; i < 3; ++i)
        v[i] = sign[i] == 0.0 ? 0.0 : sign[i] * std::exp(log_mag[i] - top) / radii[i];
    const double m = std::max({std::abs(v.x), std::abs(v.y), std::abs(v.z)});
    return normalized(v / m);
}

// ---- Cube chart of the surface -----------------------------------------------------------------------
// Central projection of the scaled cube: x(c) = w / F(w)^(ε1/2) with w = a ∘ c and c on a face of
// [−1, 1]³. Unlike Barr's (η, ω) it does not squeeze a near-box's faces into a sliver of parameter
// space at ε → 0; the warp below does the same for the spikes of concave shapes.

/// A surface point in chart coordinates, with ½|p − x|² and its gradient for a target p.
struct ChartPoint {
    Vec3 u;         ///< Warped chart coordinates: u[face] = ±1, the others in [−1, 1].
    Vec3 x;         ///< Surface point [m], shape frame.
    double f = 0;   ///< ½|p − x|² [m²].
    double df[2]{}; ///< ∂f/∂u over the two free axes, (face + 1) % 3 then (face + 2) % 3 [m²].
};

/// Axis (0, 1, 2) of the cube face a chart or scaled-direction vector lies on.
inline int face_of(const Vec3& u)
{
    const double ax = std::abs(u.x), ay = std::abs(u.y), az = std::abs(u.z);
    return az >= ax && az >= ay ? 2 : (ay >= ax ? 1 : 0);
}

/// Warp exponent of free axis j on a face of axis k: c_j = sign(u_j)|u_j|^κ. A concave exponent ε > 2
/// draws its cusps out into spikes whose points crowd into |c_j| ≲ s^(ε/2) near the ridge (s the
/// distance along the spike), so κ = ε/2 spreads them evenly again; convex exponents need none.
inline double warp(const ShapeDef& shape, int k, int j)
{
    const double e = (k <= 1 && j <= 1) ? shape.epsilon2 : shape.epsilon1;
    return std::max(1.0, 0.5 * e);
}

/// Cube coordinates c of warped chart coordinates u on a face (inverse = false), or the reverse.
inline Vec3 rewarp(const ShapeDef& shape, Vec3 v, int face, bool inverse)
{
    for (int j : {(face + 1) % 3, (face + 2) % 3})
        v[j] = signed_power(v[j], inverse ? 1.0 / warp(shape, face, j) : warp(shape, face, j));
    return v;
}

/// Warped chart coordinates of any non-zero scaled direction c (put on its cube face first).
inline Vec3 warp_from_c(const ShapeDef& shape, Vec3 c)
{
    c = c / std::max({std::abs(c.x), std::abs(c.y), std::abs(c.z)});
    return rewarp(shape, c, face_of(c), true);
}

/// Surface point of chart coordinates u on a face, with the distance objective for target p.
inline ChartPoint chart_eval(const ShapeDef& shape, const Vec3& p, const Vec3& u, int face)
{
    ChartPoint q;
    q.u = u;
    const Vec3 w = hadamard(shape.radii, rewarp(shape, u, face, false));
    const LogTerms t = log_terms(shape, w);
    const double s = 0.5 * shape.epsilon1 * t.log_f;
    const double g = std::exp(s);
    q.x = w / g;
    const LogGradient lg = log_gradient(shape, w, t);
    const Vec3 r = p - q.x;
    q.f = 0.5 * dot(r, r);
    // dx/dc_j = a_j (e_j − x ∂_j g) / g, so ∂f/∂c_j = −a_j (r_j − (r·x) ∂_j g) / g; then dc_j/du_j.
    const double rx = dot(r, q.x);
    for (int m = 0; m < 2; ++m) {
        const int j = (face + 1 + m) % 3;
        const double grad_j =
            lg.sign[j] == 0.0
                ? 0.0
                : lg.sign[j] * std::exp(std::min(s + lg.log_mag[j], k_log_huge)) / shape.radii[j];
        const double kappa = warp(shape, face, j);
        const double dc_du = kappa == 1.0 ? 1.0 : kappa * std::pow(std::abs(u[j]), kappa - 1.0);
        q.df[m] = -shape.radii[j] * (r[j] - rx * grad_j) / g * dc_du;
    }
    return q;
}

/// Chart coordinates of the ray through a non-zero shape point.
inline Vec3 chart_of(const ShapeDef& shape, const Vec3& x)
{
    return warp_from_c(shape, {x.x / shape.radii.x, x.y / shape.radii.y, x.z / shape.radii.z});
}

/// The chart point on the ray through a non-zero shape point x, for target p.
inline ChartPoint chart_at(const ShapeDef& shape, const Vec3& p, const Vec3& x)
{
    const Vec3 u = chart_of(shape, x);
    return chart_eval(shape, p, u, face_of(u));
}

// ---- Ray hits: seeds for the closest point ------------------------------------------------------------

/// Surface points hit by rays from p that a nearest point often lies on, written to out; returns how
/// many. (1) In the plane through p normal to each axis, the ray from the axis through p: these land
/// on the spikes of concave shapes and the long sides of elongated ones, which the cube chart crowds
/// into slivers. ln F is convex and increasing in t = ln(scale of the two moved coordinates), so
/// Newton's method converges monotonically after at most one overshoot. (2) When p is inside, the six
/// axis-parallel rays from p, in closed form: the nearest face of a box-like shape is one of them.
inline int ray_hits(const ShapeDef& shape, const Vec3& p, bool inside, std::array<Vec3, 9>& out)
{
    constexpr int k_max_iterations = 60; // monotone Newton: ~10 in practice
    int count = 0;
    for (int i = 0; i < 3; ++i) {
        const int j1 = (i + 1) % 3, j2 = (i + 2) % 3;
        if (std::abs(p[i]) >= shape.radii[i] || (p[j1] == 0.0 && p[j2] == 0.0))
            continue; // the plane misses the shape, or p is on the axis
        double t = 0.0;
        Vec3 q = p;
        for (int it = 0; it < k_max_iterations; ++it) {
            q[j1] = p[j1] * std::exp(t);
            q[j2] = p[j2] * std::exp(t);
            const LogTerms lt = log_terms(shape, q);
            const LogGradient lg = log_gradient(shape, q, lt);
            double slope = 0.0; // d ln F / dt = Σ (2/ε1)·∂ln F^(ε1/2)/∂ln u_j over the moved axes
            for (int j : {j1, j2})
                if (lg.sign[j] != 0.0)
                    slope += 2.0 / shape.epsilon1 * std::exp(lg.log_mag[j] + lt.log_u[j]);
            if (!(slope > 0.0) || std::abs(lt.log_f) < 1e-14)
                break;
            t -= lt.log_f / slope;
        }
        out[count++] = q;
    }
    if (!inside)
        return count;
    // Along z: T2 = 1 − T1; along x: G = (1 − T2)^(ε1/ε2) on the surface, so U = G − V.
    const LogTerms t = log_terms(shape, p);
    const double e1 = shape.epsilon1, e2 = shape.epsilon2;
    const double z_hit = shape.radii.z * std::pow(std::max(1.0 - std::exp(t.log_t1), 0.0), 0.5 * e1);
    const double g_hit = std::pow(std::max(1.0 - std::exp(t.log_t2), 0.0), e1 / e2);
    const double uv[2] = {std::exp(2.0 / e2 * t.log_u[0]), std::exp(2.0 / e2 * t.log_u[1])};
    for (int i = 0; i < 3; ++i)
        for (double sign : {1.0, -1.0}) {
            Vec3 q = p;
            q[i] = sign *
                   (i == 2 ? z_hit : shape.radii[i] * std::pow(std::max(g_hit - uv[1 - i], 0.0), 0.5 * e2));
            if (q.x != 0.0 || q.y != 0.0 || q.z != 0.0)
                out[count++] = q;
        }
    return count;
}

} // namespace supermodal::sq
