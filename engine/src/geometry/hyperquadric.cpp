// SPDX-License-Identifier: MIT
// Hyperquadrics H(x) = Σ_i |n_i·x + d_i|^γ_i ≤ 1 (Hanson 1988; Williams & Pentland 1992 cut a 4-D
// hypercube by a hyperplane, which gives four such terms in 3-D). H is evaluated as a log-sum-exp so
// no power overflows. Surfaces come from rays: with every γ ≥ 1 the body is convex, hence star-shaped
// about any interior point: rays from the minimiser of H, each cut with the surface H = 1, give
// meshes and samples (hyperquadric_mesh.cpp) and mass properties (mass_deformed.cpp). Each ray is
// bracketed by the slabs |n_i·x + d_i| ≤ 1 that contain the body, so the root-finding cannot miss.
#include "geometry/hyperquadric_solve.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace supermodal
{
namespace
{

/// ln H at a point where every term vanishes; matches inside_outside_log's value at the centre.
constexpr double k_log_zero = -1e300;
/// H saturates here instead of overflowing (geometry.h).
constexpr double k_value_max = 1e300;
/// Unit normals whose Gram matrix has det/(trace/3)³ below this lie within ~0.03 rad of one plane: the
/// body would reach ~1/0.03 slab widths or, at 0, infinitely far; such terms are called unbounded.
constexpr double k_min_span = 1e-6;
/// Terms this close to zero (in units of their slab half-width) use this value in the Hessian model
/// of the centre search, so γ < 2 terms do not give infinite curvature there.
constexpr double k_term_floor = 1e-6;
/// Added to the Hessian model's diagonal (relative to its trace) so a term whose weight underflowed
/// cannot make it singular; far below any real curvature, so steps are unchanged otherwise.
constexpr double k_hessian_ridge = 1e-12;
constexpr int k_center_iterations = 60;
constexpr int k_max_halvings = 40;
constexpr int k_ray_iterations = 200;
/// A ray root is done when its bracket is this many ulps of the distance wide.
constexpr double k_ray_tolerance = 4.0 * std::numeric_limits<double>::epsilon();

double term_value(const HyperquadricTerm& t, const Vec3& p)
{
    return dot(t.normal, p) + t.offset;
}

/// Solves a·x = b by Cramer's rule; false when a is singular.
bool solve3(const Mat3& a, const Vec3& b, Vec3& out_x)
{
    const double det = dot(a.row(0), cross(a.row(1), a.row(2)));
    if (!(std::abs(det) > 0.0) || !std::isfinite(det))
        return false;
    const Vec3 c0 = cross(a.row(1), a.row(2)), c1 = cross(a.row(2), a.row(0)), c2 = cross(a.row(0), a.row(1));
    out_x = (c0 * b.x + c1 * b.y + c2 * b.z) / det;
    return is_finite(out_x);
}

void add_outer(Mat3& m, const Vec3& n, double w)
{
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            m.m[i][j] += w * n[i] * n[j];
}

/// One damped Newton direction for minimising H at x, scaled so its weights cannot overflow.
bool center_step(const ShapeDef& shape, const Vec3& x, Vec3& out_step)
{
    double lg_max = -std::numeric_limits<double>::infinity();
    for (const HyperquadricTerm& t : shape.terms) {
        const double lt = std::log(std::max(std::abs(term_value(t, x)), k_term_floor));
        const double g = t.exponent;
        lg_max = std::max(
            {lg_max, std::log(g) + (g - 1.0) * lt, std::log(g * std::max(g - 1.0, 1.0)) + (g - 2.0) * lt});
    }
    Vec3 grad{};
    Mat3 hess{};
    for (const HyperquadricTerm& t : shape.terms) {
        const double v = term_value(t, x);
        const double lt = std::log(std::max(std::abs(v), k_term_floor));
        const double g = t.exponent;
        grad += t.normal * (std::copysign(1.0, v) * std::exp(std::log(g) + (g - 1.0) * lt - lg_max));
        // max(γ − 1, 1) keeps the model positive definite for γ < 2 (an over-estimate: shorter steps).
        add_outer(hess, t.normal, std::exp(std::log(g * std::max(g - 1.0, 1.0)) + (g - 2.0) * lt - lg_max));
    }
    const double trace = hess.m[0][0] + hess.m[1][1] + hess.m[2][2];
    for (int i = 0; i < 3; ++i)
        hess.m[i][i] += k_hessian_ridge * trace;
    return solve3(hess, -grad, out_step);
}

} // namespace

double hyperquadric_log_value(const ShapeDef& shape, const Vec3& p)
{
    // Streaming log-sum-exp: the running sum is kept relative to the largest log term seen so far.
    double m = -std::numeric_limits<double>::infinity(), sum = 0.0;
    for (const HyperquadricTerm& t : shape.terms) {
        const double a = std::abs(term_value(t, p));
        if (a == 0.0)
            continue;
        // A NaN term (non-finite input) counts as far outside rather than spreading.
        const double l =
            std::isnan(a) ? k_value_max : std::clamp(t.exponent * std::log(a), -k_value_max, k_value_max);
        if (l > m) {
            sum = sum * std::exp(m - l) + 1.0;
            m = l;
        } else {
            sum += std::exp(l - m);
        }
    }
    if (!(m > -std::numeric_limits<double>::infinity()))
        return k_log_zero;
    return std::min(m + std::log(sum), k_value_max);
}

double hyperquadric_value(const ShapeDef& shape, const Vec3& p)
{
    const double l = hyperquadric_log_value(shape, p);
    return l >= std::log(k_value_max) ? k_value_max : std::exp(l);
}

Vec3 hyperquadric_normal(const ShapeDef& shape, const Vec3& p)
{
    // ∇H = Σ γ_i sign(t_i)|t_i|^(γ_i − 1) n_i, scaled by the largest weight so nothing overflows. A
    // vanishing term with γ < 1 has an infinite weight: those terms alone give the direction.
    double w_max = -std::numeric_limits<double>::infinity();
    bool singular = false;
    for (const HyperquadricTerm& t : shape.terms) {
        const double a = std::abs(term_value(t, p));
        if (a == 0.0)
            singular = singular || t.exponent < 1.0;
        else
            w_max = std::max(w_max, std::log(t.exponent) + (t.exponent - 1.0) * std::log(a));
    }
    Vec3 g{};
    for (const HyperquadricTerm& t : shape.terms) {
        const double v = term_value(t, p);
        if (singular)
            g += v == 0.0 && t.exponent < 1.0 ? normalized(t.normal) : Vec3{};
        else if (v != 0.0)
            g += t.normal *
                 std::copysign(
                     std::exp(std::log(t.exponent) + (t.exponent - 1.0) * std::log(std::abs(v)) - w_max), v);
    }
    const Vec3 n = normalized(g);
    return is_finite(n) && dot(n, n) > 0.5 ? n : Vec3{0, 0, 1};
}

double hyperquadric_measure(const ShapeDef& shape, const Vec3& p)
{
    double gamma_max = 0.0;
    for (const HyperquadricTerm& t : shape.terms)
        gamma_max = std::max(gamma_max, t.exponent);
    if (!(gamma_max > 0.0))
        return 1.0;
    // H^(1/γmax) grows like the distance for large |p| (the steepest term dominates there).
    return std::min(std::expm1(hyperquadric_log_value(shape, p) / gamma_max), k_value_max);
}

HyperquadricCenter hyperquadric_center(const ShapeDef& shape)
{
    HyperquadricCenter out;
    Mat3 gram{}, normal_eq{};
    Vec3 rhs{};
    for (const HyperquadricTerm& t : shape.terms) {
        if (!is_finite(t.normal) || !std::isfinite(t.offset) || !(t.exponent > 0.0))
            return out;
        add_outer(gram, normalized(t.normal), 1.0);
        add_outer(normal_eq, t.normal, 1.0);
        rhs -= t.normal * t.offset;
    }
    const double trace = gram.m[0][0] + gram.m[1][1] + gram.m[2][2];
    const double det = dot(gram.row(0), cross(gram.row(1), gram.row(2)));
    out.is_bounded = trace > 0.0 && det >= k_min_span * std::pow(trace / 3.0, 3);
    if (!out.is_bounded || !solve3(normal_eq, rhs, out.point))
        return out;
    // Least squares puts every term near zero; Newton then balances terms of different exponents.
    double log_h = hyperquadric_log_value(shape, out.point);
    for (int it = 0; it < k_center_iterations; ++it) {
        Vec3 step;
        if (!center_step(shape, out.point, step))
            break;
        double t = 1.0;
        bool improved = false;
        for (int h = 0; h < k_max_halvings && !improved; ++h, t *= 0.5) {
            const Vec3 trial = out.point + t * step;
            const double l = hyperquadric_log_value(shape, trial);
            if (l < log_h) {
                out.point = trial;
                log_h = l;
                improved = true;
            }
        }
        if (!improved)
            break;
    }
    out.log_value = log_h;
    out.is_non_empty = log_h < 0.0;
    return out;
}

double hyperquadric_ray_exit(const ShapeDef& shape, const Vec3& center, const Vec3& direction)
{
    // H ≤ 1 forces every |t_i| ≤ 1, so the nearest slab face along the ray bounds the exit: H ≥ 1 there.
    double hi = std::numeric_limits<double>::infinity();
    for (const HyperquadricTerm& t : shape.terms) {
        const double nd = dot(t.normal, direction);
        const double tc = term_value(t, center);
        if (nd != 0.0)
            hi = std::min(hi, (nd > 0.0 ? 1.0 - tc : 1.0 + tc) / std::abs(nd));
    }
    if (!(hi > 0.0) || !std::isfinite(hi))
        return 0.0;
    // Safeguarded Newton (Numerical Recipes' rtsafe) on H^(1/γmax) − 1, which is close to linear in r
    // (exactly, for equal exponents around a common zero), where H − 1 would crawl in by (1 − 1/γ) per
    // step. On [0, hi] H ≤ term count, so nothing overflows.
    double gamma_max = 0.0;
    for (const HyperquadricTerm& t : shape.terms)
        gamma_max = std::max(gamma_max, t.exponent);
    const auto f = [&](double r, double& out_slope) {
        const Vec3 p = center + r * direction;
        double h = 0.0, slope = 0.0;
        for (const HyperquadricTerm& t : shape.terms) {
            const double v = term_value(t, p), a = std::abs(v);
            if (a == 0.0)
                continue;
            const double pw = std::pow(a, t.exponent);
            h += pw;
            slope += t.exponent * pw / v * dot(t.normal, direction);
        }
        const double root = std::pow(h, 1.0 / gamma_max);
        out_slope = root / (gamma_max * h) * slope;
        return root - 1.0;
    };
    double lo = 0.0, r = hi, slope = 0.0;
    double value = f(r, slope);
    for (int it = 0; it < k_ray_iterations && value != 0.0 && hi - lo > k_ray_tolerance * hi; ++it) {
        (value > 0.0 ? hi : lo) = r;
        const double newton = r - value / slope;
        r = (std::isfinite(newton) && newton > lo && newton < hi) ? newton : 0.5 * (lo + hi);
        value = f(r, slope);
    }
    return r;
}

} // namespace supermodal
