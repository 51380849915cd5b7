// SPDX-License-Identifier: MIT
// Lattice stiffness and mass over the inside of a shape (see assembly.h).
#include "modal/assembly.h"

#include "supermodal/geometry.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <deque>
#include <span>
#include <string>

namespace supermodal::modal
{
namespace
{

/// Quadrature points of a cell template: natural coordinates, weights (summing to 8, the natural
/// volume) and the shape-function data there, for a cell of the lattice's size.
struct PointTable {
    std::vector<std::array<double, 3>> xi;
    Eigen::VectorXd weight;
    Eigen::MatrixXd n;    ///< (points × nodes) N_a.
    Eigen::MatrixXd grad; ///< (points × 3·nodes) ∂N_a/∂x_i [1/m], column 3a + i.
};

/// `shift` (cells) evaluates the shape functions of the cell that far away, extended to these points.
PointTable make_table(const Lattice& lattice, int subdivisions, int points_1d,
                      const std::array<int, 3>& shift)
{
    // Gauss–Legendre on [−1, 1]: 2 points (exact to degree 3) or 3 points (degree 5).
    const double g2[2] = {-1.0 / std::sqrt(3.0), 1.0 / std::sqrt(3.0)}, w2[2] = {1.0, 1.0};
    const double g3[3] = {-std::sqrt(0.6), 0.0, std::sqrt(0.6)}, w3[3] = {5.0 / 9.0, 8.0 / 9.0, 5.0 / 9.0};
    const double* g = points_1d == 2 ? g2 : g3;
    const double* w = points_1d == 2 ? w2 : w3;
    std::vector<double> x1, w1; // composite rule along one axis
    for (int s = 0; s < subdivisions; ++s)
        for (int q = 0; q < points_1d; ++q) {
            const double half = 1.0 / subdivisions;
            x1.push_back(-1.0 + half * (2 * s + 1) + half * g[q]);
            w1.push_back(half * w[q]);
        }
    const int m = static_cast<int>(x1.size());
    const int count = cell_nodes_of_order(lattice.order).count;
    PointTable t;
    t.weight.resize(m * m * m);
    t.n.resize(m * m * m, count);
    t.grad.resize(m * m * m, 3 * count);
    double n[k_max_cell_nodes];
    std::array<double, 3> dn[k_max_cell_nodes];
    int p = 0;
    for (int k = 0; k < m; ++k)
        for (int j = 0; j < m; ++j)
            for (int i = 0; i < m; ++i, ++p) {
                t.xi.push_back({x1[i], x1[j], x1[k]});
                t.weight[p] = w1[i] * w1[j] * w1[k];
                shape_functions(lattice.order,
                                {x1[i] + 2.0 * shift[0], x1[j] + 2.0 * shift[1], x1[k] + 2.0 * shift[2]}, n,
                                dn);
                for (int a = 0; a < count; ++a) {
                    t.n(p, a) = n[a];
                    for (int d = 0; d < 3; ++d) // uniform box cell: ∂ξ/∂x = 2 / h
                        t.grad(p, 3 * a + d) = dn[a][d] * 2.0 / lattice.cell_size[d];
                }
            }
    return t;
}

/// Maps one point's reference gradients (row of t.grad) to the moulded cell whose nodes moved by
/// `offsets` (isoparametric: x = X + Σ N_a u_a, F = I + Σ u_a ⊗ ∇N_a, ∇_x N = F⁻ᵀ ∇_X N); returns det F,
/// ≤ 0 where the moulded cell is inverted.
double moulded_gradients(const PointTable& t, int p, const Vec3* offsets, Eigen::RowVectorXd& out_grad)
{
    const auto count = static_cast<int>(t.n.cols());
    Eigen::Matrix3d f = Eigen::Matrix3d::Identity();
    for (int a = 0; a < count; ++a)
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j)
                f(i, j) += offsets[a][i] * t.grad(p, 3 * a + j);
    const double det = f.determinant();
    if (!(det > 0.0))
        return det;
    const Eigen::Matrix3d f_inv_t = f.inverse().transpose();
    out_grad.resize(3 * count);
    for (int a = 0; a < count; ++a)
        out_grad.segment<3>(3 * a) = (f_inv_t * t.grad.row(p).segment<3>(3 * a).transpose()).transpose();
    return det;
}

/// Element stiffness and mass from the points selected by `rows` (all when empty). With `offsets`
/// (the cell's nodes' rest offsets [m]) the cell is integrated over its moulded shape; returns false
/// where that shape is inverted.
bool element_matrices(const PointTable& t, const std::vector<int>& rows, double det_j, const Lame& lame,
                      double density, Eigen::MatrixXd& out_k, Eigen::MatrixXd& out_m,
                      const Vec3* offsets = nullptr)
{
    const auto count = static_cast<int>(t.n.cols());
    const int m = rows.empty() ? static_cast<int>(t.weight.size()) : static_cast<int>(rows.size());
    Eigen::MatrixXd g(m, 3 * count), gw(m, 3 * count), n(m, count), nw(m, count);
    Eigen::RowVectorXd moved;
    for (int r = 0; r < m; ++r) {
        const int p = rows.empty() ? r : rows[r];
        double w = t.weight[p] * det_j;
        if (offsets != nullptr) {
            const double det_f = moulded_gradients(t, p, offsets, moved);
            if (!(det_f > 0.0))
                return false;
            w *= det_f;
            g.row(r) = moved;
        } else {
            g.row(r) = t.grad.row(p);
        }
        gw.row(r) = w * g.row(r);
        n.row(r) = t.n.row(p);
        nw.row(r) = (w * density) * t.n.row(p);
    }
    // S_(a,i),(b,j) = ∫ ∂_i N_a ∂_j N_b: one matrix product, then the isotropic stiffness
    // K_(a,i),(b,j) = λ S_(a,i),(b,j) + μ S_(a,j),(b,i) + μ δ_ij Σ_m S_(a,m),(b,m).
    const Eigen::MatrixXd s = g.transpose() * gw;
    out_k.resize(3 * count, 3 * count);
    for (int a = 0; a < count; ++a)
        for (int b = 0; b < count; ++b) {
            const double trace = s(3 * a, 3 * b) + s(3 * a + 1, 3 * b + 1) + s(3 * a + 2, 3 * b + 2);
            for (int i = 0; i < 3; ++i)
                for (int j = 0; j < 3; ++j)
                    out_k(3 * a + i, 3 * b + j) = lame.lambda * s(3 * a + i, 3 * b + j) +
                                                  lame.mu * s(3 * a + j, 3 * b + i) +
                                                  (i == j ? lame.mu * trace : 0.0);
        }
    out_m = n.transpose() * nw;
    return true;
}

/// True when the inside points of a cut cell leave more than the six rigid motions strain-free: then
/// the cell has spurious zero-energy (hourglass) patterns that would show up as extra zero modes or
/// make K − σM singular. Happens for slivers and thin slabs (one or two layers of points).
bool under_resolved(const Eigen::MatrixXd& k_e)
{
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(k_e, Eigen::EigenvaluesOnly);
    const Eigen::VectorXd& values = es.eigenvalues();
    const double tolerance = 1e-8 * values[values.size() - 1];
    return (values.array() < tolerance).count() > 6;
}

struct Bounds {
    Vec3 min{}, max{};
};

Result<Bounds> shape_bounds(const ShapeDef& shape)
{
    Bounds b;
    if (shape.type == ShapeType::Superquadric && !is_deformed(shape)) {
        b.min = -shape.radii;
        b.max = shape.radii;
    } else {
        const Aabb box = world_aabb(shape, {}, Quat::identity());
        b.min = box.min;
        b.max = box.max;
    }
    for (int d = 0; d < 3; ++d)
        if (!std::isfinite(b.min[d]) || !std::isfinite(b.max[d]) || !(b.max[d] > b.min[d]) ||
            b.max[d] - b.min[d] > 1e9)
            return Error{"", "/shape", "expected a shape with finite, non-empty bounds"};
    return b;
}

bool inside(const ShapeDef& shape, bool plain, const Vec3& p)
{
    return (plain ? contact_measure(shape, p) : shape_measure(shape, p)) < 0.0;
}

} // namespace

