// SPDX-License-Identifier: MIT
// A superquadric as the spherical product of two superellipses, parametrised for sampling and
// tessellation by arc length rather than by Barr's angles.
//
// Barr's form x = a1·cos^ε1(η)·cos^ε2(ω), … cannot reach most of a flat face at small ε in double
// precision: near η = π/2 the spacing of representable η is 2.2e-16, so cos η ≥ 6e-17 and
// cos^0.01 η ≥ 0.69; the inner 69 % of the top face of an ε1 = 0.01 box has no η. We therefore
// parametrise each superellipse |X|^(2/ε) + |Y|^(2/ε) = 1 by its polar angle φ = atan2(Y, X) (the same
// curve: tan φ = tan^ε θ), evaluate it in log space, and tabulate one quadrant as a fine polyline so
// that arc length can be inverted (Pilu & Fisher 1995, "Equal-distance sampling of superellipse models").
//
// With h(u) the horizontal superellipse (a1, a2, ε2) at arc length u and (c, s) the unit meridian
// superellipse (ε1), a surface point is (c·h(u), a3·s). Its area element is
//     dA = c · sqrt(a3²·ds² + p(u)²·dc²) · du,
// with p = h × h' the support distance of the horizontal curve, and its unit normal is (m_x·n_h, m_z)
// where n_h is the horizontal curve's unit normal and m the unit normal of the meridian curve
// (p·c, a3·s). Both follow from ∂/∂u × ∂/∂(meridian) and need no Barr angle.
//
// Everything declared here is implemented in tessellate.cpp (the mesh is this parametrisation's grid);
// sampling.cpp builds the sample layout and the area integral on top of it.
#pragma once

#include "supermodal/math.h"
#include "supermodal/shape.h"

#include <vector>

namespace supermodal
{

/// A point or direction in the plane of one superellipse.
struct Planar {
    double x = 0.0;
    double y = 0.0;
};

/// A first-quadrant point of the unit superellipse |X|^(2/ε) + |Y|^(2/ε) = 1, with its logarithms
/// (−∞ on an axis), from which the normal follows without underflow.
struct CurvePoint {
    Planar unit;     ///< (X, Y) [-].
    Planar log_unit; ///< (ln X, ln Y).
};

/// The unit superellipse at polar angle phi ∈ [0, π/2]. Exact axis points at phi = 0 and π/2; finite
/// for every ε > 0.
[[nodiscard]] CurvePoint unit_superellipse(double epsilon, double phi);

/// Unit outward normal of the scaled superellipse (a·X, b·Y) at p, given ln a and ln b. On an axis it
/// returns that axis: the exact normal for ε < 2, a symmetric choice at the vertex (ε = 2) or cusp
/// (ε > 2) where the normal is undefined.
[[nodiscard]] Planar superellipse_normal(double epsilon, double log_a, double log_b, const CurvePoint& p);

/// One quadrant of the superellipse (a·X, b·Y) as a polyline, graded in φ towards both axes (where
/// ε > 2 cusps are) and fine enough at φ = π/4 (where ε → 0 corners are); point segment_count/2 lies
/// exactly at φ = π/4.
struct QuadrantTable {
    std::vector<double> phi; ///< Polar angle of the unit curve [rad], 0 … π/2, increasing.
    std::vector<double> x;   ///< Unit-curve X per point [-].
    std::vector<double> y;   ///< Unit-curve Y per point [-].
    std::vector<double> arc; ///< Arc length of (a·X, b·Y) from φ = 0 [m], non-decreasing.

