// SPDX-License-Identifier: MIT
// Small fixed-size algebra for the public API. Eigen does n-dimensional work inside engine/src;
// these types keep the public headers free of third-party includes.
#pragma once

#include <cmath>

namespace supermodal
{

/// A 3-vector of doubles; meaning and unit come from the field that holds it.
struct Vec3 {
    double x = 0.0, y = 0.0, z = 0.0;

    [[nodiscard]] constexpr double operator[](int i) const { return i == 0 ? x : (i == 1 ? y : z); }
    [[nodiscard]] constexpr double& operator[](int i) { return i == 0 ? x : (i == 1 ? y : z); }
    constexpr Vec3& operator+=(const Vec3& o)
    {
        x += o.x;
        y += o.y;
        z += o.z;
        return *this;
    }
    constexpr Vec3& operator-=(const Vec3& o)
    {
        x -= o.x;
        y -= o.y;
        z -= o.z;
        return *this;
    }
    constexpr Vec3& operator*=(double s)
    {
        x *= s;
        y *= s;
        z *= s;
        return *this;
    }
    friend constexpr bool operator==(const Vec3&, const Vec3&) = default;
};

[[nodiscard]] constexpr Vec3 operator+(Vec3 a, const Vec3& b)
{
    return a += b;
}
[[nodiscard]] constexpr Vec3 operator-(Vec3 a, const Vec3& b)
{
    return a -= b;
}
[[nodiscard]] constexpr Vec3 operator-(const Vec3& a)
{
    return {-a.x, -a.y, -a.z};
}
[[nodiscard]] constexpr Vec3 operator*(Vec3 a, double s)
{
    return a *= s;
}
[[nodiscard]] constexpr Vec3 operator*(double s, Vec3 a)
{
    return a *= s;
}
[[nodiscard]] constexpr Vec3 operator/(const Vec3& a, double s)
{
    return {a.x / s, a.y / s, a.z / s};
}
[[nodiscard]] constexpr double dot(const Vec3& a, const Vec3& b)
{
    return a.x * b.x + a.y * b.y + a.z * b.z;
}
[[nodiscard]] constexpr Vec3 cross(const Vec3& a, const Vec3& b)
{
    return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
/// Component-wise product.
[[nodiscard]] constexpr Vec3 hadamard(const Vec3& a, const Vec3& b)
{
    return {a.x * b.x, a.y * b.y, a.z * b.z};
}
[[nodiscard]] inline double length(const Vec3& a)
{
    return std::sqrt(dot(a, a));
}
[[nodiscard]] inline bool is_finite(const Vec3& a)
{
    return std::isfinite(a.x) && std::isfinite(a.y) && std::isfinite(a.z);
}
/// a / |a|, or the zero vector when |a| is zero.
[[nodiscard]] inline Vec3 normalized(const Vec3& a)
{
    const double n = length(a);
    return n > 0.0 ? a / n : Vec3{};
}

/// A 3x3 matrix stored by rows: m[row][col].
struct Mat3 {
    double m[3][3] = {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}};

    [[nodiscard]] static constexpr Mat3 identity() { return diagonal({1, 1, 1}); }
    [[nodiscard]] static constexpr Mat3 diagonal(const Vec3& d)
    {
        Mat3 r;
        r.m[0][0] = d.x;
        r.m[1][1] = d.y;
        r.m[2][2] = d.z;
        return r;
    }
    [[nodiscard]] constexpr Vec3 row(int i) const { return {m[i][0], m[i][1], m[i][2]}; }
    [[nodiscard]] constexpr Vec3 col(int j) const { return {m[0][j], m[1][j], m[2][j]}; }
};

[[nodiscard]] constexpr Vec3 operator*(const Mat3& a, const Vec3& v)
{
    return {dot(a.row(0), v), dot(a.row(1), v), dot(a.row(2), v)};
}
[[nodiscard]] constexpr Mat3 operator*(const Mat3& a, const Mat3& b)
{
    Mat3 r;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            r.m[i][j] = dot(a.row(i), b.col(j));
    return r;
}
[[nodiscard]] constexpr Mat3 transpose(const Mat3& a)
{
    Mat3 r;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            r.m[i][j] = a.m[j][i];
    return r;
}

/// The cross-product matrix: skew(a)·v = a × v.
[[nodiscard]] constexpr Mat3 skew(const Vec3& a)
{
    Mat3 s;
    s.m[0][1] = -a.z;
    s.m[0][2] = a.y;
    s.m[1][0] = a.z;
    s.m[1][2] = -a.x;
    s.m[2][0] = -a.y;
    s.m[2][1] = a.x;
    return s;
}
/// a + s·b, element by element.
[[nodiscard]] constexpr Mat3 add_scaled(const Mat3& a, const Mat3& b, double s)
{
    Mat3 r;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            r.m[i][j] = a.m[i][j] + s * b.m[i][j];
    return r;
}

/// A rotation as a unit quaternion [w, x, y, z] (Euler parameters).
struct Quat {
    double w = 1.0, x = 0.0, y = 0.0, z = 0.0;

