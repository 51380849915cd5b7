// SPDX-License-Identifier: MIT
// Barr superquadrics: inside-outside function, contact measure and normals in log space (see
// superquadric.h), the signed-power parametric surface, and the closest-point projection.
//
// Closest point: the surface is charted by central projection of the scaled cube (sq::chart_eval).
// Seeds pick a start: the radial projection, the axis tips, the perpendicular and (inside) the
// axis-parallel ray hits, and three ever-smaller scans of the chart region that can still beat the
// best; each face's best seed near the overall best is refined by trust-region Newton on the two
// free chart coordinates (central-difference Hessian of the analytic gradient); outside, nearer
// support points of the direction to p (exact vertices, tips) are taken. Bound: docs/geometry.md.
// These functions treat every shape as the undeformed superquadric its radii and exponents describe:
// callers pass superquadrics (taper and bend live in deform.cpp).
#include "geometry/superquadric.h"

#include "geometry/measure_internal.h"
#include "supermodal/geometry.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace supermodal
{
namespace
{

// Ellipsoids (ε1 = ε2 = 1, the common case) take F = Σ u_i² with u = p ⊘ a directly while the largest
// u_i lies in [1e-100, 1e100]: there the squares neither overflow nor underflow, and a term lost below
// 1e-200 of the largest changes nothing. Sets u and returns whether the shortcut applies.
bool ellipsoid_shortcut(const ShapeDef& shape, const Vec3& p, Vec3& u)
{
    if (shape.epsilon1 != 1.0 || shape.epsilon2 != 1.0)
        return false;
    u = {p.x / shape.radii.x, p.y / shape.radii.y, p.z / shape.radii.z};
    const double m = std::max({std::abs(u.x), std::abs(u.y), std::abs(u.z)});
    return m >= 1e-100 && m <= 1e100;
}

// ln F alone: one log on the ellipsoid's shortcut instead of seven transcendentals.
double log_f_only(const ShapeDef& shape, const Vec3& p)
{
    Vec3 u;
    if (ellipsoid_shortcut(shape, p, u))
        return std::log(dot(u, u));
    return sq::log_terms(shape, p).log_f;
}

// The contact measure F^(ε1/2) − 1 from ln F; expm1 keeps full relative precision of the small values
// near the surface, where contact lives.
double measure_from_log(const ShapeDef& shape, double log_f)
{
    const double s = 0.5 * shape.epsilon1 * log_f;
    return s > sq::k_log_huge ? sq::k_huge : std::expm1(s);
}

// ∇(F^(ε1/2) − 1) from the point's log-space terms.
Vec3 gradient_from_terms(const ShapeDef& shape, const Vec3& p, const sq::LogTerms& t)
{
    const sq::LogGradient g = sq::log_gradient(shape, p, t);
    const double s = 0.5 * shape.epsilon1 * t.log_f;
    Vec3 grad;
    for (int i = 0; i < 3; ++i) {
        if (g.sign[i] == 0.0)
            continue;
        // Beside a cusp plane (ε > 2) the true slope grows without bound: saturate instead.
        const double v = std::exp(std::min(s + g.log_mag[i], sq::k_log_huge)) / shape.radii[i];
        grad[i] = g.sign[i] * std::min(v, sq::k_huge);
    }
    return grad;
}

// The ellipsoid's ∇(√F − 1) = u ⊘ (a·√F): one square root instead of eleven transcendentals.
Vec3 ellipsoid_gradient(const ShapeDef& shape, const Vec3& u)
{
    const double root = std::sqrt(dot(u, u));
    return {u.x / (shape.radii.x * root), u.y / (shape.radii.y * root), u.z / (shape.radii.z * root)};
}

} // namespace

double inside_outside_log(const ShapeDef& shape, const Vec3& p)
{
    const double log_f = log_f_only(shape, p);
    return log_f == sq::k_neg_inf ? -sq::k_huge : log_f;
}

double inside_outside(const ShapeDef& shape, const Vec3& p)
{
    const double log_f = log_f_only(shape, p);
    return log_f > sq::k_log_huge ? sq::k_huge : std::exp(log_f);
}

double contact_measure(const ShapeDef& shape, const Vec3& p)
{
    return measure_from_log(shape, log_f_only(shape, p));
}

Vec3 contact_measure_gradient(const ShapeDef& shape, const Vec3& p)
{
    Vec3 u;
    if (ellipsoid_shortcut(shape, p, u))
        return ellipsoid_gradient(shape, u);
    return gradient_from_terms(shape, p, sq::log_terms(shape, p));
}

MeasurePoint::MeasurePoint(const ShapeDef& shape, const Vec3& p) : m_shape(&shape), m_p(p)
{
    Vec3 u;
    m_shortcut = ellipsoid_shortcut(shape, p, u);
    if (m_shortcut) {
        m_p = u; // the gradient needs u alone
        m_value = measure_from_log(shape, std::log(dot(u, u)));
        return;
    }
    m_terms = sq::log_terms(shape, p);
    m_value = measure_from_log(shape, m_terms.log_f);
}

Vec3 MeasurePoint::gradient() const
{
    return m_shortcut ? ellipsoid_gradient(*m_shape, m_p) : gradient_from_terms(*m_shape, m_p, m_terms);
}

Vec3 implicit_normal(const ShapeDef& shape, const Vec3& p)
{
    const sq::LogTerms t = sq::log_terms(shape, p);
    const sq::LogGradient g = sq::log_gradient(shape, p, t);
    return sq::unit_from_logs(g.log_mag, g.sign, shape.radii);
}

double signed_power(double x, double e)
{
    if (x == 0.0)
        return 0.0; // sign(0) = 0, also for e ≤ 0 where |0|^e is not finite
    const double m = std::pow(std::abs(x), e);
    return std::copysign(std::min(m, sq::k_huge), x);
}

Vec3 surface_point(const ShapeDef& shape, double eta, double omega)
{
    const double ce = signed_power(std::cos(eta), shape.epsilon1);
    return {shape.radii.x * ce * signed_power(std::cos(omega), shape.epsilon2),
            shape.radii.y * ce * signed_power(std::sin(omega), shape.epsilon2),
            shape.radii.z * signed_power(std::sin(eta), shape.epsilon1)};
}

Vec3 surface_normal(const ShapeDef& shape, double eta, double omega)
{
    // Barr: n ∝ (cos^(2−ε1)η cos^(2−ε2)ω / a1, cos^(2−ε1)η sin^(2−ε2)ω / a2, sin^(2−ε1)η / a3). The
    // exponents are negative for ε > 2, so the powers go through logs and the largest is factored out.
    const double f[4] = {std::cos(eta), std::sin(eta), std::cos(omega), std::sin(omega)};
    double lg[4], sg[4];
    for (int i = 0; i < 4; ++i) {
        lg[i] = std::log(std::abs(f[i]));
        sg[i] = f[i] > 0.0 ? 1.0 : (f[i] < 0.0 ? -1.0 : 0.0);
    }
    const double k1 = 2.0 - shape.epsilon1, k2 = 2.0 - shape.epsilon2;
    const double log_mag[3] = {k1 * lg[0] + k2 * lg[2], k1 * lg[0] + k2 * lg[3], k1 * lg[1]};
    const double sign[3] = {sg[0] * sg[2], sg[0] * sg[3], sg[1]};
    return sq::unit_from_logs(log_mag, sign, shape.radii);
}

double radial_distance(const ShapeDef& shape, const Vec3& p)
{
    const double m = std::max({std::abs(p.x), std::abs(p.y), std::abs(p.z)});
    if (m == 0.0)
        return -shape.radii.z; // the centre: along +z, the direction implicit_normal reports there
    const double s = 0.5 * shape.epsilon1 * log_f_only(shape, p);
    const double r = length(p / m) * m;
    if (s > -1.0) // |p|·(1 − F^(−ε1/2)), with expm1 for precision near the surface
        return -r * std::expm1(-s);
    // Near the centre F^(−ε1/2) is huge: take the ray's radius from the rescaled point instead.
    const Vec3 c = p / m;
    return r - length(c) * std::exp(-0.5 * shape.epsilon1 * sq::log_terms(shape, c).log_f);
}

// ---- Closest point --------------------------------------------------------------------------------

namespace
{

using sq::chart_eval;
using sq::ChartPoint;

// Newton stops once the tangential part t of p − x gives (|r| − |r·n|) = t²/(|r| + |r·n|) below this
// fraction of the largest radius: a few hundred ulps, the precision x itself is computed to.
constexpr double k_converged_rel = 1e-13;
constexpr int k_max_newton = 60;
// Progress below this relative decrease of |p − x|² for k_max_stalls iterations in a row ends the
// refinement: ~50 ulps, where only round-off changes remain.
constexpr double k_stall_rel = 1e-14;
constexpr int k_max_stalls = 3;
// Central-difference step in chart coordinates (c ∈ [−1, 1]): truncation ~h² and cancellation
// ~1e-16/h balance near 1e-5…1e-6; Newton only needs a few correct digits of the Hessian.
constexpr double k_fd_step = 1e-6;
// Scan: k×k points per cube face, repeated as the reachable region shrinks. Inside points and concave
// shapes have several local minima of the distance; with refinement from each face's best seed and
// the far-facet restart, 4×4 per round found the global minimum in every convex case of a 1536-case
// grid, as 5×5 and 6×6 did, in 25% less time than 6×6.
constexpr int k_scan = 4;
constexpr int k_scan_rounds = 3;
constexpr double k_rescan_shrink = 0.7;
// Seeds of other faces are refined too when their distance is within this factor of the best's.
constexpr double k_restart_ratio = 1.5;

// Chart points of a k×k grid over each face, restricted to the rays that can meet the ball of radius
// `reach` around p (no surface point outside that ball can beat the current best).
template <class Consider>
void scan_ball(const ShapeDef& shape, const Vec3& p, double reach, Consider&& consider)
{
    const Vec3 inv_a{1 / shape.radii.x, 1 / shape.radii.y, 1 / shape.radii.z}, ball{reach, reach, reach};
    const Vec3 lo = hadamard(p - ball, inv_a), hi = hadamard(p + ball, inv_a);
    for (int face = 0; face < 6; ++face) {
        const int k = face / 2;
        const double s = face % 2 == 0 ? 1.0 : -1.0;
        // Range of s·u_k over the box; rays of this face have s·u_k = max |u| > 0.
        const double uk_lo = std::min(s * lo[k], s * hi[k]), uk_hi = std::max(s * lo[k], s * hi[k]);
        if (uk_hi <= 0.0)
            continue;
        double c_lo[2] = {-1.0, -1.0}, c_hi[2] = {1.0, 1.0};
        for (int m = 0; m < 2 && uk_lo > 0.0; ++m) {
            const int j = (k + 1 + m) % 3;
            // u_j / (s u_k) over a box whose denominator keeps one sign: extremes at the corners.
            const double r[4] = {lo[j] / uk_lo, lo[j] / uk_hi, hi[j] / uk_lo, hi[j] / uk_hi};
            c_lo[m] = std::max(-1.0, std::min({r[0], r[1], r[2], r[3]}));
            c_hi[m] = std::min(1.0, std::max({r[0], r[1], r[2], r[3]}));
        }
        if (c_lo[0] > c_hi[0] || c_lo[1] > c_hi[1])
            continue;
        for (int m = 0; m < 2; ++m) { // the warp is monotonic: map the range's ends
            const double inv = 1.0 / sq::warp(shape, k, (k + 1 + m) % 3);
            c_lo[m] = signed_power(c_lo[m], inv);
            c_hi[m] = signed_power(c_hi[m], inv);
        }
        for (int i = 0; i < k_scan; ++i)
            for (int l = 0; l < k_scan; ++l) {
                Vec3 u;
                u[k] = s;
                u[(k + 1) % 3] = c_lo[0] + (c_hi[0] - c_lo[0]) * i / (k_scan - 1);
                u[(k + 2) % 3] = c_lo[1] + (c_hi[1] - c_lo[1]) * l / (k_scan - 1);
                consider(u);
            }
    }
}

// Seeds: the best chart point found on each of the six cube faces (slot 2·axis + (negative side)).
using FaceSeeds = std::array<ChartPoint, 6>;

FaceSeeds face_seeds(const ShapeDef& shape, const Vec3& p)
{
    FaceSeeds best;
    for (ChartPoint& b : best)
        b.f = INFINITY;
    double best_f = INFINITY;
    const auto consider = [&](const Vec3& u) {
        if (!is_finite(u))
            return;
        const int face = sq::face_of(u);
        const ChartPoint q = chart_eval(shape, p, u, face);
        ChartPoint& slot = best[2 * face + (u[face] < 0.0 ? 1 : 0)];
        if (q.f < slot.f)
            slot = q;
        best_f = std::min(best_f, q.f);
    };
    if (p.x != 0.0 || p.y != 0.0 || p.z != 0.0)
        consider(sq::chart_of(shape, p));
    // Axis tips: the cusps of concave shapes, where the chart is too stretched for the scan to land.
    for (int i = 0; i < 6; ++i) {
        Vec3 c;
        c[i / 2] = i % 2 == 0 ? 1.0 : -1.0;
        consider(c);
    }
    std::array<Vec3, 9> hits;
    const int hit_count = sq::ray_hits(shape, p, contact_measure(shape, p) < 0.0, hits);
    for (int i = 0; i < hit_count; ++i)
        consider(sq::chart_of(shape, hits[i]));
    // Each scan shrinks the ball to the best distance so far, so the next one is denser where it
    // matters; one that did not shrink it much would only repeat itself.
    double reach = INFINITY;
    for (int round = 0; round < k_scan_rounds; ++round) {
        const double r = best_f < INFINITY ? std::sqrt(2.0 * best_f) : length(p) + length(shape.radii);
        if (r > k_rescan_shrink * reach)
            break;
        reach = r;
        scan_ball(shape, p, reach, consider);
    }
    return best;
}

// One trust-region Newton step on the two free chart coordinates. Returns false when the region has
// shrunk below round-off.
bool newton_step(const ShapeDef& shape, const Vec3& p, ChartPoint& q, double& radius)
{
    const int face = sq::face_of(q.u);
    double h[2][2];
    for (int k = 0; k < 2; ++k) {
        const int j = (face + 1 + k) % 3;
        Vec3 cp = q.u, cm = q.u;
        cp[j] += k_fd_step;
        cm[j] -= k_fd_step;
        const ChartPoint a = chart_eval(shape, p, cp, face), b = chart_eval(shape, p, cm, face);
        for (int l = 0; l < 2; ++l)
            h[l][k] = (a.df[l] - b.df[l]) / (2.0 * k_fd_step);
    }
    const double off = 0.5 * (h[0][1] + h[1][0]);
    // Shift the spectrum so the model is convex: the smallest eigenvalue becomes at least 1e-9 of the
    // scale, which turns an indefinite Newton step into a damped gradient step.
    const double mean = 0.5 * (h[0][0] + h[1][1]), dev = std::hypot(0.5 * (h[0][0] - h[1][1]), off);
    const double scale = std::abs(mean) + dev + 1e-300;
    const double shift = std::max(0.0, 1e-9 * scale - (mean - dev));
    const double h00 = h[0][0] + shift, h11 = h[1][1] + shift, det = h00 * h11 - off * off;
    if (!(det > 0.0) || !std::isfinite(det) || !std::isfinite(q.df[0]) || !std::isfinite(q.df[1]))
        return false;
    for (;;) {
        double s0 = -(h11 * q.df[0] - off * q.df[1]) / det, s1 = -(h00 * q.df[1] - off * q.df[0]) / det;
        const double len = std::hypot(s0, s1);
        if (!(len <= radius)) {
            s0 *= radius / len;
            s1 *= radius / len;
        }
        Vec3 u = q.u;
        u[(face + 1) % 3] += s0;
        u[(face + 2) % 3] += s1;
        if (std::abs(u[(face + 1) % 3]) > 1.0 || std::abs(u[(face + 2) % 3]) > 1.0)
            u = sq::warp_from_c(shape,
                                sq::rewarp(shape, u, face, false)); // onto the face the ray now crosses
        const ChartPoint trial = chart_eval(shape, p, u, sq::face_of(u));
        if (trial.f <= q.f) {
            radius = std::min(1.0, std::max(radius, 2.0 * std::min(len, radius)));
            q = trial;
            return true;
        }
        radius = 0.25 * std::min(len, radius);
        if (radius < 1e-15)
            return false;
    }
}

// Bound on |found distance| − |true distance| at surface point x (see docs/geometry.md), the normal
// that gives it, and (outside) the support point of the direction from x to p.
struct Gap {
    double bound = 0.0;
    Vec3 normal{};
    Vec3 support{};
    bool has_support = false;
};
Gap projection_gap(const ShapeDef& shape, const Vec3& p, const Vec3& x, double side)
{
    // |r| − side·(r·n) (side = +1 outside, −1 inside): how much the tangent plane at x would let the
    // distance shrink; large when p lies behind it (a stationary point that is not the nearest, such
    // as the foot of p on a far facet). Computed as |t|²/(|r| + side·(r·n)), t the tangential part.
    Gap g;
    const Vec3 r = p - x;
    g.normal = implicit_normal(shape, x);
    const double d = length(r), dn = side * dot(r, g.normal);
    const Vec3 t = r - dot(r, g.normal) * g.normal;
    g.bound = dn <= 0.0 ? d - dn : dot(t, t) / (d + dn);
    if (side > 0.0 && d > 0.0) {
        // Outside, the plane through the support point of r̂ separates p from the (hull of the) body
        // by r̂·p − h(r̂), a lower bound on the distance even at edges and tips, where no single
        // tangent plane faces p. Its gap |r| − (r̂·p − h(r̂)) equals r̂·(s − x).
        const Vec3 r_hat = r / d;
        g.support = support_point(shape, r_hat);
        g.has_support = true;
        const double support_gap = std::max(0.0, dot(r_hat, g.support - x));
        if (support_gap < g.bound) {
            g.bound = support_gap;
            g.normal = r_hat;
        }
    }
    return g;
}

struct Refined {
    ChartPoint q;
    Gap gap;
    int iterations = 0;
    bool converged = false;
};

Refined refine(const ShapeDef& shape, const Vec3& p, double side, const ChartPoint& seed)
{
    const double size = std::max({shape.radii.x, shape.radii.y, shape.radii.z});
    Refined out{seed, projection_gap(shape, p, seed.x, side)};
    double radius = 0.25;
    int stalls = 0;
    for (; out.iterations < k_max_newton; ++out.iterations) {
        if (out.gap.bound <= k_converged_rel * size) {
            out.converged = true;
            break;
        }
        const double f_before = out.q.f;
        const bool moved = newton_step(shape, p, out.q, radius);
        out.gap = projection_gap(shape, p, out.q.x, side);
        // Support points are points of the shape (hull vertices of concave ones); one nearer than x
        // jumps straight to a vertex or tip, where Newton on a kink would creep. Only after the
        // Newton step: on its own this fixed-point step converges just linearly.
        const Vec3 s = out.gap.support;
        if (out.gap.has_support && 0.5 * dot(p - s, p - s) < out.q.f) {
            out.q = sq::chart_at(shape, p, s);
            out.gap = projection_gap(shape, p, out.q.x, side);
        } else if (!moved) {
            break;
        }
        // On a kink or cusp Newton creeps: stop once the distance no longer improves beyond round-off.
        stalls = out.q.f < f_before * (1.0 - k_stall_rel) ? 0 : stalls + 1;
        if (stalls >= k_max_stalls)
            break;
    }
    return out;
}

} // namespace

SurfaceProjection closest_point(const ShapeDef& shape, const Vec3& p)
{
    const double side = contact_measure(shape, p) > 0.0 ? 1.0 : -1.0;
    const FaceSeeds seeds = face_seeds(shape, p);
    std::array<int, 6> order = {0, 1, 2, 3, 4, 5}; // by distance, ties by face: a total order
    std::sort(order.begin(), order.end(),
              [&](int a, int b) { return seeds[a].f < seeds[b].f || (seeds[a].f == seeds[b].f && a < b); });
    Refined best = refine(shape, p, side, seeds[order[0]]);
    int iterations = best.iterations;
    const auto try_seed = [&](const ChartPoint& seed) {
        const Refined r = refine(shape, p, side, seed);
        iterations += r.iterations;
        if (r.q.f < best.q.f)
            best = r;
    };
    // Refine those of other faces that start not much farther: different faces hold the competing
    // local minima (a box's faces seen from inside, a concave shape's arms).
    for (int i = 1; i < 6 && seeds[order[i]].f <= k_restart_ratio * k_restart_ratio * seeds[order[0]].f; ++i)
        try_seed(seeds[order[i]]);
    // Outside, a minimum with p behind its tangent plane is the foot on a far facet: the support point
    // of the direction to p lies on the near side, so start once more from there.
    if (side > 0.0 && best.gap.has_support && dot(p - best.q.x, implicit_normal(shape, best.q.x)) < 0.0)
        try_seed(sq::chart_at(shape, p, best.gap.support));
    // x itself lies on the surface only to the precision of its measure, which adds |measure|·|x|.
    return {.point = best.q.x,
            .normal = best.gap.normal,
            .distance = side * length(p - best.q.x),
            .error_bound = best.gap.bound + std::abs(contact_measure(shape, best.q.x)) * length(best.q.x),
            .iterations = iterations,
            .converged = best.converged};
}

} // namespace supermodal
