// SPDX-License-Identifier: MIT
// Equal-distance surface sampling of superquadrics (design in sampling.h and docs/geometry.md).
//
// Samples sit on latitude rings about one `spacing` apart in meridian arc length, and each ring carries
// samples about one `spacing` apart in its own arc length, so neither the poles nor the ε → 0 edges
// collect extra samples (Pilu & Fisher 1995 sample each superellipse at equal arc length; doing it per
// ring extends that to the spherical product without the pole crowding of a plain product grid). Each
// sample owns the patch between its band's edges and the midpoints to its neighbours; patch areas
// integrate the exact area element over the tabulated polylines, so they sum to the surface area.
//
// Sharp features decide the layout. A patch that straddles an edge gets one normal for two faces, so
// band edges run along the meridian's corners (φ = π/4, the ε → 0 box edges) and the equator, and for
// ε2 < 1 (with ε1 ≤ 1) cell edges run along the loop's corners. For ε > 1 the sharp features are the axis
// points (the ε = 2 octahedron's wedges, sharper the more unequal the radii), where two samples mirrored
// across a wedge of angle θ at distance t would sit only 2·t·sin(θ/2) apart: so no ring lies on the equator
// (the rings either side are staggered by half a step), and otherwise every ring starts ¼ or ¾ step from +x,
// alternating, which puts the samples either side of each axis meridian ¼ and ¾ step from it. Ring counts are
// even and mirrored rings get mirrored offsets, so the set is invariant under half-turns about x, y and z:
// uniform pressure on any face gives no torque.
#include "geometry/sampling.h"

