// SPDX-License-Identifier: MIT
#include "dynamics/rotation.h"

#include <cmath>

namespace supermodal
{
namespace
{

// Newton stops when the residual is this far below |Π|: a few hundred ulps, so the invariants drift
// by less than 1e-12 over 10^4 steps (measured in tests/dynamics/rotation_test.cpp).
constexpr double k_newton_rel_tol = 1e-14;
constexpr int k_newton_max_iterations = 20;

// Solves A x = b by Cramer's rule; returns false for a (numerically) singular A.
bool solve3(const Mat3& a, const Vec3& b, Vec3& out_x)
{
    const Vec3 c0 = a.col(0), c1 = a.col(1), c2 = a.col(2);
    const double det = dot(c0, cross(c1, c2));
    if (!(std::abs(det) > 0.0) || !std::isfinite(det))
        return false;
    out_x = Vec3{dot(b, cross(c1, c2)), dot(c0, cross(b, c2)), dot(c0, cross(c1, b))} / det;
    return true;
}

// Implicit midpoint: Π' = Π + h·(Π_m × D Π_m), Π_m = (Π + Π')/2, D = I⁻¹. True if converged.
bool midpoint_newton(const Vec3& p0, const Vec3& inv_inertia, double h, Vec3& io_p1)
{
    const double scale = length(p0);
    for (int it = 0; it < k_newton_max_iterations; ++it) {
        const Vec3 pm = 0.5 * (p0 + io_p1);
        const Vec3 wm = hadamard(inv_inertia, pm);
        const Vec3 r = io_p1 - p0 - h * cross(pm, wm);
        if (!is_finite(r))
            return false;
        if (length(r) <= k_newton_rel_tol * scale)
            return true;
        // d(Π_m × DΠ_m)/dΠ' = ½(skew(Π_m)·D − skew(DΠ_m)).
        const Mat3 dgyro = add_scaled(skew(pm) * Mat3::diagonal(inv_inertia), skew(wm), -1.0);
        Vec3 delta;
        if (!solve3(add_scaled(Mat3::identity(), dgyro, -0.5 * h), r, delta))
            return false;
        io_p1 -= delta;
    }
    const Vec3 pm = 0.5 * (p0 + io_p1);
    return length(io_p1 - p0 - h * cross(pm, hadamard(inv_inertia, pm))) <= 1e3 * k_newton_rel_tol * scale;
}

} // namespace

Vec3 backward_euler_one_step(const Vec3& p0, const Vec3& inertia, double h)
{
    const Vec3 w0{p0.x / inertia.x, p0.y / inertia.y, p0.z / inertia.z};
    const Vec3 f = h * cross(w0, p0);
    const Mat3 jac = add_scaled(Mat3::diagonal(inertia),
                                add_scaled(skew(w0) * Mat3::diagonal(inertia), skew(p0), -1.0), h);
    Vec3 dw;
    if (!solve3(jac, f, dw))
        return p0;
    return hadamard(inertia, w0 - dw);
}

namespace
{

// Shortest rotation taking direction a onto direction b; identity when they are (anti)parallel-degenerate.
Quat rotation_between(const Vec3& a, const Vec3& b)
{
    const double ab = length(a) * length(b);
    const Quat q{ab + dot(a, b), cross(a, b).x, cross(a, b).y, cross(a, b).z};
    if (!(q.w > 1e-6 * ab))
        return Quat::identity();
    return normalized(q);
}

} // namespace

RotationStep rotate_torque_free(const Quat& q, const Vec3& momentum_body, const Vec3& inertia_body, double h)
{
    const Vec3 inv_inertia{1.0 / inertia_body.x, 1.0 / inertia_body.y, 1.0 / inertia_body.z};
    const double size = length(momentum_body);
    if (size == 0.0)
        return {momentum_body, q, false};

    RotationStep out;
    Vec3 p1 = momentum_body + h * cross(momentum_body, hadamard(inv_inertia, momentum_body));
    if (!midpoint_newton(momentum_body, inv_inertia, h, p1)) {
        p1 = backward_euler_one_step(momentum_body, inertia_body, h);
        const double n = length(p1);
        p1 = (n > 0.0 && std::isfinite(n)) ? p1 * (size / n)
                                           : momentum_body; // keep |Π| so the spin cannot grow
        out.used_fallback = true;
    }
    const Vec3 w_mid = hadamard(inv_inertia, 0.5 * (momentum_body + p1));
    Quat q1 = normalized(q * quat_from_rotation_vector(h * w_mid));
    // Turn the body so that world angular momentum R'Π' equals RΠ exactly (the correction is O(h³)).
    q1 = normalized(rotation_between(rotate(q1, p1), rotate(q, momentum_body)) * q1);
    out.momentum_body = p1;
    out.orientation = q1;
    return out;
}

} // namespace supermodal