    /// Quadrant arc length [m].
    [[nodiscard]] double length() const { return arc.back(); }
    /// Polar angle at arc length s [m] (clamped to the quadrant), linear within a segment.
    [[nodiscard]] double phi_at(double s) const;
};

/// Tabulates one quadrant with segment_count (even, ≥ 2) segments.
[[nodiscard]] QuadrantTable make_quadrant_table(double epsilon, double a, double b, int segment_count);

/// Table segments per quadrant used by sampling and tessellation: resolves the ε = 0.01 corner with
/// about a dozen segments and keeps the polyline area within 1e-5 of the surface (docs/geometry.md).
inline constexpr int k_quadrant_segments = 512;

/// A superquadric ready for arc-length parametrisation. The meridian is measured in a reference
/// metric (R·c, a3·s), R being the arc-length mean of the horizontal support distance p: then a step
/// in meridian arc times the ring perimeter is the band's area, on average over the ring.
struct SphericalProduct {
    Vec3 radii{};              ///< a1, a2, a3 [m].
    Vec3 log_radii{};          ///< Their natural logarithms.
    double epsilon1 = 1.0;     ///< Clamped to [k_min_epsilon, 4] [-].
    double epsilon2 = 1.0;     ///< Clamped to [k_min_epsilon, 4] [-].
    QuadrantTable horizontal;  ///< (a1, a2, ε2); arc is physical length [m].
    QuadrantTable meridian;    ///< (R, a3, ε1); arc in the reference metric [m].
    double support_mean = 0.0; ///< R [m].

    /// Horizontal loop length L_H [m] (c = 1).
    [[nodiscard]] double loop_length() const { return 4.0 * horizontal.length(); }
    /// Pole-to-pole reference meridian length L_M [m].
    [[nodiscard]] double meridian_length() const { return 2.0 * meridian.length(); }
};

/// Smallest ε handled; smaller (or non-finite) exponents are clamped, so the result stays finite.
inline constexpr double k_min_epsilon = 1e-4;

/// Builds the tables for a superquadric (type, taper and bend are ignored).
[[nodiscard]] SphericalProduct make_spherical_product(const ShapeDef& shape, int segment_count);

/// Where arc u falls on the loop: quadrant (0 … 3, counter-clockwise from +x), arc within the quadrant
/// table (odd quadrants run against it, from the y axis back to the x axis), and the signs of x and y.
struct LoopArc {
    int quadrant = 0;
    double table_arc = 0.0; ///< [m].
    double sign_x = 1.0;
    double sign_y = 1.0;
};
/// Loop arc u [m] from +x, counter-clockwise about +z; periodic in L_H.
[[nodiscard]] LoopArc loop_arc_at(const SphericalProduct& sp, double u);

/// Where on the horizontal loop: first-quadrant polar angle and the signs of x and y.
struct LoopPoint {
    double phi = 0.0;
    double sign_x = 1.0;
    double sign_y = 1.0;
};
/// Loop point at arc length u [m] from +x, counter-clockwise about +z; periodic in L_H.
[[nodiscard]] LoopPoint loop_point_at(const SphericalProduct& sp, double u);

/// Where on the meridian: first-quadrant polar angle and the sign of z.
struct MeridianPoint {
    double phi = 0.0;
    double sign_z = 1.0;
};
/// Meridian point at reference arc sigma [m] from the south pole (0) to the north pole (L_M).
[[nodiscard]] MeridianPoint meridian_point_at(const SphericalProduct& sp, double sigma);

/// The loop quadrant's table segments as the area element needs them.
struct LoopSegments {
    std::vector<double> length;   ///< ℓ_k [m].
    std::vector<double> support2; ///< p_k², the squared support distance of the chord's line [m²].
    double max_support2 = 0.0;    ///< Largest p_k² [m²].
};
[[nodiscard]] LoopSegments loop_segments(const SphericalProduct& sp);

/// The meridian from south pole to north pole as one polyline.
struct MeridianPolyline {
    std::vector<double> sigma; ///< Reference arc σ from the south pole [m], increasing.
    std::vector<double> c, s;  ///< Unit meridian point (c ≥ 0, s from −1 to 1) [-].
};
[[nodiscard]] MeridianPolyline meridian_polyline(const SphericalProduct& sp);

/// One latitude ring: the meridian point every point of the ring shares, and the sign of z.
struct RingPoint {
    CurvePoint meridian;
    double sign_z = 1.0;
};
[[nodiscard]] RingPoint ring_point(const SphericalProduct& sp, MeridianPoint m);

/// Surface point [m] and unit outward normal of the undeformed superquadric, shape frame.
struct SurfacePoint {
    Vec3 point{};
    Vec3 normal{};
};
[[nodiscard]] SurfacePoint spherical_product_point(const SphericalProduct& sp, const RingPoint& ring,
                                                   LoopPoint h);

} // namespace supermodal
