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
    Eigen::VectorXd eigenvalues;               ///< (r) ω² ascending [rad²/s²]; r ≥ the modes asked for.
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
    Block,   ///< Block Krylov (the default): the factor applied to 4 vectors at once. Accepted when every
             ///< run of repeated frequencies it found is narrower than its block (it finds up to 4 copies
             ///< of one eigenvalue); otherwise the Lanczos path decides.
    Lanczos, ///< Spectra's single-vector Lanczos with confirmation runs (the reference and the fallback).
};

/// Where the cut after the `mode_count`-th mode may fall.
enum class ClusterCut {
    KeepWhole, ///< A cluster of repeated frequencies (relative gap ≤ 1e-6) the cut would split is kept
               ///< whole, so more modes come back (up to k_max_modes): which members of a split cluster
               ///< a solver keeps is arbitrary, and different picks answer the same load differently.
    Exact,     ///< Exactly `mode_count` modes (a moulded basis, whose amplitudes carry over one for one).
};

/// Solves for the lowest `mode_count` elastic modes (more with ClusterCut::KeepWhole, see there).
/// `eigenvalue_scale` [rad²/s²] is E/(ρ ℓ²) for the body's largest extent ℓ: it sets the shift (−1e-3 of
/// it) and the zero-mode threshold (spectrum.h). Rigid modes are detected by count and by their gap to
/// the first elastic eigenvalue (split_rigid_modes); a seventh zero mode (a lattice that falls apart) is
/// an error.
[[nodiscard]] Result<ModeSolution> solve_modes(const LatticeModel& model, int mode_count, ModalSolver solver,
                                               double eigenvalue_scale,
                                               SparseMethod method = SparseMethod::Block,
                                               ClusterCut cut = ClusterCut::KeepWhole);

} // namespace supermodal::modal
