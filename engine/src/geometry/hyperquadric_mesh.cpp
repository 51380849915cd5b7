// SPDX-License-Identifier: MIT
// Meshes and surface samples of hyperquadrics. A body with every γ ≥ 1 is convex, hence star-shaped
// about its interior point (the minimiser of H): rays from there through the lattice points of a box
// surface (a "cube sphere"), each cut with H = 1 (hyperquadric.cpp), give a mesh whose vertices lie on
// the surface to round-off and which is watertight by construction, since neighbouring faces share
// their lattice edges. Samples are the vertices, each with a third of its triangles' area.
#include "geometry/hyperquadric_internal.h"
#include "geometry/hyperquadric_solve.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <unordered_map>

namespace supermodal
{
namespace
{

/// Most lattice cells along one axis of a ray grid: 6·4096² ≈ 10^8 vertices is far past any use.
constexpr int k_max_cells = 4096;
/// Cells along the longest axis of the coarse meshes that choose the lattice warp: enough to see
/// where a warp crowds vertices, cheap next to any real mesh (~400 rays each).
constexpr int k_probe_cells = 8;

/// Where the rays go: rays from the centre through a lattice of cells[i] cells along axis i on the box
/// Π[−extent_i, extent_i] of the body's half-extents, so long or flat bodies get proportionally more
/// cells along their long sides. Lattice coordinates are warped from linear (right for box-like bodies,
/// β → 0) to equal angles (right for round ones, β = 1), so samples neither crowd the middle of flat
/// faces nor the edges.
struct RayGrid {
    int cells[3] = {1, 1, 1};
    double extent[3] = {1, 1, 1};
    double beta = 1.0;