#include "core/assert.h"
#include "geometry/hyperquadric_internal.h"
#include "supermodal/geometry.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace supermodal
{
namespace
{

// Each widening step grows the spacing at least this much, so the max_count loop always ends.
constexpr double k_min_widening = 1.02;
constexpr int k_max_widenings = 64;
// A cell splits into sub-rows only from a band 1.75 steps wide: rows 0.875 step apart or more keep the
// nearest-neighbour ratio down (splitting from 1.5 measured 3.0 against 2.1 on a 1:4:1 body, ε = (0.3, 0.7)),
// and the hole left is at most ~0.9 step. Sub-rows per cell are capped so a 1:1000 blade cannot ask for
// thousands (it is uneven anyway).
constexpr double k_min_rows_ratio = 1.75;
constexpr int k_max_rows = 64;
// Deformed samples are redrawn when taper or bend changes the surface area by more than this, so the
// spacing holds on the deformed surface rather than on the undeformed one.
constexpr double k_redraw_area_change = 0.1;

// One piece of the meridian inside a band: mean c, dc² and a3²·ds², so that the band's area element
// per unit loop length at support distance p is Σ c̄·sqrt(a3²ds² + p²dc²) (midpoint rule per piece).
struct MeridianPiece {
    double c_mid, dc2, ds2;
};

void band_pieces(const MeridianPolyline& mp, double a3, double lo, double hi, std::vector<MeridianPiece>& out)
{
    out.clear();
    const auto first = std::upper_bound(mp.sigma.begin(), mp.sigma.end(), lo);
    size_t j = first == mp.sigma.begin() ? 0 : size_t(first - mp.sigma.begin()) - 1;
    for (; j + 1 < mp.sigma.size() && mp.sigma[j] < hi; ++j) {
        const double s0 = std::max(mp.sigma[j], lo), s1 = std::min(mp.sigma[j + 1], hi);
        const double len = mp.sigma[j + 1] - mp.sigma[j];
        if (!(s1 > s0) || !(len > 0.0))
            continue;
        const double t0 = (s0 - mp.sigma[j]) / len, t1 = (s1 - mp.sigma[j]) / len;
        const double c0 = mp.c[j] + t0 * (mp.c[j + 1] - mp.c[j]), c1 = mp.c[j] + t1 * (mp.c[j + 1] - mp.c[j]);
        const double z0 = mp.s[j] + t0 * (mp.s[j + 1] - mp.s[j]), z1 = mp.s[j] + t1 * (mp.s[j + 1] - mp.s[j]);
        out.push_back({0.5 * (c0 + c1), (c1 - c0) * (c1 - c0), a3 * a3 * (z1 - z0) * (z1 - z0)});
    }
}

// Band area accumulated along one horizontal quadrant, in table order: prefix[k] is the area of the
// band over table segments 0 … k−1 [m²].
void band_prefix(const std::vector<MeridianPiece>& pieces, const LoopSegments& seg,
                 std::vector<double>& prefix)
{
    const size_t n = seg.length.size();
    prefix.assign(n + 1, 0.0);
    double* g = prefix.data() + 1;
    const double* p2 = seg.support2.data();
    // Pieces outermost: the inner loop carries no sum, so it can vectorise, and each g[k] still adds its
    // pieces in the same order, so the result does not depend on whether it does.
    for (const MeridianPiece& piece : pieces)
        for (size_t k = 0; k < n; ++k)
            g[k] += piece.c_mid * std::sqrt(piece.ds2 + p2[k] * piece.dc2);
    for (size_t k = 0; k < n; ++k)
        prefix[k + 1] = prefix[k] + seg.length[k] * g[k];
}

double quadrant_prefix_at(const QuadrantTable& h, const std::vector<double>& prefix, double s)
{
    if (!(s > 0.0))
        return 0.0;
    if (!(s < h.length()))
        return prefix.back();
    const size_t k = size_t(std::upper_bound(h.arc.begin(), h.arc.end(), s) - h.arc.begin()) - 1;
    const double len = h.arc[k + 1] - h.arc[k];
    const double t = len > 0.0 ? (s - h.arc[k]) / len : 0.0;
    return prefix[k] + t * (prefix[k + 1] - prefix[k]);
}

// Band area from loop arc 0 to u [m²], continued periodically so that cells may straddle u = 0.
double loop_prefix_at(const SphericalProduct& sp, const std::vector<double>& prefix, double u)
{
    const LoopArc a = loop_arc_at(sp, u);
    const double within = quadrant_prefix_at(sp.horizontal, prefix, a.table_arc),
                 quarter_area = prefix.back();
    const double local = a.quadrant % 2 == 0 ? within : quarter_area - within;
    return (4.0 * std::floor(u / sp.loop_length()) + a.quadrant) * quarter_area + local;
}

// One latitude ring: its band of the meridian (reference arc from the south pole [m]), its centre, and
// how its samples sit around the loop.
struct Ring {
    double lo = 0.0, hi = 0.0, centre = 0.0;
    int count = 1;                  ///< Cells around the ring.
    double offset = 0.0;            ///< Even layout: first cell centre at offset·(L_H/count) from +x.
    std::array<int, 2> faces{0, 0}; ///< Corner-aligned layout: cells on each ±x and each ±y face arc.
    double width_c = 0.0; ///< |Δc| across the band [-]: its width at u is hypot(width_s, p(u)·width_c).
    double width_s = 0.0; ///< a3·|Δs| across the band [m].
};

double bounded_ratio(double num, double den)
{
    return std::min(num / den, 1e8); // keeps lround and the int counts built from it far from overflow
}

int at_least_one(double x)
{
    return int(std::max(1L, std::lround(x)));
}

// One sample when the perimeter P < 2·step, since two on such a ring (a spike near a pointed pole) would
// sit only P/π < 0.64·step apart. Otherwise corner-aligned cells for ε2 < 1 (from P ≥ 4·step, where
// each face arc can hold one), else P/step rounded to even. Corner-aligned rings mirror onto each other
// across the equator, so for ε1 > 1, whose equator is a wedge, the staggered even layout wins.
void lay_out_ring(const SphericalProduct& sp, double c, double step, Ring& ring)
{
    const double perimeter = c * sp.loop_length();
    if (!(perimeter >= 2.0 * step))
        return;
    if (sp.epsilon2 < 1.0 && sp.epsilon1 <= 1.0 && perimeter >= 4.0 * step) {
        const double corner = c * sp.horizontal.arc[sp.horizontal.arc.size() / 2];
        const double quarter = c * sp.horizontal.length();
        ring.faces = {at_least_one(bounded_ratio(2.0 * corner, step)),
                      at_least_one(bounded_ratio(2.0 * (quarter - corner), step))};
        ring.count = 2 * (ring.faces[0] + ring.faces[1]);
        return;
    }
    ring.count = 2 * at_least_one(bounded_ratio(perimeter, 2.0 * step));
}

// The north half from the equator up (bands between the equator and the corner, then rings whose bands
// reach the corner, then the pole, whose single sample on the axis stands for a half-width cap), mirrored
// into the south half.
std::vector<Ring> rings_for(const SphericalProduct& sp, double step)
{
    const double half = sp.meridian.length(), lm = 2.0 * half;
    const double corner = sp.meridian.arc[sp.meridian.arc.size() / 2], polar = half - corner;
    const int side_count = at_least_one(bounded_ratio(corner, step));
    const int polar_count = at_least_one(bounded_ratio(polar, step) + 0.5);
    const double side_step = corner / side_count, polar_step = polar / (polar_count - 0.5);
    std::vector<Ring> north;
    for (int i = 0; i < side_count; ++i)
        north.push_back({half + i * side_step, half + (i + 1) * side_step, half + (i + 0.5) * side_step});
    for (int k = polar_count - 1; k >= 1; --k)
        north.push_back({lm - (k + 0.5) * polar_step, lm - (k - 0.5) * polar_step, lm - k * polar_step});
    north.push_back({lm - 0.5 * polar_step, lm, lm});
    const auto unit_at = [&](double sigma) {
        return unit_superellipse(sp.epsilon1, meridian_point_at(sp, sigma).phi).unit;
    };
    for (size_t j = 0; j + 1 < north.size(); ++j) {
        Ring& r = north[j];
        lay_out_ring(sp, unit_at(r.centre).x, step, r);
        r.offset = j % 2 == 0 ? 0.25 : 0.75;
        const Planar lo = unit_at(r.lo), hi = unit_at(r.hi);
        r.width_c = std::abs(hi.x - lo.x);
        r.width_s = sp.radii.z * std::abs(hi.y - lo.y);
    }
    std::vector<Ring> rings(north.rbegin(), north.rend());
    for (Ring& r : rings)
        r = {lm - r.hi, lm - r.lo, lm - r.centre, r.count, 1.0 - r.offset, r.faces, r.width_c, r.width_s};
    rings.insert(rings.end(), north.begin(), north.end());
    return rings;
}

double estimated_area(const SphericalProduct& sp)
{
    const QuadrantTable& m = sp.meridian;
    double band = 0.0;
    for (size_t k = 0; k + 1 < m.arc.size(); ++k)
        band += 0.5 * (m.x[k] + m.x[k + 1]) * (m.arc[k + 1] - m.arc[k]);
    return 2.0 * band * sp.loop_length();
}

// A cell: its centre u along the loop [m], its half-width [m], and how many sub-rows split its band.
struct Cell {
    double u, half_width;
    int rows = 1;
};

// Support distance p of the loop at arc u [m], from the table segment there.
double support_at(const SphericalProduct& sp, const LoopSegments& seg, double u)
{
    const std::vector<double>& arc = sp.horizontal.arc;
    const size_t k =
        size_t(std::upper_bound(arc.begin(), arc.end() - 1, loop_arc_at(sp, u).table_arc) - arc.begin());
    return std::sqrt(seg.support2[std::clamp<size_t>(k, 1, seg.support2.size()) - 1]);
}

// Rings are scaled copies of the loop, so a band is p(u)/R times wider along sides of large support
// distance p (the short sides of an elongated box's top face): there its cells split into sub-rows about
// one step apart.
void ring_cells(const SphericalProduct& sp, const LoopSegments& seg, const Ring& ring, double step,
                std::vector<Cell>& out)
{
    out.clear();
    const double lh = sp.loop_length();
    if (ring.faces[0] == 0) {
        const double du = lh / ring.count;
        for (int j = 0; j < ring.count; ++j)
            out.push_back({(j + ring.offset) * du, 0.5 * du});
    } else {
        // Face arcs between the loop's corners, counter-clockwise from the one through +x.
        const double corner = sp.horizontal.arc[sp.horizontal.arc.size() / 2], half = 0.5 * lh;
        const double start[4] = {-corner, corner, half - corner, half + corner};
        for (int f = 0; f < 4; ++f) {
            const int m = ring.faces[size_t(f % 2)];
            const double width = (f % 2 == 0 ? 2.0 * corner : half - 2.0 * corner) / m;
            for (int i = 0; i < m; ++i)
                out.push_back({start[f] + (i + 0.5) * width, 0.5 * width});
        }
    }
    // Most rings are nowhere wide enough to split: skip the per-cell look-ups for them.
    const double widest = std::hypot(ring.width_s, std::sqrt(seg.max_support2) * ring.width_c);
    if (ring.count > 1 && bounded_ratio(widest, step) >= k_min_rows_ratio)
        for (Cell& c : out) {
            const double width = std::hypot(ring.width_s, support_at(sp, seg, c.u) * ring.width_c);
            const double rows = bounded_ratio(width, step);
            c.rows = rows < k_min_rows_ratio ? 1 : std::clamp(int(std::lround(rows)), 1, k_max_rows);
        }
}

struct Plan {
    std::vector<Ring> rings;
    double step = 0.0;
    long count = 1; ///< Samples.
};

Plan plan_rings(const SphericalProduct& sp, const LoopSegments& seg, double spacing, int max_count)
{
    const double area = estimated_area(sp);
    double step = spacing;
    if (!(step > 0.0) || area / (step * step) > max_count)
        step = std::sqrt(area / max_count);
    // The equator ring alone needs L_H/step samples and every ring at least one, so a shorter step can
    // never fit; starting from here also bounds the ring list of a needle or a blade.
    step = std::max({step, sp.loop_length() / max_count, sp.meridian_length() / max_count});
    std::vector<Cell> cells;
    for (int i = 0; i < k_max_widenings; ++i) {
        std::vector<Ring> rings = rings_for(sp, step);
        long total = 0;
        for (const Ring& r : rings) {
            ring_cells(sp, seg, r, step, cells);
            for (const Cell& c : cells)
                total += c.rows;
        }
        if (total <= max_count)
            return {rings, step, total};
        step *= std::max(k_min_widening, std::sqrt(double(total) / max_count));
    }
    // The coarsest sets: the two poles with a hemisphere each, or one sample on the equator at +x.
    const double half = sp.meridian.length(), inf = std::numeric_limits<double>::infinity();
    if (max_count >= 2)
        return {{{0.0, half, 0.0}, {half, 2.0 * half, 2.0 * half}}, inf, 2};
    return {{{0.0, 2.0 * half, half}}, inf, 1};
}

// The sub-bands of one ring for a given sub-row count: their centre points and area prefixes.
struct SubBands {
    std::vector<RingPoint> points;
    std::vector<std::vector<double>> prefixes;
};

const SubBands& sub_bands(const SphericalProduct& sp, const LoopSegments& seg, const MeridianPolyline& mp,
                          const Ring& ring, int rows, std::vector<SubBands>& cache)
{
    if (cache.size() <= size_t(rows))
        cache.resize(size_t(rows) + 1);
    SubBands& b = cache[size_t(rows)];
    if (!b.points.empty())
        return b;
    std::vector<MeridianPiece> pieces;
    const double d = (ring.hi - ring.lo) / rows;
    b.prefixes.resize(size_t(rows));
    for (int j = 0; j < rows; ++j) {
        band_pieces(mp, sp.radii.z, ring.lo + j * d, ring.lo + (j + 1) * d, pieces);
        band_prefix(pieces, seg, b.prefixes[size_t(j)]);
        // One row keeps the ring's own centre: for a pole that is the pole, not the middle of its cap.
        b.points.push_back(
            ring_point(sp, meridian_point_at(sp, rows == 1 ? ring.centre : ring.lo + (j + 0.5) * d)));
    }
    return b;
}

std::vector<SurfaceSample> sample_product(const SphericalProduct& sp, double spacing, int max_count)
{
    const LoopSegments seg = loop_segments(sp);
    const MeridianPolyline mp = meridian_polyline(sp);
    const Plan plan = plan_rings(sp, seg, spacing, max_count);
    std::vector<SurfaceSample> samples;
    samples.reserve(size_t(plan.count));
    std::vector<Cell> cells;
    std::vector<SubBands> cache;
    for (const Ring& ring : plan.rings) {
        ring_cells(sp, seg, ring, plan.step, cells);
        cache.clear();
        for (const Cell& cell : cells) {
            const SubBands& b = sub_bands(sp, seg, mp, ring, cell.rows, cache);
            for (int j = 0; j < cell.rows; ++j) {
                const SurfacePoint p =
                    spherical_product_point(sp, b.points[size_t(j)], loop_point_at(sp, cell.u));
                const std::vector<double>& prefix = b.prefixes[size_t(j)];
                const double area = loop_prefix_at(sp, prefix, cell.u + cell.half_width) -
                                    loop_prefix_at(sp, prefix, cell.u - cell.half_width);
                samples.push_back({p.point, p.normal, area});
            }
        }
    }
    return samples;
}

// Nanson's formula: a patch dA with normal N maps to |cof(J)·N| dA, cof(J) = det(J)·J^{-T}, whose
// columns are the cross products of J's columns. It needs no inverse, so it stays finite where J is
// singular.
double area_scale(const Mat3& j, const Vec3& n)
{
    const Vec3 c0 = j.col(0), c1 = j.col(1), c2 = j.col(2);
    return length(n.x * cross(c1, c2) + n.y * cross(c2, c0) + n.z * cross(c0, c1));
}

double deform_samples(const ShapeDef& shape, std::vector<SurfaceSample>& samples)
{
    double total = 0.0;
    for (SurfaceSample& s : samples) {
        const Vec3 p = s.point;
        s.area *= area_scale(deform_jacobian(shape, p), s.normal);
        s.point = deform_point(shape, p);
        s.normal = deform_normal(shape, p, s.normal);
        total += s.area;
    }
    return total;
}

double total_area(const std::vector<SurfaceSample>& samples)
{
    double total = 0.0;
    for (const SurfaceSample& s : samples)
        total += s.area;
    return total;
}

} // namespace

std::vector<SurfaceSample> sample_surface(const ShapeDef& shape, double spacing, int max_count)
{
    max_count = std::max(1, max_count);
    if (shape.type == ShapeType::Hyperquadric)
        return sample_hyperquadric_surface(shape, spacing, max_count);
    if (shape.type != ShapeType::Superquadric)
        return {}; // a plane has no finite surface to sample
    const Vec3& a = shape.radii;
    const bool radii_ok = is_finite(a) && a.x > 0.0 && a.y > 0.0 && a.z > 0.0;
    SM_ASSERT(radii_ok, "sample_surface: radii must be finite and > 0");
    if (!radii_ok)
        return {};
    const SphericalProduct sp = make_spherical_product(shape, k_quadrant_segments);
    std::vector<SurfaceSample> samples = sample_product(sp, spacing, max_count);
    if (!is_deformed(shape))
        return samples;
    const double undeformed = total_area(samples);
    const double deformed = deform_samples(shape, samples);
    const double change = deformed / undeformed;
    if (spacing > 0.0 && std::isfinite(change) && change > 0.0 &&
        std::abs(change - 1.0) > k_redraw_area_change) {
        samples = sample_product(sp, spacing / std::sqrt(change), max_count);
        deform_samples(shape, samples);
    }
    return samples;
}

} // namespace supermodal
