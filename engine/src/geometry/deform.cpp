// SPDX-License-Identifier: MIT
// Barr's global deformations along the polar axis z: taper, then bend (Barr 1984; Solina & Bajcsy 1990,
// "Recovery of parametric models from range images", eqs. 10-13).
//   taper: x_t = (1 + kx·z/a3)·x,  y_t = (1 + ky·z/a3)·y,  z_t = z.
//   bend (curvature k, plane at angle α from x): with u = x_t·cos α + y_t·sin α, θ = k·z, σ = 1 − k·u,
//         u' = u + σ·(1 − cos θ)/k,  z' = σ·sin θ / k,  the component normal to the plane unchanged.
// The z axis becomes an arc of radius 1/k of the same length. det J = (1 + kx·z/a3)(1 + ky·z/a3)·σ, so
// the map is locally invertible exactly where all three factors are positive; with |θ| < π as well it
// is one-to-one there (domain D). The bend and the taper both have closed-form inverses on D; Newton's
// method only polishes their round-off, and the guard reports points whose preimage is not in D.
#include "geometry/deform_internal.h"
#include "geometry/hyperquadric_solve.h"
#include "supermodal/geometry.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace supermodal
{
namespace
{

/// Below this a Jacobian factor (taper factor or bend σ) counts as zero: the inverse would amplify
/// round-off by more than 1/k_min_factor = 10^6, so the preimage could not be trusted to 1e-9 of the
/// body size; such points are reported as not invertible.
constexpr double k_min_factor = 1e-6;
/// Below k·size this small the bend moves no point by more than 1e-150 of the body: treated as none,
/// so sin(kz)/k never works on subnormal numbers.
constexpr double k_min_relative_curvature = 1e-150;
/// Newton accepts a preimage whose forward image is within this fraction of max(body size, |q|) of q;
/// the closed-form start is already within a few ulps, so this only rejects a broken polish.
constexpr double k_accept_residual = 1e-12;
/// Newton stops once the residual is this many ulps of the scale: round-off floor of the forward map.
constexpr double k_stop_residual = 8.0 * std::numeric_limits<double>::epsilon();
constexpr int k_max_newton_iterations = 20;
constexpr int k_max_halvings = 30;
/// Returned by shape_measure where the inverse map fails: positive (outside), so an unresolved point
/// never produces a contact force, and small, so it does not look like a distant point either.
constexpr double k_unresolved_measure = 1e-3;

/// sin x / x; below |x| = 1e-8 the series' next term x⁴/120 is far under an ulp, and 0/0 is avoided.
double sinc(double x)
{
    return std::abs(x) < 1e-8 ? 1.0 - x * x / 6.0 : std::sin(x) / x;
}

Vec3 forward(const Deformation& d, const Vec3& p)
{
    return deform_with(d, p, bend_arc(d, p.z));
}

Mat3 jacobian(const Deformation& d, const Vec3& p)
{
    const double fx = 1.0 + d.kx * p.z / d.a3, fy = 1.0 + d.ky * p.z / d.a3;
    Mat3 jt = Mat3::diagonal({fx, fy, 1.0});
    jt.m[0][2] = d.kx * p.x / d.a3;
    jt.m[1][2] = d.ky * p.y / d.a3;
    if (!d.has_bend)
        return jt;
    const double u = d.c * fx * p.x + d.s * fy * p.y;
    const double theta = d.k * p.z;
    const double sigma = 1.0 - d.k * u;
    const double one_minus_cos = 2.0 * std::sin(0.5 * theta) * std::sin(0.5 * theta);
    const double sin_t = std::sin(theta), cos_t = std::cos(theta);
    // Differentiate u' − u = σ(1 − cos θ)/k and z' = σ sin θ/k with ∂σ/∂u = −k, ∂θ/∂z = k.
    const double plane[2] = {d.c, d.s};
    Mat3 jb = Mat3::identity();
    for (int i = 0; i < 2; ++i) {
        for (int j = 0; j < 2; ++j)
            jb.m[i][j] -= plane[i] * one_minus_cos * plane[j];
        jb.m[i][2] = plane[i] * sigma * sin_t;
        jb.m[2][i] = -sin_t * plane[i];
    }
    jb.m[2][2] = sigma * cos_t;
    return jb * jt;
}

/// Cofactor matrix: det(J)·J^(−T), finite even where J is singular.
Mat3 cofactor(const Mat3& a)
{
    Mat3 r;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
            const int i1 = (i + 1) % 3, i2 = (i + 2) % 3, j1 = (j + 1) % 3, j2 = (j + 2) % 3;
            r.m[i][j] = a.m[i1][j1] * a.m[i2][j2] - a.m[i1][j2] * a.m[i2][j1];
        }
    return r;
}

double determinant(const Mat3& a)
{
    return dot(a.row(0), cross(a.row(1), a.row(2)));
}

/// True where all three Jacobian factors are clearly positive and the bend angle stays within a half
/// turn: the map is one-to-one and well conditioned around p.
bool in_domain(const Deformation& d, const Vec3& p)
{
    const double fx = 1.0 + d.kx * p.z / d.a3, fy = 1.0 + d.ky * p.z / d.a3;
    if (!(fx > k_min_factor && fy > k_min_factor))
        return false;
    if (!d.has_bend)
        return true;
    const double sigma = 1.0 - d.k * (d.c * fx * p.x + d.s * fy * p.y);
    return sigma > k_min_factor && std::abs(d.k * p.z) < std::numbers::pi - k_min_factor;
}

/// Closed-form inverse on D: undo the bend (polar coordinates about the centre of curvature), then the
/// taper. Outside D it still returns finite numbers (factors clamped), which the caller rejects.
Vec3 closed_form_inverse(const Deformation& d, const Vec3& q)
{
    Vec3 t = q;
    if (d.has_bend) {
        const double u1 = d.c * q.x + d.s * q.y;
        const double w = -d.s * q.x + d.c * q.y;
        const double sigma1 = 1.0 - d.k * u1;
        const double sigma = std::hypot(sigma1, d.k * q.z);
        const double theta = std::atan2(d.k * q.z, sigma1);
        // u = (1 − σ)/k rewritten as (1 − σ²)/(k(1 + σ)) so small curvatures do not cancel.
        const double u = (2.0 * u1 - d.k * (u1 * u1 + q.z * q.z)) / (1.0 + sigma);
        t = {u * d.c - w * d.s, u * d.s + w * d.c, theta / d.k};
    }
    const double fx = std::max(1.0 + d.kx * t.z / d.a3, k_min_factor);
    const double fy = std::max(1.0 + d.ky * t.z / d.a3, k_min_factor);
    return {t.x / fx, t.y / fy, t.z};
}

} // namespace

