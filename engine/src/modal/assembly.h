// SPDX-License-Identifier: MIT
// The finite-element model behind a modal basis: a lattice over the shape's bounding box, isotropic
// linear-elastic stiffness and consistent mass integrated over the part of each cell inside the body,
// assembled into sparse matrices.
#pragma once

#include "modal/lattice.h"
#include "supermodal/modal.h"

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <vector>

namespace supermodal::modal
{

using SparseMatrix = Eigen::SparseMatrix<double>;

/// Lamé parameters λ, μ [Pa] of an isotropic material.
struct Lame {
    double lambda = 0.0;
    double mu = 0.0;
};
[[nodiscard]] Lame lame_from(double young, double poisson);

/// A lattice with its material: the full model that modes are computed from.
struct LatticeModel {
    Lattice lattice;
    std::vector<int32_t> cell_nodes;           ///< (cells × nodes per cell) node indices, −1 if empty.
    std::vector<int32_t> cell_proxy;           ///< Per cell: itself if it has nodes, else the nearest
                                               ///< cell that has (a sliver: the cell it was merged into).
    std::vector<Vec3> node_positions;          ///< Rest positions [m], shape frame.
    std::vector<std::array<int, 3>> node_grid; ///< Node-grid coordinates of each node.
    SparseMatrix stiffness;                    ///< K (3n × 3n) [N/m], dof 3·node + axis.
    SparseMatrix mass;                         ///< Consistent M (3n × 3n) [kg].
    int kept_cell_count = 0;
    int cut_cell_count = 0;
    int aggregated_cell_count = 0; ///< Slivers merged into a face neighbour.
    int dropped_sliver_count = 0;  ///< Slivers with no face neighbour to merge into: material lost.

    LatticeModel() = default;
    LatticeModel(const LatticeModel&) = default;
    LatticeModel& operator=(const LatticeModel&) = default;
    /// Moves swap K and M: Eigen 3.4's SparseMatrix has no move, and copying them costs as much as
    /// assembling them on a large lattice.
    LatticeModel(LatticeModel&& other) noexcept { *this = std::move(other); }
    LatticeModel& operator=(LatticeModel&& other) noexcept;

    [[nodiscard]] int node_count() const { return static_cast<int>(node_positions.size()); }
    [[nodiscard]] int dof_count() const { return 3 * node_count(); }
};

/// Builds the lattice and integrates K and M. Cells the surface cuts are integrated with
/// cut_cell_subdivisions³ sub-cells of 2×2×2 Gauss points and an inside indicator (first-order
/// accurate in the sub-cell size, so it converges as cells are refined); cells entirely inside use the
/// exact 3×3×3 rule; cells with no inside point are dropped, and so are nodes that only they touch.
/// A cut cell whose inside points cannot pin its strain field (a sliver: left alone it would add
/// zero-energy modes) is merged into its nearest good face neighbour, whose field extends over it.
/// Errors: a shape without finite bounds, or no material on the lattice.
[[nodiscard]] Result<LatticeModel> assemble_lattice_model(const ModalBasisDef& def);

/// For each cell, the nearest source cell by face steps (breadth-first from all sources at once, in
/// index order, so ties break deterministically); −1 everywhere when there is no source.
[[nodiscard]] std::vector<int32_t> nearest_cells(const Lattice& lattice,
                                                 const std::vector<uint8_t>& is_source);

/// The six rigid-body motions at the nodes (3n × 6): translations x, y, z, then rotations about x, y, z
/// through the lattice centre. Not orthonormalised.
[[nodiscard]] Eigen::MatrixXd rigid_body_vectors(const LatticeModel& model);

} // namespace supermodal::modal
