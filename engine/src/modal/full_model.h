// SPDX-License-Identifier: MIT
// The full model of a modal body's lattice, for measuring the modal path against (
// docs/modal.md "Full model and the modal trade"): every degree of freedom, integrated implicitly.
//
// Integrator: Newmark average acceleration (γ = 1/2, β = 1/4). It is unconditionally stable, second
// order and adds no numerical damping (its only error is a period elongation ≈ (ωh)²/12), so the
// physical damping is not swamped as it would be by backward Euler (numerical ζ ≈ ωh/2). The step
// matrix K_eff = K + (γ/βh) C + (1/βh²) M is factored once per h (sparse LDLᵀ).
//
// Damping: Rayleigh, C = a M + b K, fitted to a ratio ζ at two frequencies (the modal path's constant
// ζ per mode cannot be written as a sparse C). Mode k of the lattice then has ζ_k = a/2ω_k + b ω_k/2
// (rayleigh_zeta), which the modal path can be given to solve exactly the same damped model.
//
// Free body: the rigid-body part of each load is removed, f_e = f − M Ψ Ψᵀ f (Ψ the M-orthonormal
// rigid motions), as the modal path does implicitly (Φᵀ M Ψ = 0); the rigid body carries the rest.
#pragma once

#include "supermodal/modal.h"

#include <memory>
#include <span>
#include <vector>

namespace supermodal::modal
{

/// C = mass_factor·M + stiffness_factor·K.
struct RayleighDamping {
    double mass_factor = 0.0;      ///< a [1/s].
    double stiffness_factor = 0.0; ///< b [s].
};
/// The Rayleigh damping with ratio zeta [-] at ω_low and ω_high [rad/s] (both > 0; equal: mass and
/// stiffness parts share the ratio). Non-finite or non-positive inputs give no damping.
[[nodiscard]] RayleighDamping fit_rayleigh(double zeta, double omega_low, double omega_high);
/// The damping ratio a Rayleigh damping gives a mode of frequency ω > 0 [rad/s].
[[nodiscard]] double rayleigh_zeta(const RayleighDamping& d, double omega);

/// A point load [N] at a rest point [m] of the shape frame.
struct PointLoad {
    Vec3 point{};
    Vec3 force{};
};

/// The full lattice of a ModalBasisDef with its Newmark state (displacement, velocity, acceleration of
/// every node, shape frame, starting at rest). Eigen stays behind the implementation (the test and
/// benchmark targets do not see it).
class FullModel
{
  public:
    /// Assembles the lattice of def (mode_count is ignored) and factors M. Errors: the lattice cannot
    /// be built, or a factorisation fails.
    [[nodiscard]] static Result<std::unique_ptr<FullModel>> build(const ModalBasisDef& def,
                                                                  const RayleighDamping& damping);

    /// Advances by h [s] (> 0, finite) with the loads held constant over the step. A new h refactors
    /// K_eff. Errors: a bad h, a non-finite load, or a factorisation that fails.
    [[nodiscard]] Status step(double h, std::span<const PointLoad> loads);

    /// Displacement [m] of a rest point [m] (shape frame), through the lattice's shape functions.
    [[nodiscard]] Vec3 displacement(const Vec3& point) const;

    /// The direct static solution of K u = f_e (rigid part of the loads removed, result M-orthogonal to
    /// the rigid motions): what the damped motion under constant loads settles to.
    [[nodiscard]] std::vector<double> static_solution(std::span<const PointLoad> loads) const;

    /// (3n) nodal displacements [m], dof 3·node + axis.
    [[nodiscard]] std::span<const double> nodal_displacement() const;
    [[nodiscard]] int dof_count() const;
    /// Nonzeros of K_eff's factor (0 before the first step): what one step's solve costs.
    [[nodiscard]] long factor_nonzeros() const;
    /// Back to rest (the factorisation is kept).
    void reset();

    FullModel(const FullModel&) = delete;
    FullModel& operator=(const FullModel&) = delete;
    ~FullModel();

  private:
    struct Impl;
    explicit FullModel(std::unique_ptr<Impl> impl);
    std::unique_ptr<Impl> m;
};

} // namespace supermodal::modal
