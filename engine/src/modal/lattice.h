// SPDX-License-Identifier: MIT
// The uniform hexahedral lattice of a modal basis: cell and node numbering, and the shape functions
// of 8-node (trilinear) and 20-node (serendipity) cells in natural coordinates ξ ∈ [−1, 1]³.
//
// Nodes live on a "node grid" of order·cells + 1 points per axis: order 1 uses every grid point (cell
// corners), order 2 the points with at most one odd index (corners and edge midpoints; 20 per cell).
#pragma once

#include "supermodal/math.h"
#include "supermodal/modal.h"

#include <array>
#include <cstdint>

namespace supermodal::modal
{

inline constexpr int k_max_cell_nodes = 20;

/// Local node table of one cell: offsets on the node grid from the cell's low corner (each 0..order)
/// and natural coordinates (−1, 0 or 1 per axis).
struct CellNodes {
    int count = 0;
    std::array<std::array<int, 3>, k_max_cell_nodes> offset{};
    std::array<std::array<double, 3>, k_max_cell_nodes> xi{};
};
/// The local node order used everywhere (z slowest, x fastest; order 2 skips face and body centres).
[[nodiscard]] const CellNodes& cell_nodes_of_order(int order);

/// Shape function values N[a] and natural derivatives dN[a][axis] at ξ, for one element order; dn_out
/// may be null when only the values are needed.
void shape_functions(int order, const std::array<double, 3>& xi, double* n_out,
                     std::array<double, 3>* dn_out);

/// A uniform lattice over an axis-aligned box.
struct Lattice {
    std::array<int, 3> cells{};
    int order = 2;
    Vec3 min{};       ///< Low corner [m].
    Vec3 cell_size{}; ///< [m].

    [[nodiscard]] int cell_count() const { return cells[0] * cells[1] * cells[2]; }
    [[nodiscard]] int grid_points(int axis) const { return order * cells[axis] + 1; }
    [[nodiscard]] int grid_count() const { return grid_points(0) * grid_points(1) * grid_points(2); }
    [[nodiscard]] int cell_index(int i, int j, int k) const { return i + cells[0] * (j + cells[1] * k); }
    [[nodiscard]] int grid_index(int i, int j, int k) const
    {
        return i + grid_points(0) * (j + grid_points(1) * k);
    }
    /// Rest position of a node-grid point [m].
    [[nodiscard]] Vec3 grid_position(int i, int j, int k) const
    {
        return {min.x + cell_size.x * i / order, min.y + cell_size.y * j / order,
                min.z + cell_size.z * k / order};
    }
    /// Node-grid indices of one cell's nodes, in the local order.
    void cell_grid_nodes(int i, int j, int k, int32_t* out) const;
    /// Centre of cell (i, j, k) [m].
    [[nodiscard]] Vec3 cell_center(int i, int j, int k) const
    {
        return {min.x + cell_size.x * (i + 0.5), min.y + cell_size.y * (j + 0.5),
                min.z + cell_size.z * (k + 0.5)};
    }
};

/// Default lattice of 20-node cells (docs/modal.md, "Default lattice"): cells along the longest side
/// of the shape's box [-], ...
inline constexpr int k_default_long_cells = 16;
/// ... at least this many through every other side, however thin [-], ...
inline constexpr int k_default_thin_cells = 3;
/// ... and fewer cells along every side while the lattice would have more degrees of freedom than this
/// (lattice_dof_bound) [-].
inline constexpr int k_default_max_dofs = 3000;

/// Degrees of freedom of a lattice over its full box: corners, plus edge midpoints for 20-node cells.
/// An upper bound (cells the body does not reach carry none), known before anything is built.
/// Exported (SM_API): the scene reader in the assets library refuses oversized lattices with it.
[[nodiscard]] SM_API int lattice_dof_bound(const std::array<int, 3>& cells, int order);

/// Cells per axis for the zeros of `requested` from the box's extent [m]: 20-node cells as the constants
/// above say (a sphere gets 5³, the 2x4 board 16 × 3 × 3); 8-node cells 16 along the longest side, at
/// least 2, at most 512 cells (a sphere 8³). Requested counts > 0 are kept.
[[nodiscard]] std::array<int, 3> resolve_cells(const std::array<int, 3>& requested, int order,
                                               const Vec3& extent);

/// The cell containing p (clamped into the box) and p's natural coordinates in it (clamped to [−1, 1]).
void locate(const Lattice& lattice, const Vec3& p, std::array<int, 3>& out_cell,
            std::array<double, 3>& out_xi);

/// The lattice a basis was built on.
[[nodiscard]] Lattice lattice_of(const ModalBasis& basis);

/// The cell whose field covers p (shape frame) [m]: p's own cell or, for a cell without nodes, its
/// proxy, with p's natural coordinates extended into the proxy (at most one cell beyond it: a merged
/// sliver is exactly that extension). Returns the proxy cell's index, or −1 when no field covers p.
[[nodiscard]] int locate_field(const ModalBasis& basis, const Lattice& lattice, const Vec3& p,
                               std::array<double, 3>& out_xi);

} // namespace supermodal::modal