Deformation deformation_of(const ShapeDef& shape)
{
    Deformation d;
    d.kx = shape.taper.kx;
    d.ky = shape.taper.ky;
    d.a3 = shape.radii.z > 0.0 ? shape.radii.z : 1.0;
    const double size = std::max({shape.radii.x, shape.radii.y, shape.radii.z});
    d.has_bend =
        shape.bend.curvature * size > k_min_relative_curvature && std::isfinite(shape.bend.curvature);
    if (d.has_bend) {
        d.k = shape.bend.curvature;
        d.c = std::cos(shape.bend.angle);
        d.s = std::sin(shape.bend.angle);
    }
    return d;
}

BendArc bend_arc(const Deformation& d, double z)
{
    if (!d.has_bend)
        return {};
    // (1 − cos θ)/k = (k z²/2)·sinc²(θ/2) and sin θ/k = z·sinc θ: no cancellation or 0/0 as k → 0.
    const double theta = d.k * z, half_sinc = sinc(0.5 * theta);
    return {0.5 * d.k * z * z * half_sinc * half_sinc, z * sinc(theta)};
}

bool is_deformed(const ShapeDef& shape)
{
    return shape.type != ShapeType::Plane &&
           (shape.taper.kx != 0.0 || shape.taper.ky != 0.0 || shape.bend.curvature != 0.0);
}

Vec3 deform_point(const ShapeDef& shape, const Vec3& p)
{
    return is_deformed(shape) ? forward(deformation_of(shape), p) : p;
}

Mat3 deform_jacobian(const ShapeDef& shape, const Vec3& p)
{
    return is_deformed(shape) ? jacobian(deformation_of(shape), p) : Mat3::identity();
}

Vec3 deform_normal(const ShapeDef& shape, const Vec3& p, const Vec3& normal)
{
    if (!is_deformed(shape))
        return normalized(normal);
    const Mat3 j = jacobian(deformation_of(shape), p);
    // cof(J) = det(J)·J^(−T): same direction as the inverse-transpose when det > 0, and finite at det = 0.
    Vec3 n = cofactor(j) * normal;
    if (determinant(j) < 0.0)
        n = -n;
    const Vec3 unit = normalized(n);
    return is_finite(unit) && dot(unit, unit) > 0.5 ? unit : normalized(normal);
}

UndeformResult undeform_point(const ShapeDef& shape, const Vec3& q)
{
    if (!is_finite(q))
        return {.point = Vec3{}, .converged = false, .iterations = 0};
    UndeformResult result{.point = q, .converged = true, .iterations = 0};
    if (!is_deformed(shape))
        return result;
    const Deformation d = deformation_of(shape);
    const double size = std::max({shape.radii.x, shape.radii.y, shape.radii.z});
    const double scale = std::max(size, length(q));
    Vec3 p = closed_form_inverse(d, q);
    if (!is_finite(p))
        p = q;
    double residual = length(forward(d, p) - q);
    for (int it = 0; it < k_max_newton_iterations && residual > k_stop_residual * scale; ++it) {
        const Mat3 j = jacobian(d, p);
        const double det = determinant(j);
        if (!(std::abs(det) > 0.0) || !std::isfinite(det))
            break;
        const Vec3 step = (transpose(cofactor(j)) * (forward(d, p) - q)) / det;
        // Backtracking: the step must lower the residual, or Newton has left its basin and stops.
        double t = 1.0;
        bool improved = false;
        for (int h = 0; h < k_max_halvings && !improved; ++h, t *= 0.5) {
            const Vec3 trial = p - t * step;
            const double r = length(forward(d, trial) - q);
            if (is_finite(trial) && r < residual) {
                p = trial;
                residual = r;
                improved = true;
            }
        }
        result.iterations = it + 1;
        if (!improved)
            break;
    }
    result.point = is_finite(p) ? p : q;
    result.converged = residual <= k_accept_residual * scale && in_domain(d, result.point);
    return result;
}

double shape_measure(const ShapeDef& shape, const Vec3& q)
{
    if (shape.type == ShapeType::Plane)
        return dot(normalized(shape.plane_normal), q) - shape.plane_offset;
    const auto base = [&](const Vec3& p) {
        return shape.type == ShapeType::Hyperquadric ? hyperquadric_measure(shape, p)
                                                     : contact_measure(shape, p);
    };
    if (!is_deformed(shape))
        return base(q);
    const UndeformResult r = undeform_point(shape, q);
    const double m = base(r.point);
    return r.converged ? m : std::max(m, k_unresolved_measure);
}

} // namespace supermodal