    [[nodiscard]] static constexpr Quat identity() { return {}; }
    friend constexpr bool operator==(const Quat&, const Quat&) = default;
};

/// Hamilton product: (a * b) rotates by b first, then by a.
[[nodiscard]] constexpr Quat operator*(const Quat& a, const Quat& b)
{
    return {a.w * b.w - a.x * b.x - a.y * b.y - a.z * b.z, a.w * b.x + a.x * b.w + a.y * b.z - a.z * b.y,
            a.w * b.y - a.x * b.z + a.y * b.w + a.z * b.x, a.w * b.z + a.x * b.y - a.y * b.x + a.z * b.w};
}
[[nodiscard]] constexpr Quat conjugate(const Quat& q)
{
    return {q.w, -q.x, -q.y, -q.z};
}
[[nodiscard]] inline double norm(const Quat& q)
{
    return std::sqrt(q.w * q.w + q.x * q.x + q.y * q.y + q.z * q.z);
}
/// q / |q|, or identity when |q| is zero.
[[nodiscard]] inline Quat normalized(const Quat& q)
{
    const double n = norm(q);
    return n > 0.0 ? Quat{q.w / n, q.x / n, q.y / n, q.z / n} : Quat::identity();
}
[[nodiscard]] inline bool is_finite(const Quat& q)
{
    return std::isfinite(q.w) && std::isfinite(q.x) && std::isfinite(q.y) && std::isfinite(q.z);
}
/// Rotates v by the unit quaternion q.
[[nodiscard]] constexpr Vec3 rotate(const Quat& q, const Vec3& v)
{
    const Vec3 u{q.x, q.y, q.z};
    const Vec3 t = 2.0 * cross(u, v);
    return v + q.w * t + cross(u, t);
}
/// Rotates v by the inverse of the unit quaternion q.
[[nodiscard]] constexpr Vec3 inv_rotate(const Quat& q, const Vec3& v)
{
    return rotate(conjugate(q), v);
}
/// The rotation matrix of a unit quaternion.
[[nodiscard]] constexpr Mat3 to_mat3(const Quat& q)
{
    Mat3 r;
    const Vec3 c0 = rotate(q, {1, 0, 0}), c1 = rotate(q, {0, 1, 0}), c2 = rotate(q, {0, 0, 1});
    for (int i = 0; i < 3; ++i) {
        r.m[i][0] = c0[i];
        r.m[i][1] = c1[i];
        r.m[i][2] = c2[i];
    }
    return r;
}
/// Rotation by |rotation| radians about rotation/|rotation| (the exponential map).
[[nodiscard]] inline Quat quat_from_rotation_vector(const Vec3& rotation)
{
    const double angle = length(rotation);
    if (angle < 1e-12) // second-order series keeps the unit norm to round-off for tiny angles
        return normalized(Quat{1.0, 0.5 * rotation.x, 0.5 * rotation.y, 0.5 * rotation.z});
    const double s = std::sin(0.5 * angle) / angle;
    return {std::cos(0.5 * angle), s * rotation.x, s * rotation.y, s * rotation.z};
}

} // namespace supermodal
