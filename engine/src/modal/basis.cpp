// SPDX-License-Identifier: MIT
// The public modal API: defs, build_modal_basis, the deformation field and the basis cache.
#include "modal/assembly.h"
#include "modal/eigen_solve.h"
#include "modal/lattice.h"
#include "modal/mode_kind.h"
#include "supermodal/modal.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <numbers>
#include <string>

namespace supermodal
{
namespace
{

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start)
{
    return std::chrono::duration<double>(Clock::now() - start).count();
}

Error field_error(const char* where, const char* what)
{
    return Error{"", where, what};
}

/// Copies the solution into the public layout (node·3 + axis)·r + k and fills the checks.
void store_modes(const modal::LatticeModel& model, const modal::ModeSolution& sol, ModalBasis& b)
{
    const int r = b.mode_count;
    b.frequencies_hz.resize(r);
    for (int k = 0; k < r; ++k)
        b.frequencies_hz[k] = std::sqrt(std::max(sol.eigenvalues[k], 0.0)) / (2.0 * std::numbers::pi);
    b.mode_shapes.resize(static_cast<size_t>(model.dof_count()) * r);
    for (int k = 0; k < r; ++k) {
        // A mode's sign is arbitrary: fix it (largest entry positive) so that both solvers, and every
        // platform, hand out the same basis.
        Eigen::Index largest = 0;
        sol.vectors.col(k).cwiseAbs().maxCoeff(&largest);
        const double sign = sol.vectors(largest, k) < 0.0 ? -1.0 : 1.0;
        for (int row = 0; row < model.dof_count(); ++row)
            b.mode_shapes[static_cast<size_t>(row) * r + k] = sign * sol.vectors(row, k);
    }
    const Eigen::MatrixXd gram = sol.vectors.transpose() * (model.mass * sol.vectors);
    b.diagnostics.mass_orthonormality_error = (gram - Eigen::MatrixXd::Identity(r, r)).cwiseAbs().maxCoeff();
    // A rigid translation along x has M-norm² = total mass; every axis gives the same.
    b.mass = Eigen::VectorXd(model.mass * Eigen::VectorXd::Ones(model.dof_count())).sum() / 3.0;
}

/// The eigen solve's scale E/(ρ·L²) [1/s²], L the lattice's largest extent: keeps its numbers near 1.
double eigen_scale(const ModalBasisDef& def, const modal::Lattice& lat)
{
    double extent = 0.0;
    for (int d = 0; d < 3; ++d)
        extent = std::max(extent, lat.cells[d] * lat.cell_size[d]);
    return def.young / (def.density * extent * extent);
}

/// The solve's checks and the lattice's counts (not the timings).
void fill_diagnostics(const modal::LatticeModel& model, const modal::ModeSolution& sol, int mode_count,
                      ModalDiagnostics& d)
{
    d.rigid_eigenvalues = sol.rigid_eigenvalues;
    d.first_elastic_eigenvalue = sol.eigenvalues[0];
    for (const double l : sol.rigid_eigenvalues)
        d.rigid_ratio = std::max(d.rigid_ratio, std::abs(l) / d.first_elastic_eigenvalue);
    const double last = sol.eigenvalues[mode_count - 1];
    d.splits_degenerate_cluster =
        sol.next_eigenvalue > 0.0 && sol.next_eigenvalue - last <= 1e-6 * std::abs(last);
    d.sparse_solver = sol.sparse;
    d.solver_rounds = sol.rounds;
    d.inertia_checked = sol.inertia_checked;
    d.dof_count = model.dof_count();
    d.kept_cell_count = model.kept_cell_count;
    d.cut_cell_count = model.cut_cell_count;
    d.aggregated_cell_count = model.aggregated_cell_count;
    d.dropped_sliver_count = model.dropped_sliver_count;
    // Per-mode residual of the eigenproblem on the full lattice: how well each kept pair solves it.
    d.mode_residuals.resize(static_cast<size_t>(mode_count));
    for (int k = 0; k < mode_count; ++k) {
        const Eigen::VectorXd k_phi = model.stiffness * sol.vectors.col(k);
        const Eigen::VectorXd m_phi = model.mass * sol.vectors.col(k);
        const double scale = k_phi.norm();
        d.mode_residuals[k] = scale > 0.0 ? (k_phi - sol.eigenvalues[k] * m_phi).norm() / scale : 0.0;
    }
}

} // namespace

ModalBasisDef default_modal_basis_def()
{
    return {};
}

