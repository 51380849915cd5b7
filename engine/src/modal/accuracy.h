// SPDX-License-Identifier: MIT
// How far a body's reduced (modal) solution is from the full lattice it was cut from: the residual of
// the full equations of motion on the reduced solution and the static energy the dropped modes would
// carry (docs/modal.md, "Accuracy report").
#pragma once

#include "modal/assembly.h"
#include "supermodal/modal.h"

#include <Eigen/SparseCholesky>
#include <memory>
#include <mutex>
#include <span>
#include <string>
#include <vector>

namespace supermodal::modal
{

struct AccuracyModel;

/// Columns of the full lattice's static flexibility with inertia relief, K⁺_e e_j (3n each) [m/N], each
/// solved the first time a load reaches dof j and kept. A point load reaches the 60 dofs of its cell and a
/// resting contact the same few hundred substep after substep, so a static answer is then a sum of those
/// columns instead of a sparse solve (10–30× cheaper on 1335–4386 dofs). Thread-safe; the columns do not
/// depend on which thread made them or when.
class StaticColumns
{
  public:
    /// The columns of `dofs` (ascending), made where missing; valid while the model lives.
    void get(const AccuracyModel& model, std::span<const int> dofs, std::vector<const double*>& out);

  private:
    std::mutex m_mutex;
    std::vector<std::unique_ptr<const std::vector<double>>> m_columns; ///< (3n) null until made.
};

/// The full lattice of a basis with what the report needs factored once.
struct AccuracyModel {
    SparseMatrix stiffness, mass; ///< K [N/m], M [kg] (3n × 3n).
    Eigen::MatrixXd rigid;        ///< (3n × 6) rigid motions, M-orthonormal: Ψᵀ M Ψ = I.
    Eigen::SimplicialLDLT<SparseMatrix> mass_solver;   ///< M⁻¹ for the norms.
    Eigen::SimplicialLDLT<SparseMatrix> pinned_solver; ///< K with six pinned dofs (static solves).
    std::array<int, 6> pinned{};                       ///< The pinned dofs.
    mutable StaticColumns columns;                     ///< For static_correction, made on use.
};

/// Assembles the lattice of `def` (the def the basis was built from) and factors M and the pinned K.
/// Errors: the lattice does not match the basis, or a factorisation fails.
[[nodiscard]] Result<std::unique_ptr<AccuracyModel>> build_accuracy_model(const ModalBasisDef& def,
                                                                          const ModalBasis& basis);

/// A basis's AccuracyModel, built on first use and shared (ModalSurface::accuracy). Thread-safe.
struct AccuracyCache {
    ModalBasisDef def; ///< The def its basis was built from.
    /// The model, or null when it cannot be built (why: in `error`).
    const AccuracyModel* get(const ModalBasis& basis);
    std::string error;

  private:
    std::mutex m_mutex;
    bool m_tried = false;
    std::unique_ptr<AccuracyModel> m_model;
};

/// One body's reduced state and the loads of its last substep, body frame.
struct AccuracyInput {
    std::span<const double> nodal_force;         ///< (3n) F [N], the loads lumped on the lattice nodes.
    std::span<const double> modal_force;         ///< (r) Q [N/√kg] the modes were driven with.
    std::span<const double> q, q_dot, q_plastic; ///< (r) each.
    std::span<const double> omega;               ///< (r) [rad/s].
};

/// The residual R = M ü + C u̇ + K u − F of the full lattice on u = Φ(q − q_p), u̇ = Φ q̇,
/// ü = Φ q̈ + Ψ Ψᵀ F (q̈ from the modal equation, plus the lattice's rigid acceleration, which the rigid
/// body carries; C = M Φ 2ζΩ Φᵀ M the modal damping), and the truncated static energy.
[[nodiscard]] ModalAccuracy evaluate_accuracy(const AccuracyModel& model, const ModalBasis& basis,
                                              const AccuracyInput& in);

/// The static correction (mode acceleration) of nodal loads F (3n) [N], body frame: the full lattice's
/// static response to F's elastic part (inertia relief: F − M Ψ Ψᵀ F, with no rigid motion) minus the part
/// the first `shown` modes carry, Φ Ω⁻² Φᵀ F. What the dropped modes would do if they answered F at once:
/// it adds to the modal displacement, nodal, into `out` (3n) [m]. Costs a sum of one stored column per
/// loaded dof (StaticColumns; a solve with the pinned K for each dof loaded for the first time).
void static_correction(const AccuracyModel& model, const ModalBasis& basis,
                       std::span<const double> nodal_force, std::span<const double> omega, size_t shown,
                       std::span<double> out);

/// A nodal field stored flat (3 × nodes: x, y, z per node), e.g. a static correction, at a point with
/// precomputed weights.
[[nodiscard]] Vec3 interpolate_flat(const LatticeWeights& weights, std::span<const double> nodal);

} // namespace supermodal::modal
