// SPDX-License-Identifier: MIT
// The generalized eigenproblem K φ = ω² M φ of a free lattice: the six rigid modes found and dropped,
// the lowest elastic modes kept, mass-normalised.
#pragma once

#include "modal/assembly.h"

#include <array>

namespace supermodal::modal
{

/// Lowest elastic modes of a lattice model.
struct ModeSolution {
    Eigen::VectorXd eigenvalues;               ///< (r) ω² ascending [rad²/s²].
    Eigen::MatrixXd vectors;                   ///< (3n × r) mass-normalised: Φᵀ M Φ = I.
    std::array<double, 6> rigid_eigenvalues{}; ///< ω² of the rigid modes before dropping [rad²/s²].
    double next_eigenvalue = 0.0;              ///< ω²_(r+1) when it was computed, else 0.
    bool sparse = false;
    bool block = false; ///< Sparse: the block iteration delivered (not the Lanczos fallback).
    int rounds = 0;
    bool inertia_checked = false;
};

/// How the sparse path iterates with its one Cholesky factor of K − σM.
enum class SparseMethod {
    Block,   ///< Block Krylov: the factor applied to a block of vectors at once. Not the default: with
             ///< no confirmation run it can miss members of a cluster of repeated frequencies as wide
             ///< as its block (a sphere's five-fold modes), which made a soft sphere ring at rest.
    Lanczos, ///< Spectra's single-vector Lanczos with confirmation runs (the default, the reference).
};

/// Solves for the lowest `mode_count` elastic modes. `eigenvalue_scale` [rad²/s²] is E/(ρ ℓ²) for the
/// body's largest extent ℓ: it sets the shift (−1e-3 of it) and the zero-mode threshold (spectrum.h).
/// Rigid modes are detected by count and by their gap to the first elastic eigenvalue
/// (split_rigid_modes); a seventh zero mode (a lattice that falls apart) is an error.
[[nodiscard]] Result<ModeSolution> solve_modes(const LatticeModel& model, int mode_count, ModalSolver solver,
                                               double eigenvalue_scale,
                                               SparseMethod method = SparseMethod::Lanczos);

} // namespace supermodal::modal