Status validate(const ModalBasisDef& def)
{
    if (const Status s = validate(def.shape); !s)
        return s;
    if (def.shape.type == ShapeType::Plane)
        return field_error("/shape/type", "expected a superquadric or hyperquadric, found a plane");
    if (!(std::isfinite(def.density) && def.density > 0.0))
        return field_error("/density", "expected a finite density > 0 [kg/m³]");
    if (!(std::isfinite(def.young) && def.young > 0.0))
        return field_error("/young", "expected a finite Young's modulus > 0 [Pa]");
    if (!(def.poisson > -1.0 && def.poisson < 0.5))
        return field_error("/poisson", "expected a Poisson's ratio in (-1, 0.5)");
    for (const int n : def.lattice.cells)
        if (n < 0 || n > k_max_lattice_cells)
            return field_error("/lattice/cells", "expected cell counts in [0, 128] (0 = automatic)");
    if (def.lattice.element_order != 1 && def.lattice.element_order != 2)
        return field_error("/lattice/element_order", "expected 1 (8-node) or 2 (20-node)");
    // Automatic axes get at least one cell: what is given must fit on its own.
    const std::array<int, 3>& c = def.lattice.cells;
    if (modal::lattice_dof_bound({std::max(c[0], 1), std::max(c[1], 1), std::max(c[2], 1)},
                                 def.lattice.element_order) > k_max_lattice_dofs)
        return Error{"", "/lattice/cells",
                     "expected a lattice of at most " + std::to_string(k_max_lattice_dofs) +
                         " degrees of freedom (3 per corner and edge-midpoint node over its box)"};
    if (def.lattice.cut_cell_subdivisions < 1 || def.lattice.cut_cell_subdivisions > 16)
        return field_error("/lattice/cut_cell_subdivisions", "expected an integer in [1, 16]");
    if (def.mode_count != k_all_modes && (def.mode_count < 1 || def.mode_count > k_max_modes))
        return field_error("/mode_count", "expected a mode count in [1, 256], or 0 for every mode");
    if (def.solver != ModalSolver::Auto && def.solver != ModalSolver::Dense &&
        def.solver != ModalSolver::Sparse)
        return field_error("/solver", "expected auto, dense or sparse");
    for (const Vec3& u : def.rest_offsets)
        if (!is_finite(u))
            return field_error("/rest_offsets", "expected finite rest offsets [m]");
    return {};
}

const char* mode_kind_name(ModeKind kind)
{
    switch (kind) {
    case ModeKind::Bend:
        return "bend";
    case ModeKind::Torsion:
        return "torsion";
    case ModeKind::Axial:
        return "axial";
    case ModeKind::Other:
        break;
    }
    return "other";
}

int lattice_nodes_per_cell(int element_order)
{
    return element_order == 1 ? 8 : 20;
}

Result<ModalBasis> build_modal_basis(const ModalBasisDef& def)
{
    if (const Status s = validate(def); !s)
        return s.error();
    const Clock::time_point start = Clock::now();
    Result<modal::LatticeModel> model = modal::assemble_lattice_model(def);
    if (!model)
        return model.error();
    const double assembly_seconds = seconds_since(start);

    const Clock::time_point solve_start = Clock::now();
    const modal::Lattice& lat = model->lattice;
    // Every mode: the whole lattice, which only the dense solver delivers.
    const bool all = def.mode_count == k_all_modes;
    const int dofs = model->dof_count();
    if (all && dofs > k_max_full_dofs)
        return Error{"", "/lattice",
                     "a full body's lattice has " + std::to_string(dofs) + " degrees of freedom, more than " +
                         std::to_string(k_max_full_dofs) + " (dense solve): coarsen the lattice"};
    const int mode_count = all ? dofs - 6 : def.mode_count;
    // A moulded basis replaces the unmoulded one amplitude for amplitude: the same count, exactly.
    const modal::ClusterCut cut =
        def.rest_offsets.empty() ? modal::ClusterCut::KeepWhole : modal::ClusterCut::Exact;
    Result<modal::ModeSolution> sol =
        modal::solve_modes(*model, mode_count, all ? ModalSolver::Dense : def.solver, eigen_scale(def, lat),
                           modal::SparseMethod::Block, cut);
    if (!sol)
        return sol.error();

    ModalBasis b;
    b.cells = lat.cells;
    b.element_order = lat.order;
    b.lattice_min = lat.min;
    b.cell_size = lat.cell_size;
    b.node_positions = model->node_positions;
    b.cell_nodes = model->cell_nodes;
    b.cell_proxy = model->cell_proxy;
    b.density = def.density;
    b.young = def.young;
    b.poisson = def.poisson;
    b.mode_count = static_cast<int>(sol->eigenvalues.size()); // more than asked: a cluster kept whole
    store_modes(*model, *sol, b);
    b.kinds = modal::classify_modes(*model, sol->vectors);
    fill_diagnostics(*model, *sol, b.mode_count, b.diagnostics);
    b.diagnostics.assembly_seconds = assembly_seconds;
    b.diagnostics.eigen_seconds = seconds_since(solve_start);
    return b;
}

