// SPDX-License-Identifier: MIT
#include "modal/full_model.h"

#include "modal/assembly.h"

#include <Eigen/Dense>
#include <Eigen/SparseCholesky>
#include <cmath>
#include <vector>

namespace supermodal::modal
{
namespace
{

// Newmark average acceleration.
constexpr double k_gamma = 0.5, k_beta = 0.25;

Error fail(const char* message)
{
    return Error{"", "modal", message};
}

} // namespace

struct FullModel::Impl {
    ModalBasis lattice; ///< Only the lattice fields: the point → node weights (modal_weights).
    SparseMatrix k, m, c;
    Eigen::MatrixXd rigid;      ///< Ψ (n × 6), Ψᵀ M Ψ = I.
    Eigen::MatrixXd mass_rigid; ///< M Ψ (n × 6).
    Eigen::SimplicialLDLT<SparseMatrix> mass_solver, step_solver, static_solver;
    std::array<int, 6> pinned{};
    double h = 0.0;
    long factor_nonzeros = 0;
    Eigen::VectorXd u, v, a, load, new_load, rhs, work;

    /// Nodal loads with the rigid part removed; false for a non-finite load.
    [[nodiscard]] bool gather_loads(std::span<const PointLoad> loads, Eigen::VectorXd& out) const;
    [[nodiscard]] bool factor(double step);
};

FullModel::FullModel(std::unique_ptr<Impl> impl) : m(std::move(impl)) {}
FullModel::~FullModel() = default;
std::span<const double> FullModel::nodal_displacement() const
{
    return {m->u.data(), static_cast<size_t>(m->u.size())};
}
int FullModel::dof_count() const
{
    return static_cast<int>(m->u.size());
}
long FullModel::factor_nonzeros() const
{
    return m->factor_nonzeros;
}

RayleighDamping fit_rayleigh(double zeta, double omega_low, double omega_high)
{
    RayleighDamping d;
    if (!(std::isfinite(zeta) && zeta > 0.0 && std::isfinite(omega_low) && omega_low > 0.0 &&
          std::isfinite(omega_high) && omega_high > 0.0))
        return d;
    // ζ(ω) = a/2ω + bω/2 equal to zeta at both frequencies.
    const double sum = omega_low + omega_high;
    d.mass_factor = 2.0 * zeta * omega_low * omega_high / sum;
    d.stiffness_factor = 2.0 * zeta / sum;
    return d;
}

double rayleigh_zeta(const RayleighDamping& d, double omega)
{
    return omega > 0.0 ? d.mass_factor / (2.0 * omega) + d.stiffness_factor * omega / 2.0 : 0.0;
}

Result<std::unique_ptr<FullModel>> FullModel::build(const ModalBasisDef& def, const RayleighDamping& damping)
{
    if (!(std::isfinite(damping.mass_factor) && std::isfinite(damping.stiffness_factor) &&
          damping.mass_factor >= 0.0 && damping.stiffness_factor >= 0.0))
        return fail("full model: Rayleigh factors must be finite and ≥ 0");
    if (Status valid = validate(def); !valid.ok())
        return valid.error();
    Result<LatticeModel> lattice = assemble_lattice_model(def);
    if (!lattice)
        return lattice.error();
    auto m = std::make_unique<Impl>();
    ModalBasis& shell = m->lattice;
    shell.cells = lattice->lattice.cells;
    shell.element_order = lattice->lattice.order;
    shell.lattice_min = lattice->lattice.min;
    shell.cell_size = lattice->lattice.cell_size;
    shell.node_positions = lattice->node_positions;
    shell.cell_nodes = lattice->cell_nodes;
    shell.cell_proxy = lattice->cell_proxy;

    const Eigen::MatrixXd raw = rigid_body_vectors(*lattice);
    m->k = std::move(lattice->stiffness);
    m->m = std::move(lattice->mass);
    m->c = damping.mass_factor * m->m + damping.stiffness_factor * m->k;
    // Rigid motions, M-orthonormalised through the Cholesky factor of their Gram matrix.
    const Eigen::LLT<Eigen::MatrixXd> llt(raw.transpose() * (m->m * raw));
    if (llt.info() != Eigen::Success)
        return fail("full model: the lattice's rigid motions are degenerate");
    m->rigid = llt.matrixU().solve<Eigen::OnTheRight>(raw);
    m->mass_rigid = m->m * m->rigid;
    m->mass_solver.compute(m->m);
    if (m->mass_solver.info() != Eigen::Success)
        return fail("full model: cannot factor the lattice's mass matrix");

    // Static solves: pin six dofs that hold every rigid motion (column-pivoted QR of Ψᵀ picks the most
    // independent ones). For a self-equilibrated load the pins carry no reaction.
    const Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(m->rigid.transpose());
    const Eigen::Index n = m->k.rows();
    std::vector<char> pinned(static_cast<size_t>(n), 0);
    for (int i = 0; i < 6; ++i) {
        m->pinned[i] = static_cast<int>(qr.colsPermutation().indices()[i]);
        pinned[static_cast<size_t>(m->pinned[i])] = 1;
    }
    const double diag = m->k.diagonal().cwiseAbs().maxCoeff();
    std::vector<Eigen::Triplet<double>> triplets;
    for (int col = 0; col < m->k.outerSize(); ++col)
        for (SparseMatrix::InnerIterator it(m->k, col); it; ++it)
            if (!pinned[static_cast<size_t>(it.row())] && !pinned[static_cast<size_t>(it.col())])
                triplets.emplace_back(static_cast<int>(it.row()), static_cast<int>(it.col()), it.value());
    for (const int p : m->pinned)
        triplets.emplace_back(p, p, diag);
    SparseMatrix k_pinned(n, n);
    k_pinned.setFromTriplets(triplets.begin(), triplets.end());
    m->static_solver.compute(k_pinned);
    if (m->static_solver.info() != Eigen::Success)
        return fail("full model: cannot factor the pinned stiffness");
    std::unique_ptr<FullModel> model(new FullModel(std::move(m)));
    model->reset();
    return model;
}

void FullModel::reset()
{
    const Eigen::Index n = m->k.rows();
    for (Eigen::VectorXd* x : {&m->u, &m->v, &m->a, &m->load, &m->new_load, &m->rhs, &m->work})
        x->setZero(n);
}

bool FullModel::Impl::gather_loads(std::span<const PointLoad> loads, Eigen::VectorXd& out) const
{
    out.setZero();
    for (const PointLoad& p : loads) {
        if (!(std::isfinite(p.point.x) && std::isfinite(p.point.y) && std::isfinite(p.point.z) &&
              std::isfinite(p.force.x) && std::isfinite(p.force.y) && std::isfinite(p.force.z)))
            return false;
        const LatticeWeights w = modal_weights(lattice, p.point);
        for (int i = 0; i < w.count; ++i) {
            const Eigen::Index dof = 3 * static_cast<Eigen::Index>(w.nodes[i]);
            out[dof] += w.weights[i] * p.force.x;
            out[dof + 1] += w.weights[i] * p.force.y;
            out[dof + 2] += w.weights[i] * p.force.z;
        }
    }
    // f_e = f − M Ψ (Ψᵀ f): the rigid body takes the rest.
    out -= mass_rigid * (rigid.transpose() * out);
    return true;
}

bool FullModel::Impl::factor(double step)
{
    const SparseMatrix k_eff = k + (k_gamma / (k_beta * step)) * c + (1.0 / (k_beta * step * step)) * m;
    step_solver.compute(k_eff);
    if (step_solver.info() != Eigen::Success)
        return false;
    h = step;
    factor_nonzeros = step_solver.matrixL().nestedExpression().nonZeros();
    return true;
}

Status FullModel::step(double h, std::span<const PointLoad> loads)
{
    Impl& s = *m;
    if (!(std::isfinite(h) && h > 0.0))
        return fail("full model: the step must be finite and > 0");
    if (h != s.h && !s.factor(h))
        return fail("full model: cannot factor K_eff");
    if (!s.gather_loads(loads, s.new_load))
        return fail("full model: a load is not finite");
    // A load that changes at the step boundary changes the acceleration there: a₀⁺ = a₀⁻ + M⁻¹ Δf, so
    // the trapezoidal rule integrates the load as held over the step (as the modal path does).
    s.work = s.new_load - s.load;
    if (s.work.squaredNorm() > 0.0) {
        s.a += s.mass_solver.solve(s.work);
        s.load = s.new_load;
    }
    // K_eff u₁ = f + M (u/βh² + v/βh + (1/2β − 1) a) + C (γ/βh u + (γ/β − 1) v + h (γ/2β − 1) a).
    const double c0 = 1.0 / (k_beta * h * h), c1 = 1.0 / (k_beta * h), c2 = 1.0 / (2.0 * k_beta) - 1.0;
    const double d0 = k_gamma / (k_beta * h), d1 = k_gamma / k_beta - 1.0,
                 d2 = h * (k_gamma / (2.0 * k_beta) - 1.0);
    s.work = c0 * s.u + c1 * s.v + c2 * s.a;
    s.rhs = s.load + s.m * s.work;
    s.work = d0 * s.u + d1 * s.v + d2 * s.a;
    s.rhs += s.c * s.work;
    s.work = s.step_solver.solve(s.rhs); // u₁
    // a₁ = (u₁ − u)/βh² − v/βh − (1/2β − 1) a;  v₁ = v + h ((1 − γ) a + γ a₁).
    s.rhs = c0 * (s.work - s.u) - c1 * s.v - c2 * s.a; // a₁
    s.v += h * ((1.0 - k_gamma) * s.a + k_gamma * s.rhs);
    s.a.swap(s.rhs);
    s.u.swap(s.work);
    if (!s.u.allFinite())
        return fail("full model: the state is not finite");
    return {};
}

Vec3 FullModel::displacement(const Vec3& point) const
{
    const LatticeWeights w = modal_weights(m->lattice, point);
    Vec3 out{};
    for (int i = 0; i < w.count; ++i) {
        const Eigen::Index dof = 3 * static_cast<Eigen::Index>(w.nodes[i]);
        out.x += w.weights[i] * m->u[dof];
        out.y += w.weights[i] * m->u[dof + 1];
        out.z += w.weights[i] * m->u[dof + 2];
    }
    return out;
}

std::vector<double> FullModel::static_solution(std::span<const PointLoad> loads) const
{
    const Eigen::Index n = m->k.rows();
    Eigen::VectorXd f(n);
    if (!m->gather_loads(loads, f))
        return std::vector<double>(static_cast<size_t>(n), 0.0);
    for (const int p : m->pinned)
        f[p] = 0.0;
    Eigen::VectorXd u = m->static_solver.solve(f);
    u -= m->rigid * (m->mass_rigid.transpose() * u); // drop the rigid motion the pins chose
    return {u.data(), u.data() + n};
}

} // namespace supermodal::modal