LatticeModel& LatticeModel::operator=(LatticeModel&& other) noexcept
{
    lattice = other.lattice;
    cell_nodes = std::move(other.cell_nodes);
    cell_proxy = std::move(other.cell_proxy);
    node_positions = std::move(other.node_positions);
    node_grid = std::move(other.node_grid);
    stiffness.swap(other.stiffness);
    mass.swap(other.mass);
    kept_cell_count = other.kept_cell_count;
    cut_cell_count = other.cut_cell_count;
    aggregated_cell_count = other.aggregated_cell_count;
    dropped_sliver_count = other.dropped_sliver_count;
    return *this;
}

Lame lame_from(double young, double poisson)
{
    return {young * poisson / ((1.0 + poisson) * (1.0 - 2.0 * poisson)), young / (2.0 * (1.0 + poisson))};
}

namespace
{

enum class CellState : uint8_t {
    Empty,  ///< No inside point: dropped.
    Full,   ///< Every point inside: the exact full-cell matrices.
    Cut,    ///< Integrated over its inside points.
    Sliver, ///< Too few inside points to pin its strain field: merged into a neighbour (or dropped).
};

/// Per-cell working data of one build.
struct CellWork {
    std::vector<CellState> state;
    std::vector<std::vector<int>> rows; ///< Inside points (cut template) of Cut/Sliver cells.
    std::vector<Eigen::MatrixXd> k, m;  ///< Own matrices of Cut cells and of aggregation roots.
    Eigen::MatrixXd full_k, full_m;
};

/// Which cut-template points of every cell lie inside the shape.
void classify_cells(const ModalBasisDef& def, const Lattice& lat, const PointTable& cut, CellWork& w)
{
    const bool plain = def.shape.type == ShapeType::Superquadric && !is_deformed(def.shape);
    w.state.assign(lat.cell_count(), CellState::Empty);
    w.rows.assign(lat.cell_count(), {});
    for (int k = 0; k < lat.cells[2]; ++k)
        for (int j = 0; j < lat.cells[1]; ++j)
            for (int i = 0; i < lat.cells[0]; ++i) {
                const int c = lat.cell_index(i, j, k);
                const Vec3 center = lat.cell_center(i, j, k);
                std::vector<int>& rows = w.rows[c];
                for (size_t p = 0; p < cut.xi.size(); ++p) {
                    const Vec3 xi{cut.xi[p][0], cut.xi[p][1], cut.xi[p][2]};
                    if (inside(def.shape, plain, center + 0.5 * hadamard(xi, lat.cell_size)))
                        rows.push_back(static_cast<int>(p));
                }
                if (rows.size() == cut.xi.size()) {
                    w.state[c] = CellState::Full;
                    rows.clear();
                } else if (!rows.empty()) {
                    w.state[c] = CellState::Cut;
                }
            }
}

std::array<int, 3> cell_coords(const Lattice& lat, int c)
{
    return {c % lat.cells[0], (c / lat.cells[0]) % lat.cells[1], c / (lat.cells[0] * lat.cells[1])};
}

/// Merges each sliver into the neighbouring cell its proxy names (cell aggregation: Badia, Verdugo &
/// Martín 2018): the sliver's inside points are integrated with the root cell's shape functions,
/// extended one cell beyond it. Slivers with no good face neighbour are dropped.
void aggregate_slivers(const ModalBasisDef& def, const Lattice& lat, const std::vector<int32_t>& proxy,
                       double det_j, const Lame& lame, CellWork& w, LatticeModel& model)
{
    Eigen::MatrixXd ke, me;
    for (int c = 0; c < lat.cell_count(); ++c) {
        if (w.state[c] != CellState::Sliver)
            continue;
        const int root = proxy[c];
        const std::array<int, 3> a = cell_coords(lat, c), b = cell_coords(lat, root);
        const std::array<int, 3> shift{a[0] - b[0], a[1] - b[1], a[2] - b[2]};
        if (std::abs(shift[0]) + std::abs(shift[1]) + std::abs(shift[2]) != 1) {
            w.state[c] = CellState::Empty;
            ++model.dropped_sliver_count;
            continue;
        }
        if (w.k[root].size() == 0) { // a Full root gets its own copy to add to
            w.k[root] = w.full_k;
            w.m[root] = w.full_m;
        }
        const PointTable shifted = make_table(lat, def.lattice.cut_cell_subdivisions, 2, shift);
        element_matrices(shifted, w.rows[c], det_j, lame, def.density, ke, me);
        w.k[root] += ke;
        w.m[root] += me;
        ++model.aggregated_cell_count;
    }
}

bool is_good(CellState s)
{
    return s == CellState::Full || s == CellState::Cut;
}

/// Numbers the nodes of good cells in node-grid order (deterministic) and fills cell_nodes.
void number_nodes(const Lattice& lat, const CellWork& w, LatticeModel& model)
{
    const int per_cell = cell_nodes_of_order(lat.order).count;
    std::vector<int32_t> grid_to_node(lat.grid_count(), -1);
    std::vector<int32_t> grid_nodes(static_cast<size_t>(lat.cell_count()) * per_cell, -1);
    for (int c = 0; c < lat.cell_count(); ++c) {
        if (!is_good(w.state[c]))
            continue;
        const std::array<int, 3> ijk = cell_coords(lat, c);
        lat.cell_grid_nodes(ijk[0], ijk[1], ijk[2], &grid_nodes[static_cast<size_t>(c) * per_cell]);
        for (int a = 0; a < per_cell; ++a)
            grid_to_node[grid_nodes[static_cast<size_t>(c) * per_cell + a]] = 0;
    }
    for (int k = 0; k < lat.grid_points(2); ++k)
        for (int j = 0; j < lat.grid_points(1); ++j)
            for (int i = 0; i < lat.grid_points(0); ++i) {
                int32_t& slot = grid_to_node[lat.grid_index(i, j, k)];
                if (slot < 0)
                    continue;
                slot = model.node_count();
                model.node_positions.push_back(lat.grid_position(i, j, k));
                model.node_grid.push_back({i, j, k});
            }
    model.cell_nodes.assign(grid_nodes.size(), -1);
    for (size_t i = 0; i < grid_nodes.size(); ++i)
        if (grid_nodes[i] >= 0)
            model.cell_nodes[i] = grid_to_node[grid_nodes[i]];
}

/// Per node, the sorted nodes it shares a kept cell with (itself included): the sparsity of K and M
/// by 3 × 3 node blocks.
std::vector<std::vector<int32_t>> node_neighbours(const Lattice& lat, const CellWork& w,
                                                  const LatticeModel& model)
{
    const int per_cell = cell_nodes_of_order(lat.order).count;
    std::vector<std::vector<int32_t>> near(static_cast<size_t>(model.node_count()));
    for (int c = 0; c < lat.cell_count(); ++c) {
        if (!is_good(w.state[c]))
            continue;
        const int32_t* nodes = &model.cell_nodes[static_cast<size_t>(c) * per_cell];
        for (int a = 0; a < per_cell; ++a)
            near[nodes[a]].insert(near[nodes[a]].end(), nodes, nodes + per_cell);
    }
    for (std::vector<int32_t>& list : near) {
        std::sort(list.begin(), list.end());
        list.erase(std::unique(list.begin(), list.end()), list.end());
    }
    return near;
}

/// Compressed columns with the node-block pattern: every (row node, column node) pair in `near` gives
/// rows 3a + i of column 3b + j, for i ∈ `rows_of(j)` (all three for K, i = j for M). Values zero.
SparseMatrix block_pattern(const std::vector<std::vector<int32_t>>& near, bool diagonal_blocks)
{
    const auto nodes = static_cast<int>(near.size());
    const int per_pair = diagonal_blocks ? 1 : 3;
    SparseMatrix a(3 * nodes, 3 * nodes);
    size_t total = 0;
    for (const std::vector<int32_t>& list : near)
        total += 3 * per_pair * list.size();
    a.resizeNonZeros(static_cast<Eigen::Index>(total));
    int* outer = a.outerIndexPtr();
    int* inner = a.innerIndexPtr();
    int at = 0;
    for (int b = 0; b < nodes; ++b)
        for (int j = 0; j < 3; ++j) {
            outer[3 * b + j] = at;
            for (const int32_t node : near[b])
                for (int i = 0; i < 3; ++i)
                    if (!diagonal_blocks || i == j)
                        inner[at++] = 3 * node + i;
        }
    outer[3 * nodes] = at;
    std::fill(a.valuePtr(), a.valuePtr() + at, 0.0);
    return a;
}

/// Adds each kept cell's K and M into compressed storage with the node-block pattern, cell by cell
/// (the sums come out in the order a triplet assembly would make them).
void scatter(const Lattice& lat, const CellWork& w, LatticeModel& model)
{
    const int per_cell = cell_nodes_of_order(lat.order).count;
    const std::vector<std::vector<int32_t>> near = node_neighbours(lat, w, model);
    SparseMatrix k = block_pattern(near, false), m = block_pattern(near, true);
    model.stiffness.swap(k);
    model.mass.swap(m);
    double* k_values = model.stiffness.valuePtr();
    double* m_values = model.mass.valuePtr();
    const int* k_outer = model.stiffness.outerIndexPtr();
    const int* m_outer = model.mass.outerIndexPtr();
    int slot[k_max_cell_nodes]; // position of row node a among column node b's neighbours
    for (int c = 0; c < lat.cell_count(); ++c) {
        if (!is_good(w.state[c]))
            continue;
        ++model.kept_cell_count;
        model.cut_cell_count += w.state[c] == CellState::Cut;
        const int32_t* nodes = &model.cell_nodes[static_cast<size_t>(c) * per_cell];
        const bool own = w.k[c].size() > 0;
        const Eigen::MatrixXd& k_e = own ? w.k[c] : w.full_k;
        const Eigen::MatrixXd& m_e = own ? w.m[c] : w.full_m;
        for (int b = 0; b < per_cell; ++b) {
            const std::vector<int32_t>& list = near[nodes[b]];
            for (int a = 0; a < per_cell; ++a)
                slot[a] =
                    static_cast<int>(std::lower_bound(list.begin(), list.end(), nodes[a]) - list.begin());
            for (int j = 0; j < 3; ++j) {
                const int col = 3 * nodes[b] + j;
                double* k_col = k_values + k_outer[col];
                double* m_col = m_values + m_outer[col];
                for (int a = 0; a < per_cell; ++a) {
                    for (int i = 0; i < 3; ++i)
                        k_col[3 * slot[a] + i] += k_e(3 * a + i, 3 * b + j);
                    m_col[slot[a]] += m_e(a, b);
                }
            }
        }
    }
}

/// The rest offsets [m] of cell c's nodes (its proxy's for a merged sliver).
std::vector<Vec3> cell_offsets(const LatticeModel& model, int per_cell, int c, std::span<const Vec3> offsets)
{
    std::vector<Vec3> out(static_cast<size_t>(per_cell));
    for (int a = 0; a < per_cell; ++a)
        out[a] = offsets[static_cast<size_t>(model.cell_nodes[static_cast<size_t>(c) * per_cell + a])];
    return out;
}

/// Integrates every kept cell again over its moulded shape (nodes moved by def.rest_offsets), on the
/// same points, cells, slivers and nodes as the unmoulded lattice: the moulded body is the same material
/// carried to new places. Each cell gets its own matrices.
Status remould_cells(const ModalBasisDef& def, const Lattice& lat, const PointTable& cut, double det_j,
                     const Lame& lame, CellWork& w, LatticeModel& model)
{
    const int per_cell = cell_nodes_of_order(lat.order).count;
    const std::span<const Vec3> offsets = def.rest_offsets;
    if (offsets.size() != static_cast<size_t>(model.node_count()))
        return Error{"", "/rest_offsets",
                     "expected " + std::to_string(model.node_count()) +
                         " rest offsets (one per lattice node), found " + std::to_string(offsets.size())};
    const PointTable full = make_table(lat, 1, 3, {});
    const Error inverted{"", "/rest_offsets", "the moulded shape turns a lattice cell inside out"};
    for (int c = 0; c < lat.cell_count(); ++c) {
        if (!is_good(w.state[c]))
            continue;
        const std::vector<Vec3> u = cell_offsets(model, per_cell, c, offsets);
        const bool ok =
            w.state[c] == CellState::Full
                ? element_matrices(full, {}, det_j, lame, def.density, w.k[c], w.m[c], u.data())
                : element_matrices(cut, w.rows[c], det_j, lame, def.density, w.k[c], w.m[c], u.data());
        if (!ok)
            return inverted;
    }
    Eigen::MatrixXd ke, me;
    for (int c = 0; c < lat.cell_count(); ++c) {
        if (w.state[c] != CellState::Sliver) // merged slivers keep that state; dropped ones are Empty
            continue;
        const int root = model.cell_proxy[c];
        const std::array<int, 3> a = cell_coords(lat, c), b = cell_coords(lat, root);
        const PointTable shifted =
            make_table(lat, def.lattice.cut_cell_subdivisions, 2, {a[0] - b[0], a[1] - b[1], a[2] - b[2]});
        const std::vector<Vec3> u = cell_offsets(model, per_cell, root, offsets);
        if (!element_matrices(shifted, w.rows[c], det_j, lame, def.density, ke, me, u.data()))
            return inverted;
        w.k[root] += ke;
        w.m[root] += me;
    }
    for (int n = 0; n < model.node_count(); ++n)
        model.node_positions[n] += offsets[static_cast<size_t>(n)];
    return {};
}

} // namespace

