// SPDX-License-Identifier: MIT
// Lattice numbering and hexahedral shape functions (see lattice.h).
#include "modal/lattice.h"

#include <algorithm>
#include <cmath>

namespace supermodal::modal
{
namespace
{

CellNodes make_cell_nodes(int order)
{
    CellNodes c;
    for (int k = 0; k <= order; ++k)
        for (int j = 0; j <= order; ++j)
            for (int i = 0; i <= order; ++i) {
                // Serendipity: corners and edge midpoints only (at most one index at the midpoint).
                if (order == 2 && (i == 1) + (j == 1) + (k == 1) > 1)
                    continue;
                c.offset[c.count] = {i, j, k};
                c.xi[c.count] = {2.0 * i / order - 1.0, 2.0 * j / order - 1.0, 2.0 * k / order - 1.0};
                ++c.count;
            }
    return c;
}

const CellNodes k_linear_nodes = make_cell_nodes(1);
const CellNodes k_serendipity_nodes = make_cell_nodes(2);

} // namespace

const CellNodes& cell_nodes_of_order(int order)
{
    return order == 1 ? k_linear_nodes : k_serendipity_nodes;
}

void shape_functions(int order, const std::array<double, 3>& xi, double* n_out, std::array<double, 3>* dn_out)
{
    const CellNodes& nodes = cell_nodes_of_order(order);
    for (int a = 0; a < nodes.count; ++a) {
        const std::array<double, 3>& c = nodes.xi[a];
        // Linear factor (1 + ξ ξa) per axis where the node is at a corner coordinate; the serendipity
        // edge node has one axis with ξa = 0, where the factor is the bubble (1 − ξ²).
        double f[3], df[3];
        int mid_axis = -1;
        for (int d = 0; d < 3; ++d) {
            if (c[d] == 0.0) {
                mid_axis = d;
                f[d] = 1.0 - xi[d] * xi[d];
                df[d] = -2.0 * xi[d];
            } else {
                f[d] = 1.0 + xi[d] * c[d];
                df[d] = c[d];
            }
        }
        if (order == 1) {
            n_out[a] = 0.125 * f[0] * f[1] * f[2];
            if (dn_out != nullptr)
                dn_out[a] = {0.125 * df[0] * f[1] * f[2], 0.125 * f[0] * df[1] * f[2],
                             0.125 * f[0] * f[1] * df[2]};
        } else if (mid_axis >= 0) {
            n_out[a] = 0.25 * f[0] * f[1] * f[2];
            if (dn_out != nullptr)
                dn_out[a] = {0.25 * df[0] * f[1] * f[2], 0.25 * f[0] * df[1] * f[2],
                             0.25 * f[0] * f[1] * df[2]};
        } else {
            // Corner: N = ⅛ Π(1 + ξ ξa) · (Σ ξ ξa − 2).
            const double s = xi[0] * c[0] + xi[1] * c[1] + xi[2] * c[2] - 2.0;
            const double p = f[0] * f[1] * f[2];
            n_out[a] = 0.125 * p * s;
            if (dn_out != nullptr)
                dn_out[a] = {0.125 * (df[0] * f[1] * f[2] * s + p * c[0]),
                             0.125 * (f[0] * df[1] * f[2] * s + p * c[1]),
                             0.125 * (f[0] * f[1] * df[2] * s + p * c[2])};
        }
    }
}

void Lattice::cell_grid_nodes(int i, int j, int k, int32_t* out) const
{
    const CellNodes& nodes = cell_nodes_of_order(order);
    for (int a = 0; a < nodes.count; ++a) {
        const std::array<int, 3>& o = nodes.offset[a];
        out[a] = grid_index(order * i + o[0], order * j + o[1], order * k + o[2]);
    }
}

int lattice_dof_bound(const std::array<int, 3>& cells, int order)
{
    const long nx = cells[0], ny = cells[1], nz = cells[2];
    long nodes = (nx + 1) * (ny + 1) * (nz + 1);
    if (order == 2)
        nodes += nx * (ny + 1) * (nz + 1) + (nx + 1) * ny * (nz + 1) + (nx + 1) * (ny + 1) * nz;
    return static_cast<int>(std::min<long>(3 * nodes, 1L << 30));
}

std::array<int, 3> resolve_cells(const std::array<int, 3>& requested, int order, const Vec3& extent)
{
    // 20-node cells: k_default_long_cells along the longest side, the others in proportion but at least
    // k_default_thin_cells (one quadratic cell through a thin board cannot follow the warping of its
    // section in torsion; two leave a rounded section's bending 2% stiff), coarser everywhere while the
    // lattice would pass k_default_max_dofs (a compact body needs fewer cells than a slender one for the same
    // accuracy). 8-node cells lock in bending; their default stays 16 along the longest side, at least 2, at
    // most 512 cells.
    const bool serendipity = order != 1;
    const int n_min = serendipity ? k_default_thin_cells : 2;
    const double longest = std::max({extent.x, extent.y, extent.z});
    std::array<int, 3> cells{};
    for (int n_long = serendipity ? k_default_long_cells : 16; n_long >= n_min; --n_long) {
        for (int d = 0; d < 3; ++d) {
            const auto proportional = static_cast<int>(std::lround(n_long * extent[d] / longest));
            cells[d] = requested[d] > 0 ? requested[d] : std::max(n_min, proportional);
        }
        const bool fits = serendipity ? lattice_dof_bound(cells, order) <= k_default_max_dofs
                                      : cells[0] * cells[1] * cells[2] <= 512;
        if (fits)
            break;
    }
    return cells;
}

void locate(const Lattice& lattice, const Vec3& p, std::array<int, 3>& out_cell,
            std::array<double, 3>& out_xi)
{
    for (int d = 0; d < 3; ++d) {
        double u = (p[d] - lattice.min[d]) / lattice.cell_size[d]; // in cells
        if (std::isnan(u))
            u = 0.0; // a NaN point must not become an out-of-range index
        const double cell = std::clamp(std::floor(u), 0.0, static_cast<double>(lattice.cells[d] - 1));
        out_cell[d] = static_cast<int>(cell);
        out_xi[d] = std::clamp(2.0 * (u - cell) - 1.0, -1.0, 1.0);
    }
}

Lattice lattice_of(const ModalBasis& basis)
{
    Lattice lat;
    lat.cells = basis.cells;
    lat.order = basis.element_order;
    lat.min = basis.lattice_min;
    lat.cell_size = basis.cell_size;
    return lat;
}

int locate_field(const ModalBasis& basis, const Lattice& lat, const Vec3& p, std::array<double, 3>& out_xi)
{
    if (basis.cell_proxy.empty() || lat.cell_count() != static_cast<int>(basis.cell_proxy.size()))
        return -1;
    std::array<int, 3> cell{};
    locate(lat, p, cell, out_xi);
    const int proxy = basis.cell_proxy[lat.cell_index(cell[0], cell[1], cell[2])];
    if (proxy < 0)
        return -1;
    const int pidx[3] = {proxy % lat.cells[0], (proxy / lat.cells[0]) % lat.cells[1],
                         proxy / (lat.cells[0] * lat.cells[1])};
    for (int d = 0; d < 3; ++d)
        if (pidx[d] != cell[d])
            out_xi[d] = std::clamp(out_xi[d] + 2.0 * (cell[d] - pidx[d]), -3.0, 3.0);
    return proxy;
}

} // namespace supermodal::modal
