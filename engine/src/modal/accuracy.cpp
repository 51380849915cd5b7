// SPDX-License-Identifier: MIT
#include "modal/accuracy.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

namespace supermodal::modal
{
namespace
{

using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

Eigen::Map<const RowMajor> modes_of(const ModalBasis& basis)
{
    return {basis.mode_shapes.data(), static_cast<Eigen::Index>(basis.node_positions.size() * 3),
            basis.mode_count};
}

Eigen::Map<const Eigen::VectorXd> vec(std::span<const double> v)
{
    return {v.data(), static_cast<Eigen::Index>(v.size())};
}

/// √(xᵀ M⁻¹ x): the kinetic-energy norm of the acceleration M⁻¹x a force x gives the lattice.
double inverse_mass_norm(const AccuracyModel& m, const Eigen::VectorXd& x)
{
    const Eigen::VectorXd a = m.mass_solver.solve(x);
    return std::sqrt(std::max(x.dot(a), 0.0));
}

/// K⁺ F_e: the full lattice's static response to the elastic part of F (F_e = F − M Ψ Ψᵀ F, inertia
/// relief), solved with six pinned dofs, the rigid motion the pins chose dropped.
Eigen::VectorXd static_response(const AccuracyModel& m, const Eigen::VectorXd& f)
{
    Eigen::VectorXd rhs = f - m.mass * (m.rigid * (m.rigid.transpose() * f));
    for (const int p : m.pinned)
        rhs[p] = 0.0;
    Eigen::VectorXd full = m.pinned_solver.solve(rhs);
    full -= m.rigid * (m.rigid.transpose() * (m.mass * full));
    return full;
}

/// Ω⁻² Φᵀ F over the first `shown` modes (the rest zero): the kept modes' static amplitudes [√kg·m].
Eigen::VectorXd kept_static(const Eigen::Map<const RowMajor>& phi, const Eigen::VectorXd& f,
                            std::span<const double> omega, size_t shown)
{
    Eigen::VectorXd q = phi.transpose() * f;
    for (Eigen::Index k = 0; k < q.size(); ++k) {
        const double w2 = omega[static_cast<size_t>(k)] * omega[static_cast<size_t>(k)];
        q[k] = static_cast<size_t>(k) < shown && w2 > 0.0 ? q[k] / w2 : 0.0;
    }
    return q;
}

} // namespace

Result<std::unique_ptr<AccuracyModel>> build_accuracy_model(const ModalBasisDef& def, const ModalBasis& basis)
{
    Result<LatticeModel> lattice = assemble_lattice_model(def);
    if (!lattice)
        return lattice.error();
    if (lattice->node_positions != basis.node_positions)
        return Error{"", "modal", "the lattice does not match the basis it should check"};
    auto m = std::make_unique<AccuracyModel>();
    m->stiffness = std::move(lattice->stiffness);
    m->mass = std::move(lattice->mass);
    // Rigid motions, M-orthonormalised (Cholesky of the 6 × 6 Gram matrix).
    const Eigen::MatrixXd raw = rigid_body_vectors(*lattice);
    const Eigen::MatrixXd gram = raw.transpose() * (m->mass * raw);
    const Eigen::LLT<Eigen::MatrixXd> llt(gram);
    if (llt.info() != Eigen::Success)
        return Error{"", "modal", "the lattice's rigid motions are degenerate"};
    m->rigid = llt.matrixU().solve<Eigen::OnTheRight>(raw);
    m->mass_solver.compute(m->mass);
    if (m->mass_solver.info() != Eigen::Success)
        return Error{"", "modal", "cannot factor the lattice's mass matrix"};
    // Six dofs that pin every rigid motion: the pivots of a column-pivoted QR of Ψᵀ (the dofs where the
    // six motions are most independent). K u = F_e then has a solution with no reaction at the pins
    // whenever F_e is self-equilibrated (Ψᵀ F_e = 0): the reactions would be self-equilibrated forces on
    // six dofs that pin every rigid motion, hence zero.
    const Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(m->rigid.transpose());
    std::vector<char> is_pinned(static_cast<size_t>(m->stiffness.rows()), 0);
    for (int i = 0; i < 6; ++i) {
        m->pinned[i] = static_cast<int>(qr.colsPermutation().indices()[i]);
        is_pinned[m->pinned[i]] = 1;
    }
    const double diag = m->stiffness.diagonal().cwiseAbs().maxCoeff();
    std::vector<Eigen::Triplet<double>> triplets;
    triplets.reserve(static_cast<size_t>(m->stiffness.nonZeros()));
    for (int col = 0; col < m->stiffness.outerSize(); ++col)
        for (SparseMatrix::InnerIterator it(m->stiffness, col); it; ++it)
            if (!is_pinned[it.row()] && !is_pinned[it.col()])
                triplets.emplace_back(static_cast<int>(it.row()), static_cast<int>(it.col()), it.value());
    for (const int p : m->pinned)
        triplets.emplace_back(p, p, diag);
    SparseMatrix pinned(m->stiffness.rows(), m->stiffness.cols());
    pinned.setFromTriplets(triplets.begin(), triplets.end());
    m->pinned_solver.compute(pinned);
    if (m->pinned_solver.info() != Eigen::Success)
        return Error{"", "modal", "cannot factor the pinned lattice stiffness"};
    return m;
}

const AccuracyModel* AccuracyCache::get(const ModalBasis& basis)
{
    const std::lock_guard<std::mutex> lock(m_mutex);
    if (!m_tried) {
        m_tried = true;
        Result<std::unique_ptr<AccuracyModel>> built = build_accuracy_model(def, basis);
        if (built)
            m_model = std::move(*built);
        else
            error = built.error().message();
    }
    return m_model.get();
}

ModalAccuracy evaluate_accuracy(const AccuracyModel& m, const ModalBasis& basis, const AccuracyInput& in)
{
    ModalAccuracy out;
    const int r = basis.mode_count;
    const Eigen::Index n = m.stiffness.rows();
    if (static_cast<Eigen::Index>(in.nodal_force.size()) != n || static_cast<int>(in.q.size()) != r ||
        static_cast<int>(in.modal_force.size()) != r || static_cast<int>(in.q_dot.size()) != r ||
        static_cast<int>(in.q_plastic.size()) != r || static_cast<int>(in.omega.size()) != r)
        return out;
    const auto phi = modes_of(basis);
    const Eigen::VectorXd f = vec(in.nodal_force);
    Eigen::VectorXd elastic(r), accel_plus_damping(r), omega2(r);
    for (int k = 0; k < r; ++k) {
        omega2[k] = in.omega[k] * in.omega[k];
        elastic[k] = in.q[k] - in.q_plastic[k];
        // q̈ + 2ζω q̇ = Q − ω² q_e: the modal equation, damping force included (C u̇ = M Φ 2ζΩ q̇).
        accel_plus_damping[k] = in.modal_force[k] - omega2[k] * elastic[k];
    }
    const Eigen::VectorXd u = phi * elastic;
    const Eigen::VectorXd rigid_load = m.rigid.transpose() * f; // Ψᵀ F: the rigid accelerations
    const Eigen::VectorXd ku = m.stiffness * u;
    const Eigen::VectorXd residual = m.mass * (phi * accel_plus_damping + m.rigid * rigid_load) + ku - f;
    out.residual_norm = inverse_mass_norm(m, residual);
    out.load_norm = f.norm();
    const double scale = std::max(inverse_mass_norm(m, f), inverse_mass_norm(m, ku));
    out.residual = scale > 0.0 ? out.residual_norm / scale : 0.0;

    // Static response of the full lattice to the elastic part of F (inertia relief) against the part of
    // it the kept modes carry, Φ Ω⁻² Φᵀ F; the difference is what the dropped modes would carry.
    const Eigen::VectorXd full = static_response(m, f);
    const Eigen::VectorXd difference = full - phi * kept_static(phi, f, in.omega, static_cast<size_t>(r));
    out.static_energy = 0.5 * full.dot(m.stiffness * full);
    out.truncated_energy = 0.5 * difference.dot(m.stiffness * difference);
    out.truncated_fraction = out.static_energy > 0.0 ? out.truncated_energy / out.static_energy : 0.0;
    return out;
}

void StaticColumns::get(const AccuracyModel& m, std::span<const int> dofs, std::vector<const double*>& out)
{
    const Eigen::Index n = m.stiffness.rows();
    const std::lock_guard<std::mutex> lock(m_mutex);
    m_columns.resize(static_cast<size_t>(n));
    out.clear();
    for (const int j : dofs) {
        std::unique_ptr<const std::vector<double>>& column = m_columns[static_cast<size_t>(j)];
        if (column == nullptr) {
            const Eigen::VectorXd answer = static_response(m, Eigen::VectorXd::Unit(n, j));
            column = std::make_unique<const std::vector<double>>(answer.data(), answer.data() + n);
        }
        out.push_back(column->data());
    }
}

void static_correction(const AccuracyModel& m, const ModalBasis& basis, std::span<const double> nodal_force,
                       std::span<const double> omega, size_t shown, std::span<double> out)
{
    const size_t n = static_cast<size_t>(m.stiffness.rows());
    const size_t r = static_cast<size_t>(basis.mode_count);
    if (nodal_force.size() != n || out.size() != n || omega.size() != r)
        return;
    std::vector<int> loaded;
    for (size_t j = 0; j < n; ++j)
        if (nodal_force[j] != 0.0)
            loaded.push_back(static_cast<int>(j));
    std::vector<const double*> columns;
    m.columns.get(m, loaded, columns);
    // K⁺_e F = Σ_j F_j K⁺_e e_j over the loaded dofs, in dof order; then less Φ Ω⁻² Φᵀ F of the shown modes.
    std::fill(out.begin(), out.end(), 0.0);
    std::vector<double> kept(std::min(shown, r), 0.0);
    for (size_t c = 0; c < loaded.size(); ++c) {
        const size_t j = static_cast<size_t>(loaded[c]);
        const double f = nodal_force[j];
        const double* column = columns[c];
        for (size_t i = 0; i < n; ++i)
            out[i] += f * column[i];
        const double* phi = &basis.mode_shapes[j * r];
        for (size_t k = 0; k < kept.size(); ++k)
            kept[k] += phi[k] * f;
    }
    for (size_t k = 0; k < kept.size(); ++k)
        kept[k] = omega[k] > 0.0 ? kept[k] / (omega[k] * omega[k]) : 0.0;
    for (size_t i = 0; i < n; ++i) {
        const double* phi = &basis.mode_shapes[i * r];
        double u = 0.0;
        for (size_t k = 0; k < kept.size(); ++k)
            u += phi[k] * kept[k];
        out[i] -= u;
    }
}

Vec3 interpolate_flat(const LatticeWeights& weights, std::span<const double> nodal)
{
    Vec3 out{};
    for (int j = 0; j < weights.count; ++j) {
        const double* x = &nodal[static_cast<size_t>(weights.nodes[j]) * 3];
        out += weights.weights[j] * Vec3{x[0], x[1], x[2]};
    }
    return out;
}

} // namespace supermodal::modal