    /// Lattice coordinate i of cells[axis] [m], mirrored exactly about the centre.
    [[nodiscard]] double coordinate(int axis, int i) const
    {
        const int n = cells[axis];
        if (2 * i > n)
            return -coordinate(axis, n - i);
        if (2 * i == n)
            return 0.0;
        const double t = 2.0 * i / n - 1.0, q = 0.25 * std::numbers::pi * beta;
        return extent[axis] * (beta < 1e-6 ? t : std::tan(q * t) / std::tan(q));
    }
    [[nodiscard]] Vec3 direction(const int (&l)[3]) const
    {
        return normalized(Vec3{coordinate(0, l[0]), coordinate(1, l[1]), coordinate(2, l[2])});
    }
    [[nodiscard]] size_t vertex_count() const
    {
        return 2 * size_t(cells[0] * cells[1] + cells[1] * cells[2] + cells[2] * cells[0]) + 2;
    }
};

/// A grid whose lattice cells are about `cell` [m] wide on the body's extent box.
RayGrid make_ray_grid(const ShapeDef& shape, const HyperquadricCenter& center, double cell, double beta)
{
    RayGrid g;
    g.beta = beta;
    for (int axis = 0; axis < 3; ++axis) {
        Vec3 e{};
        e[axis] = 1.0;
        const double half = 0.5 * (hyperquadric_ray_exit(shape, center.point, e) +
                                   hyperquadric_ray_exit(shape, center.point, -e));
        g.extent[axis] = half > 0.0 ? half : 1.0;
        const double n = std::ceil(2.0 * g.extent[axis] / cell);
        g.cells[axis] = static_cast<int>(std::clamp(std::isfinite(n) ? n : 1.0, 1.0, double(k_max_cells)));
    }
    return g;
}

/// Watertight mesh of the hyperquadric from the rays of `grid`; deformed shapes map each vertex and
/// its normal afterwards.
TriangleMesh cube_sphere(const ShapeDef& shape, const RayGrid& grid, const HyperquadricCenter& center)
{
    TriangleMesh mesh;
    std::unordered_map<uint64_t, uint32_t> index_of;
    index_of.reserve(grid.vertex_count());
    const bool deformed = is_deformed(shape);
    const auto vertex = [&](const int(&l)[3]) {
        const uint64_t key = (uint64_t(l[0]) * (grid.cells[1] + 1) + l[1]) * (grid.cells[2] + 1) + l[2];
        const auto [it, inserted] = index_of.emplace(key, static_cast<uint32_t>(mesh.positions.size()));
        if (inserted) {
            const Vec3 dir = grid.direction(l);
            const Vec3 p = center.point + hyperquadric_ray_exit(shape, center.point, dir) * dir;
            const Vec3 normal = hyperquadric_normal(shape, p);
            mesh.positions.push_back(deformed ? deform_point(shape, p) : p);
            mesh.normals.push_back(deformed ? deform_normal(shape, p, normal) : normal);
        }
        return it->second;
    };
    for (int axis = 0; axis < 3; ++axis)
        for (int sign = -1; sign <= 1; sign += 2) {
            const int b = (axis + 1) % 3, c = (axis + 2) % 3;
            for (int i = 0; i < grid.cells[b]; ++i)
                for (int j = 0; j < grid.cells[c]; ++j) {
                    uint32_t v[4];
                    const int corner[4][2] = {{i, j}, {i + 1, j}, {i + 1, j + 1}, {i, j + 1}};
                    for (int k = 0; k < 4; ++k) {
                        int l[3];
                        l[axis] = sign > 0 ? grid.cells[axis] : 0;
                        l[b] = corner[k][0];
                        l[c] = corner[k][1];
                        v[k] = vertex(l);
                    }
                    // (e_b, e_c) runs counter-clockwise seen from +e_axis; the −e_axis face is reversed.
                    if (sign < 0)
                        std::swap(v[1], v[3]);
                    const auto& x = mesh.positions;
                    // Split along the shorter diagonal so sharp hyperquadric edges give no slivers.
                    const bool split02 = length(x[v[0]] - x[v[2]]) <= length(x[v[1]] - x[v[3]]);
                    const uint32_t tri[6] = {v[0], v[1], split02 ? v[2] : v[3], split02 ? v[0] : v[1],
                                             v[2], v[3]};
                    mesh.indices.insert(mesh.indices.end(), tri, tri + 6);
                }
        }
    return mesh;
}

double triangle_area(const TriangleMesh& mesh, size_t t)
{
    const Vec3& a = mesh.positions[mesh.indices[t]];
    return 0.5 *
           length(cross(mesh.positions[mesh.indices[t + 1]] - a, mesh.positions[mesh.indices[t + 2]] - a));
}

/// Largest over smallest vertex area (a third of the adjacent triangles): 1 for a perfectly even mesh.
double area_spread(const TriangleMesh& mesh)
{
    std::vector<double> area(mesh.positions.size(), 0.0);
    for (size_t t = 0; t < mesh.indices.size(); t += 3)
        for (size_t k = 0; k < 3; ++k)
            area[mesh.indices[t + k]] += triangle_area(mesh, t);
    const auto [lo, hi] = std::minmax_element(area.begin(), area.end());
    return *lo > 0.0 ? *hi / *lo : std::numeric_limits<double>::infinity();
}

/// The warp β that spreads a coarse mesh most evenly: neither "round" (β = 1) nor "box" (β = 0) fits
/// every hyperquadric (a cut hypercube is neither), so the three candidates are simply tried.
double choose_beta(const ShapeDef& shape, const HyperquadricCenter& center)
{
    const RayGrid probe = make_ray_grid(shape, center, 1.0, 1.0);
    const double cell = 2.0 * std::max({probe.extent[0], probe.extent[1], probe.extent[2]}) / k_probe_cells;
    double best_beta = 1.0, best_spread = std::numeric_limits<double>::infinity();
    for (double beta : {1.0, 0.5, 0.0}) {
        const double spread =
            area_spread(cube_sphere(shape, make_ray_grid(shape, center, cell, beta), center));
        if (spread < best_spread) {
            best_spread = spread;
            best_beta = beta;
        }
    }
    return best_beta;
}

} // namespace

TriangleMesh tessellate_hyperquadric(const ShapeDef& shape, int resolution)
{
    const HyperquadricCenter center = hyperquadric_center(shape);
    if (!center.is_bounded || !center.is_non_empty)
        return {};
    // `resolution` segments around the equator (about z) = 2(cells_x + cells_y).
    const RayGrid extents = make_ray_grid(shape, center, 1.0, 1.0);
    const double cell = 4.0 * (extents.extent[0] + extents.extent[1]) / std::max(resolution, 4);
    return cube_sphere(shape, make_ray_grid(shape, center, cell, choose_beta(shape, center)), center);
}

std::vector<SurfaceSample> sample_hyperquadric_surface(const ShapeDef& shape, double spacing, int max_count)
{
    const HyperquadricCenter center = hyperquadric_center(shape);
    if (!center.is_bounded || !center.is_non_empty || max_count <= 0)
        return {};
    // One vertex per lattice cell of size `spacing`; widened by 10% steps until the count fits.
    const double beta = choose_beta(shape, center);
    RayGrid grid = make_ray_grid(shape, center, 1.0, beta);
    double cell = spacing > 0.0 && std::isfinite(spacing) ? spacing : 2.0 * grid.extent[0];
    grid = make_ray_grid(shape, center, cell, beta);
    while (grid.vertex_count() > static_cast<size_t>(max_count) && grid.vertex_count() > 8) {
        cell *= 1.1;
        grid = make_ray_grid(shape, center, cell, beta);
    }
    const TriangleMesh mesh = cube_sphere(shape, grid, center);
    std::vector<SurfaceSample> samples(mesh.positions.size());
    for (size_t i = 0; i < samples.size(); ++i)
        samples[i] = {.point = mesh.positions[i], .normal = mesh.normals[i], .area = 0.0};
    double total = 0.0;
    for (size_t t = 0; t < mesh.indices.size(); t += 3) {
        const double a = triangle_area(mesh, t);
        total += a;
        for (size_t k = 0; k < 3; ++k)
            samples[mesh.indices[t + k]].area += a / 3.0;
    }
    if (samples.size() > static_cast<size_t>(max_count)) {
        // Only when max_count < 8 (one cell per axis): keep the first ones, still summing to the area.
        samples.resize(static_cast<size_t>(max_count));
        double kept = 0.0;
        for (const SurfaceSample& x : samples)
            kept += x.area;
        for (SurfaceSample& x : samples)
            x.area *= kept > 0.0 ? total / kept : 0.0;
    }
    return samples;
}

} // namespace supermodal
