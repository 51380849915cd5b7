// SPDX-License-Identifier: MIT
// Tessellation of superquadrics into watertight, outward-facing indexed meshes, and mesh volume.
//
// The mesh is a latitude-longitude grid in arc length (geometry/sampling.h), not in Barr's angles, so
// triangles stay roughly even at ε → 0 and ε = 4. Every quadrant of both superellipses is split at its
// axis point and at φ = π/4, and these points are always vertices: the ε → 0 box then keeps its edges
// and corners exactly, and the ε ≥ 2 vertices and cusps (on the axes) are never cut off. Each pole is
// one vertex with a triangle fan, and the loop index wraps, so every edge has exactly two triangles.
//
// The arc-length parametrisation itself (sampling.h) and its polyline tables are implemented here too:
// the mesh is its grid, and sampling.cpp adds the layout and the area integral on top.
#include "geometry/aabb.h"
#include "geometry/hyperquadric_internal.h"
#include "geometry/sampling.h"
#include "supermodal/geometry.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace supermodal
{
namespace
{

constexpr double k_half_pi = 0.5 * std::numbers::pi;

// Below four segments there is no closed solid; above 2048 a mesh passes 10^7 triangles, far beyond
// rendering or export needs, so the request is clamped rather than allowed to exhaust memory.
constexpr int k_min_resolution = 4;
constexpr int k_max_resolution = 2048;
// Pole to pole the meridian gets between resolution/2 (a sphere's share at equal spacing) and
// 2·resolution segments, whatever the equal-arc step asks: a needle (a3 ≫ a1) then does not turn into
// 10^5 rings, and a blade (a1 ≫ a2, a3), whose loop step is much longer than its thickness, still gets
// a round cross-section.
constexpr double k_min_meridian_share = 0.5;
constexpr double k_max_meridian_share = 2.0;

double clamp_epsilon(double e)
{
    return std::isfinite(e) ? std::clamp(e, k_min_epsilon, 4.0) : 1.0;
}

int segments_for(double length, double step)
{
    return int(std::max(1L, std::lround(std::min(length / step, 1e6))));
}

// Appends polar angles of equal-arc vertices on the table arc [lo, hi]: from lo upwards, or from hi
// downwards when reversed, the far end excluded (the next arc starts there). With skip_first the start
// is left out too (a pole, which is its own vertex).
void append_arc(const QuadrantTable& t, double lo, double hi, bool reversed, double step, bool skip_first,
                std::vector<double>& out_phi)
{
    const int m = segments_for(hi - lo, step);
    for (int i = skip_first ? 1 : 0; i < m; ++i) {
        const double d = (hi - lo) * i / m;
        out_phi.push_back(t.phi_at(reversed ? hi - d : lo + d));
    }
}

std::vector<LoopPoint> loop_vertices(const SphericalProduct& sp, double step)
{
    const QuadrantTable& t = sp.horizontal;
    const double corner = t.arc[t.arc.size() / 2], end = t.length();
    std::vector<LoopPoint> out;
    // Quadrants run counter-clockwise from +x; odd ones traverse the table from φ = π/2 down to 0.
    const double sign_x[4] = {1, -1, -1, 1}, sign_y[4] = {1, 1, -1, -1};
    for (int q = 0; q < 4; ++q) {
        std::vector<double> phi;
        if (q % 2 == 0) {
            append_arc(t, 0.0, corner, false, step, false, phi);
            append_arc(t, corner, end, false, step, false, phi);
        } else {
            append_arc(t, corner, end, true, step, false, phi);
            append_arc(t, 0.0, corner, true, step, false, phi);
        }
        for (double p : phi)
            out.push_back({p, sign_x[q], sign_y[q]});
    }
    return out;
}

std::vector<MeridianPoint> ring_vertices(const SphericalProduct& sp, double step)
{
    const QuadrantTable& t = sp.meridian;
    const double corner = t.arc[t.arc.size() / 2], end = t.length();
    std::vector<double> south, north;
    append_arc(t, corner, end, true, step, true, south); // from the south pole, pole excluded
    append_arc(t, 0.0, corner, true, step, false, south);
    append_arc(t, 0.0, corner, false, step, false, north); // from the equator up
    append_arc(t, corner, end, false, step, false, north);
    std::vector<MeridianPoint> out;
    for (double p : south)
        out.push_back({p, -1.0});
    for (double p : north)
        out.push_back({p, 1.0});
    return out;
}

double distance2(const Vec3& a, const Vec3& b)
{
    const Vec3 d = a - b;
    return dot(d, d);
}

void add_triangle(TriangleMesh& mesh, uint32_t a, uint32_t b, uint32_t c)
{
    mesh.indices.insert(mesh.indices.end(), {a, b, c});
}

// Connects poles and rings. Vertex 0 is the south pole, then ring r (south to north) vertex j at
// 1 + r·loop + j, then the north pole. Triangles are counter-clockwise seen from outside because the
// loop runs counter-clockwise about +z and rings run south to north: (∂/∂loop × ∂/∂ring) points out.
void connect_grid(TriangleMesh& mesh, uint32_t ring_count, uint32_t loop)
{
    const auto v = [loop](uint32_t r, uint32_t j) { return 1 + r * loop + j % loop; };
    const uint32_t north = 1 + ring_count * loop;
    for (uint32_t j = 0; j < loop; ++j)
        add_triangle(mesh, 0, v(0, j + 1), v(0, j));
    for (uint32_t r = 0; r + 1 < ring_count; ++r)
        for (uint32_t j = 0; j < loop; ++j) {
            const uint32_t a = v(r, j), b = v(r, j + 1), c = v(r + 1, j + 1), d = v(r + 1, j);
            // The shorter diagonal avoids slivers where the quad is skewed (tapered or sheared cells).
            if (distance2(mesh.positions[a], mesh.positions[c]) <=
                distance2(mesh.positions[b], mesh.positions[d])) {
                add_triangle(mesh, a, b, c);
                add_triangle(mesh, a, c, d);
            } else {
                add_triangle(mesh, a, b, d);
                add_triangle(mesh, b, c, d);
            }
        }
    for (uint32_t j = 0; j < loop; ++j)
        add_triangle(mesh, north, v(ring_count - 1, j), v(ring_count - 1, j + 1));
}

// Angle [rad] between two directions of the plane.
double turn(double ax, double ay, double bx, double by)
{
    return std::atan2(std::abs(ax * by - ay * bx), ax * bx + ay * by);
}

// Replaces a table's arc length by the measure in which even steps leave an even gap between chord and
// curve: ∫ √κ ds (a chord over a stretch of measure w stands off the curve by about w²/8), plus a
// quarter of a circle's share of arc so that flat stretches still get vertices. Each vertex's turn is
// split between its two segments; at the quadrant's ends the curve continues mirrored.
void weight_by_curvature(QuadrantTable& t, double a, double b)
{
    const size_t n = t.arc.size() - 1;
    const double flat = 0.25 / std::sqrt(std::max(2.0 * t.length() / std::numbers::pi, 1e-300));
    std::vector<double> dx(n), dy(n), theta(n + 1, 0.0);
    for (size_t k = 0; k < n; ++k) {
        dx[k] = a * (t.x[k + 1] - t.x[k]);
        dy[k] = b * (t.y[k + 1] - t.y[k]);
    }
    theta[0] = 2.0 * turn(0.0, 1.0, dx[0], dy[0]);          // across the x axis: the tangent is +y
    theta[n] = 2.0 * turn(dx[n - 1], dy[n - 1], -1.0, 0.0); // across the y axis: the tangent is −x
    for (size_t k = 1; k < n; ++k)
        theta[k] = turn(dx[k - 1], dy[k - 1], dx[k], dy[k]);
    double w = 0.0;
    for (size_t k = 0; k < n; ++k) {
        const double length = t.arc[k + 1] - t.arc[k];
        const double share =
            0.5 * (k == 0 ? 0.5 * theta[0] : theta[k]) + 0.5 * (k + 1 == n ? 0.5 * theta[n] : theta[k + 1]);
        t.arc[k] = w;
        w += std::sqrt(share * length) + flat * length;
    }
    t.arc[n] = w;
}

// The tables in the measure vertices are spaced in (their points stay those of sp), and the steps along
// the loop and the meridian for `resolution` segments round the loop.
struct Spacing {
    SphericalProduct tables;
    double loop_step = 0.0, meridian_step = 0.0;
};

Spacing make_spacing(const SphericalProduct& sp, int resolution, MeshSpacing spacing)
{
    Spacing out{sp};
    if (spacing == MeshSpacing::Curvature) {
        weight_by_curvature(out.tables.horizontal, sp.radii.x, sp.radii.y);
        weight_by_curvature(out.tables.meridian, sp.support_mean, sp.radii.z);
    }
    out.loop_step = out.tables.loop_length() / resolution;
    const double lm = out.tables.meridian_length();
    out.meridian_step = std::clamp(out.loop_step, lm / (k_max_meridian_share * resolution),
                                   lm / (k_min_meridian_share * resolution));
    return out;
}

TriangleMesh tessellate_superquadric(const ShapeDef& shape, int resolution, MeshSpacing spacing)
{
    const SphericalProduct sp = make_spherical_product(shape, k_quadrant_segments);
    const Spacing spaced = make_spacing(sp, resolution, spacing);
    const std::vector<LoopPoint> loop = loop_vertices(spaced.tables, spaced.loop_step);
    const std::vector<MeridianPoint> rings = ring_vertices(spaced.tables, spaced.meridian_step);
    TriangleMesh mesh;
    const size_t vertex_count = 2 + rings.size() * loop.size();
    mesh.positions.reserve(vertex_count);
    mesh.normals.reserve(vertex_count);
    mesh.positions.push_back({0.0, 0.0, -shape.radii.z});
    mesh.normals.push_back({0.0, 0.0, -1.0});
    for (const MeridianPoint& m : rings) {
        const RingPoint ring = ring_point(sp, m);
        for (const LoopPoint& h : loop) {
            const SurfacePoint p = spherical_product_point(sp, ring, h);
            mesh.positions.push_back(p.point);
            mesh.normals.push_back(p.normal);
        }
    }
    mesh.positions.push_back({0.0, 0.0, shape.radii.z});
    mesh.normals.push_back({0.0, 0.0, 1.0});
    if (is_deformed(shape))
        for (size_t i = 0; i < mesh.positions.size(); ++i) {
            const Vec3 p = mesh.positions[i];
            mesh.normals[i] = deform_normal(shape, p, mesh.normals[i]);
            mesh.positions[i] = deform_point(shape, p);
        }
    mesh.indices.reserve(6 * rings.size() * loop.size());
    connect_grid(mesh, uint32_t(rings.size()), uint32_t(loop.size()));
    return mesh;
}

} // namespace

CurvePoint unit_superellipse(double epsilon, double phi)
{
    constexpr double inf = std::numeric_limits<double>::infinity();
    if (!(phi > 0.0))
        return {{1.0, 0.0}, {0.0, -inf}};
    if (!(phi < k_half_pi))
        return {{0.0, 1.0}, {-inf, 0.0}};
    // X = cos φ · r, Y = sin φ · r with r^(−2/ε) = cos^(2/ε) φ + sin^(2/ε) φ, by log-sum-exp: the powers
    // underflow to zero for small ε, their logarithms do not.
    const double lc = std::log(std::cos(phi)), ls = std::log(std::sin(phi));
    const double log_r =
        -std::max(lc, ls) - 0.5 * epsilon * std::log1p(std::exp(-(2.0 / epsilon) * std::abs(lc - ls)));
    return {{std::exp(lc + log_r), std::exp(ls + log_r)}, {lc + log_r, ls + log_r}};
}

Planar superellipse_normal(double epsilon, double log_a, double log_b, const CurvePoint& p)
{
    if (std::isinf(p.log_unit.x))
        return {0.0, 1.0};
    if (std::isinf(p.log_unit.y))
        return {1.0, 0.0};
    // ∇(|x/a|^(2/ε) + |y/b|^(2/ε)) ∝ (X^(2/ε−1)/a, Y^(2/ε−1)/b), scaled by its larger component in logs.
    const double k = 2.0 / epsilon - 1.0;
    const double lx = k * p.log_unit.x - log_a, ly = k * p.log_unit.y - log_b;
    const double top = std::max(lx, ly);
    const double nx = std::exp(lx - top), ny = std::exp(ly - top);
    const double n = std::hypot(nx, ny);
    return {nx / n, ny / n};
}

double QuadrantTable::phi_at(double s) const
{
    if (!(s > 0.0))
        return phi.front();
    if (!(s < length()))
        return phi.back();
    const size_t k = size_t(std::upper_bound(arc.begin(), arc.end(), s) - arc.begin()) - 1;
    const double len = arc[k + 1] - arc[k];
    const double t = len > 0.0 ? (s - arc[k]) / len : 0.0;
    return phi[k] + t * (phi[k + 1] - phi[k]);
}

QuadrantTable make_quadrant_table(double epsilon, double a, double b, int segment_count)
{
    const int n = std::max(2, segment_count + segment_count % 2);
    QuadrantTable t;
    t.phi.resize(size_t(n) + 1);
    t.x.resize(size_t(n) + 1);
    t.y.resize(size_t(n) + 1);
    t.arc.resize(size_t(n) + 1);
    for (int k = 0; k <= n; ++k) {
        // Smoothstep grading: φ ∝ τ² at both ends makes the ε > 2 cusp (arc ∝ √φ) linear in τ, while
        // the slope 1.5 at φ = π/4 keeps the ε → 0 corner resolved. τ = ½ gives π/4 exactly.
        const double tau = double(k) / n;
        t.phi[size_t(k)] = k_half_pi * (tau * tau * (3.0 - 2.0 * tau));
        const Planar p = unit_superellipse(epsilon, t.phi[size_t(k)]).unit;
        t.x[size_t(k)] = p.x;
        t.y[size_t(k)] = p.y;
        t.arc[size_t(k)] = k == 0 ? 0.0
                                  : t.arc[size_t(k) - 1] + std::hypot(a * (p.x - t.x[size_t(k) - 1]),
                                                                      b * (p.y - t.y[size_t(k) - 1]));
    }
    return t;
}

SphericalProduct make_spherical_product(const ShapeDef& shape, int segment_count)
{
    SphericalProduct sp;
    sp.radii = shape.radii;
    sp.log_radii = {std::log(sp.radii.x), std::log(sp.radii.y), std::log(sp.radii.z)};
    sp.epsilon1 = clamp_epsilon(shape.epsilon1);
    sp.epsilon2 = clamp_epsilon(shape.epsilon2);
    sp.horizontal = make_quadrant_table(sp.epsilon2, sp.radii.x, sp.radii.y, segment_count);
    // R = ∮p du / L_H = 2·(enclosed area) / L_H, from the polyline's triangle fan.
    double twice_area = 0.0;
    const QuadrantTable& h = sp.horizontal;
    for (size_t k = 0; k + 1 < h.arc.size(); ++k)
        twice_area += sp.radii.x * sp.radii.y * std::abs(h.x[k] * h.y[k + 1] - h.x[k + 1] * h.y[k]);
    sp.support_mean = twice_area / h.length();
    sp.meridian = make_quadrant_table(sp.epsilon1, sp.support_mean, sp.radii.z, segment_count);
    return sp;
}

LoopSegments loop_segments(const SphericalProduct& sp)
{
    const QuadrantTable& h = sp.horizontal;
    LoopSegments seg;
    const size_t n = h.arc.size() - 1;
    seg.length.resize(n);
    seg.support2.resize(n);
    for (size_t k = 0; k < n; ++k) {
        const double x0 = sp.radii.x * h.x[k], y0 = sp.radii.y * h.y[k];
        const double x1 = sp.radii.x * h.x[k + 1], y1 = sp.radii.y * h.y[k + 1];
        seg.length[k] = h.arc[k + 1] - h.arc[k];
        const double support = seg.length[k] > 0.0 ? std::abs(x0 * y1 - x1 * y0) / seg.length[k] : 0.0;
        seg.support2[k] = support * support;
        seg.max_support2 = std::max(seg.max_support2, seg.support2[k]);
    }
    return seg;
}

MeridianPolyline meridian_polyline(const SphericalProduct& sp)
{
    const QuadrantTable& m = sp.meridian;
    const int n = int(m.arc.size()) - 1;
    const double half = m.length();
    MeridianPolyline mp;
    for (int k = n; k >= 0; --k) {
        mp.sigma.push_back(half - m.arc[k]);
        mp.c.push_back(m.x[k]);
        mp.s.push_back(-m.y[k]);
    }
    for (int k = 1; k <= n; ++k) {
        mp.sigma.push_back(half + m.arc[k]);
        mp.c.push_back(m.x[k]);
        mp.s.push_back(m.y[k]);
    }
    return mp;
}

LoopArc loop_arc_at(const SphericalProduct& sp, double u)
{
    const double quarter = sp.horizontal.length(), loop = 4.0 * quarter;
    // A curve too long for a double (a 1e308 m radius: scene fuzz) has no arc parameter: its start.
    if (!(quarter > 0.0) || !std::isfinite(loop) || !std::isfinite(u))
        return {0, 0.0, 1.0, 1.0};
    const double r = std::clamp(u - std::floor(u / loop) * loop, 0.0, loop);
    const int q = std::min(3, int(r / quarter));
    const double sign_x[4] = {1, -1, -1, 1}, sign_y[4] = {1, 1, -1, -1};
    return {q, q % 2 == 0 ? r - q * quarter : (q + 1) * quarter - r, sign_x[q], sign_y[q]};
}

LoopPoint loop_point_at(const SphericalProduct& sp, double u)
{
    const LoopArc a = loop_arc_at(sp, u);
    return {sp.horizontal.phi_at(a.table_arc), a.sign_x, a.sign_y};
}

MeridianPoint meridian_point_at(const SphericalProduct& sp, double sigma)
{
    const double half = sp.meridian.length();
    if (sigma < half)
        return {sp.meridian.phi_at(half - sigma), -1.0};
    return {sp.meridian.phi_at(sigma - half), 1.0};
}

RingPoint ring_point(const SphericalProduct& sp, MeridianPoint m)
{
    return {unit_superellipse(sp.epsilon1, m.phi), m.sign_z};
}

SurfacePoint spherical_product_point(const SphericalProduct& sp, const RingPoint& ring, LoopPoint h)
{
    const Vec3& a = sp.radii;
    const CurvePoint ch = unit_superellipse(sp.epsilon2, h.phi);
    const Planar nh = superellipse_normal(sp.epsilon2, sp.log_radii.x, sp.log_radii.y, ch);
    // The meridian normal is that of the curve (p·c, a3·s), p = h·n_h the loop's support distance.
    const double support =
        std::max(a.x * ch.unit.x * nh.x + a.y * ch.unit.y * nh.y, std::numeric_limits<double>::min());
    const Planar nm = superellipse_normal(sp.epsilon1, std::log(support), sp.log_radii.z, ring.meridian);
    const Planar um = ring.meridian.unit, uh = ch.unit;
    return {{h.sign_x * a.x * um.x * uh.x, h.sign_y * a.y * um.x * uh.y, ring.sign_z * a.z * um.y},
            {h.sign_x * nm.x * nh.x, h.sign_y * nm.x * nh.y, ring.sign_z * nm.y}};
}

TriangleMesh tessellate(const ShapeDef& shape, int resolution)
{
    return tessellate(shape, resolution, MeshSpacing::EqualArc);
}

TriangleMesh tessellate(const ShapeDef& shape, int resolution, MeshSpacing spacing)
{
    resolution = std::clamp(resolution, k_min_resolution, k_max_resolution);
    if (shape.type == ShapeType::Hyperquadric)
        return tessellate_hyperquadric(shape, resolution);
    if (shape.type != ShapeType::Superquadric)
        return {}; // a plane does not bound a solid
    const Vec3& a = shape.radii;
    if (!(is_finite(a) && a.x > 0.0 && a.y > 0.0 && a.z > 0.0))
        return {};
    return tessellate_superquadric(shape, resolution, spacing);
}

double tessellation_gap(const ShapeDef& shape, int resolution)
{
    const Vec3& a = shape.radii;
    if (shape.type != ShapeType::Superquadric || resolution < 1 ||
        !(is_finite(a) && a.x > 0.0 && a.y > 0.0 && a.z > 0.0))
        return 0.0;
    const Spacing spaced =
        make_spacing(make_spherical_product(shape, k_quadrant_segments), resolution, MeshSpacing::Curvature);
    // A chord over a step w of the measure stands off by about w²/8; inside a triangle the loop's and the
    // meridian's sag add up.
    return (spaced.loop_step * spaced.loop_step + spaced.meridian_step * spaced.meridian_step) / 8.0;
}

double mesh_volume(const TriangleMesh& mesh)
{
    if (mesh.positions.empty())
        return 0.0;
    // Measuring from the centre of the vertex box keeps the triple products well conditioned for a
    // mesh far from the origin; a closed mesh's volume does not depend on the reference point.
    const Aabb box = bounds_of(mesh.positions);
    const Vec3 o = 0.5 * (box.min + box.max);
    const size_t n = mesh.positions.size();
    double six_volume = 0.0;
    for (size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
        const uint32_t i0 = mesh.indices[t], i1 = mesh.indices[t + 1], i2 = mesh.indices[t + 2];
        if (i0 >= n || i1 >= n || i2 >= n)
            continue;
        six_volume += dot(mesh.positions[i0] - o, cross(mesh.positions[i1] - o, mesh.positions[i2] - o));
    }
    return six_volume / 6.0;
}

} // namespace supermodal