std::vector<int32_t> nearest_cells(const Lattice& lat, const std::vector<uint8_t>& is_source)
{
    std::vector<int32_t> proxy(lat.cell_count(), -1);
    std::deque<int> queue;
    for (int c = 0; c < lat.cell_count(); ++c)
        if (is_source[c]) {
            proxy[c] = c;
            queue.push_back(c);
        }
    while (!queue.empty()) {
        const int c = queue.front();
        queue.pop_front();
        const std::array<int, 3> idx = cell_coords(lat, c);
        for (int d = 0; d < 3; ++d)
            for (const int step : {-1, 1}) {
                std::array<int, 3> n = idx;
                n[d] += step;
                if (n[d] < 0 || n[d] >= lat.cells[d])
                    continue;
                const int nc = lat.cell_index(n[0], n[1], n[2]);
                if (proxy[nc] >= 0)
                    continue;
                proxy[nc] = proxy[c];
                queue.push_back(nc);
            }
    }
    return proxy;
}

Result<LatticeModel> assemble_lattice_model(const ModalBasisDef& def)
{
    Result<Bounds> bounds = shape_bounds(def.shape);
    if (!bounds)
        return bounds.error();
    LatticeModel model;
    Lattice& lat = model.lattice;
    lat.order = def.lattice.element_order;
    lat.cells = resolve_cells(def.lattice.cells, lat.order, bounds->max - bounds->min);
    // Refused before any quadrature: axes chosen beside large given ones can pass the cap together.
    const int dof_bound = lattice_dof_bound(lat.cells, lat.order);
    if (dof_bound > k_max_lattice_dofs)
        return Error{"", "/lattice/cells",
                     "the lattice would have up to " + std::to_string(dof_bound) +
                         " degrees of freedom, more than " + std::to_string(k_max_lattice_dofs)};
    if (def.mode_count != k_all_modes && def.mode_count > dof_bound - 6)
        return Error{"", "/mode_count",
                     "the lattice has at most " + std::to_string(dof_bound - 6) +
                         " elastic modes (asked for " + std::to_string(def.mode_count) +
                         "): refine it or ask for fewer modes"};
    lat.min = bounds->min;
    for (int d = 0; d < 3; ++d)
        lat.cell_size[d] = (bounds->max[d] - bounds->min[d]) / lat.cells[d];
    const PointTable cut = make_table(lat, def.lattice.cut_cell_subdivisions, 2, {});
    const double det_j = lat.cell_size.x * lat.cell_size.y * lat.cell_size.z / 8.0;
    const Lame lame = lame_from(def.young, def.poisson);

    CellWork w;
    element_matrices(make_table(lat, 1, 3, {}), {}, det_j, lame, def.density, w.full_k, w.full_m);
    classify_cells(def, lat, cut, w);
    w.k.resize(lat.cell_count());
    w.m.resize(lat.cell_count());
    for (int c = 0; c < lat.cell_count(); ++c) {
        if (w.state[c] != CellState::Cut)
            continue;
        element_matrices(cut, w.rows[c], det_j, lame, def.density, w.k[c], w.m[c]);
        if (under_resolved(w.k[c])) {
            w.state[c] = CellState::Sliver;
            w.k[c].resize(0, 0);
            w.m[c].resize(0, 0);
        }
    }
    std::vector<uint8_t> good(lat.cell_count());
    for (int c = 0; c < lat.cell_count(); ++c)
        good[c] = is_good(w.state[c]);
    model.cell_proxy = nearest_cells(lat, good);
    if (model.cell_proxy.empty() || model.cell_proxy[0] < 0)
        return Error{"", "/shape", "no cell of the lattice holds enough of the shape to integrate"};
    aggregate_slivers(def, lat, model.cell_proxy, det_j, lame, w, model);
    number_nodes(lat, w, model);
    if (!def.rest_offsets.empty())
        if (const Status s = remould_cells(def, lat, cut, det_j, lame, w, model); !s)
            return s.error();
    scatter(lat, w, model);
    return model;
}

Eigen::MatrixXd rigid_body_vectors(const LatticeModel& model)
{
    const Lattice& lat = model.lattice;
    const Vec3 center = lat.min + 0.5 * hadamard(lat.cell_size, Vec3{1.0 * lat.cells[0], 1.0 * lat.cells[1],
                                                                     1.0 * lat.cells[2]});
    Eigen::MatrixXd r = Eigen::MatrixXd::Zero(model.dof_count(), 6);
    for (int a = 0; a < model.node_count(); ++a) {
        const Vec3 p = model.node_positions[a] - center;
        for (int d = 0; d < 3; ++d) {
            r(3 * a + d, d) = 1.0;
            const Vec3 axis{d == 0 ? 1.0 : 0.0, d == 1 ? 1.0 : 0.0, d == 2 ? 1.0 : 0.0};
            const Vec3 u = cross(axis, p); // rotation about `axis` through the centre
            for (int e = 0; e < 3; ++e)
                r(3 * a + e, 3 + d) = u[e];
        }
    }
    return r;
}

} // namespace supermodal::modal