LatticeWeights modal_weights(const ModalBasis& basis, const Vec3& point_shape)
{
    LatticeWeights w;
    const modal::Lattice lat = modal::lattice_of(basis);
    std::array<double, 3> xi{};
    const int proxy = modal::locate_field(basis, lat, point_shape, xi);
    if (proxy < 0)
        return w;
    const int per_cell = lattice_nodes_per_cell(lat.order);
    modal::shape_functions(lat.order, xi, w.weights.data(), nullptr);
    for (int a = 0; a < per_cell; ++a)
        w.nodes[a] = basis.cell_nodes[static_cast<size_t>(proxy) * per_cell + a];
    w.count = per_cell;
    return w;
}

namespace
{
// Σ_k φ_k(node) q_k over the first `used` modes: the displacement of one lattice node.
Vec3 node_displacement(const ModalBasis& basis, size_t node, std::span<const double> q, int used)
{
    const int r = basis.mode_count;
    const double* phi = &basis.mode_shapes[node * 3 * static_cast<size_t>(r)];
    Vec3 u{};
    for (int d = 0; d < 3; ++d) {
        double s = 0.0;
        for (int k = 0; k < used; ++k)
            s += phi[d * r + k] * q[k];
        u[d] = s;
    }
    return u;
}

int used_modes(const ModalBasis& basis, std::span<const double> q)
{
    return std::min(basis.mode_count, static_cast<int>(q.size()));
}
} // namespace

Vec3 modal_displacement(const ModalBasis& basis, const LatticeWeights& weights, std::span<const double> q)
{
    const int used = used_modes(basis, q);
    Vec3 u{};
    for (int a = 0; a < weights.count; ++a)
        u += weights.weights[a] * node_displacement(basis, static_cast<size_t>(weights.nodes[a]), q, used);
    return u;
}

void modal_nodal_displacements(const ModalBasis& basis, std::span<const double> q, std::vector<Vec3>& out)
{
    const int used = used_modes(basis, q);
    out.resize(basis.node_positions.size());
    for (size_t node = 0; node < out.size(); ++node)
        out[node] = node_displacement(basis, node, q, used);
}

Vec3 interpolate_nodal(const LatticeWeights& weights, std::span<const Vec3> nodal)
{
    Vec3 u{};
    for (int a = 0; a < weights.count; ++a)
        u += weights.weights[a] * nodal[static_cast<size_t>(weights.nodes[a])];
    return u;
}

Vec3 modal_displacement(const ModalBasis& basis, const Vec3& point_shape, std::span<const double> q)
{
    return modal_displacement(basis, modal_weights(basis, point_shape), q);
}

namespace
{
template <class T> void append_bytes(std::string& key, const T& value)
{
    char bytes[sizeof(T)];
    std::memcpy(bytes, &value, sizeof(T));
    key.append(bytes, sizeof(T));
}

/// Every field the build reads, byte for byte.
std::string cache_key(const ModalBasisDef& def)
{
    std::string key;
    const ShapeDef& s = def.shape;
    append_bytes(key, s.type);
    for (const double v : {s.radii.x, s.radii.y, s.radii.z, s.epsilon1, s.epsilon2, s.taper.kx, s.taper.ky,
                           s.bend.curvature, s.bend.angle, def.density, def.young, def.poisson})
        append_bytes(key, v);
    for (const HyperquadricTerm& t : s.terms)
        for (const double v : {t.normal.x, t.normal.y, t.normal.z, t.offset, t.exponent})
            append_bytes(key, v);
    for (const int v : {def.lattice.cells[0], def.lattice.cells[1], def.lattice.cells[2],
                        def.lattice.element_order, def.lattice.cut_cell_subdivisions, def.mode_count,
                        static_cast<int>(def.solver), static_cast<int>(s.terms.size())})
        append_bytes(key, v);
    for (const Vec3& u : def.rest_offsets)
        for (const double v : {u.x, u.y, u.z})
            append_bytes(key, v);
    return key;
}
} // namespace

Result<std::shared_ptr<const ModalBasis>> ModalBasisCache::get_or_build(const ModalBasisDef& def)
{
    const std::string key = cache_key(def);
    {
        const std::lock_guard<std::mutex> lock(m_mutex);
        if (const auto it = m_entries.find(key); it != m_entries.end())
            return it->second;
    }
    Result<ModalBasis> built = build_modal_basis(def); // outside the lock: builds take long
    if (!built)
        return built.error();
    auto basis = std::make_shared<const ModalBasis>(std::move(*built));
    const std::lock_guard<std::mutex> lock(m_mutex);
    return m_entries.emplace(key, std::move(basis)).first->second; // an earlier racer's result wins
}

int ModalBasisCache::size() const
{
    const std::lock_guard<std::mutex> lock(m_mutex);
    return static_cast<int>(m_entries.size());
}

void ModalBasisCache::clear()
{
    const std::lock_guard<std::mutex> lock(m_mutex);
    m_entries.clear();
}

} // namespace supermodal
