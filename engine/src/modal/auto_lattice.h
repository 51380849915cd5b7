// SPDX-License-Identifier: MIT
// The lattice of an auto body (scene "dynamics": "auto" with no "lattice"). A lattice's modes
// are stiffer than the body's (too few cells to bend freely), so its frequencies fall as it is refined;
// how much they still move from one lattice to the next twice as fine estimates what the coarser one
// leaves out. An auto body takes the default lattice, refined by doubling until its kept modes'
// frequencies move less than a target from the lattice before, within a cap on degrees of freedom.
#pragma once

#include "supermodal/modal.h"

#include <memory>
#include <vector>

namespace supermodal::modal
{

/// Relative frequency change [-] under which a lattice counts as converged: a mode's static response
/// goes as 1/ω², so 2% in frequency is about 4% of the displacement the mode shows.
inline constexpr double k_auto_lattice_target = 0.02;
/// The change from the lattice half as fine is not a bound on a lattice's own frequency error: measured
/// on a slender rounded slat (tests/modal/auto_lattice_test.cpp) the error was up to 1.8× the change,
/// because cut cells' boundary quadrature converges unevenly as the cross-section refines. Error
/// estimates take twice the change [-].
inline constexpr double k_lattice_change_safety = 2.0;
/// Most degrees of freedom an auto refinement may reach [-]: a 16×2×2 board (1503) builds in 0.07 s, a
/// 32×2×4 one (5103) in 0.36 s on this machine; past 3000 the build time would dominate a scene's start.
inline constexpr int k_auto_lattice_max_dofs = 3000;

/// What choose_lattice() settled on.
struct LatticeChoice {
    std::shared_ptr<const ModalBasis> basis;
    /// Relative change of each kept mode's frequency from the lattice half as fine [-] (r, or empty when
    /// there was no coarser lattice to compare): an upper estimate of the chosen lattice's own error.
    std::vector<double> frequency_changes;
    double frequency_change = -1.0; ///< Their largest; −1 when empty.
    bool met = false;               ///< frequency_change ≤ target.
};

/// For def with an automatic lattice (cells all 0): the default lattice (lattice.h resolve_cells), then
/// each axis doubled while the kept modes moved more than `target` from the lattice before and the next
/// stays within max_dofs. The first comparison is against the default halved along each axis (where that
/// differs and can hold the modes). Bases come from and go to `cache`.
[[nodiscard]] Result<LatticeChoice> choose_lattice(ModalBasisCache& cache, const ModalBasisDef& def,
                                                   double target = k_auto_lattice_target,
                                                   int max_dofs = k_auto_lattice_max_dofs);

/// Relative difference of each of fine's frequencies from coarse's, mode by mode [-], over the modes both
/// keep (at least the r asked for: a basis keeps a cluster of repeated frequencies whole).
[[nodiscard]] std::vector<double> frequency_changes(const ModalBasis& fine, const ModalBasis& coarse);

} // namespace supermodal::modal
