// SPDX-License-Identifier: MIT
// Adaptive modes (scene "dynamics": "auto"): a modal body shows on its surface only the lowest modes its
// loads and motion need to keep the displacement it leaves out under a tolerance (docs/modal.md). The
// hidden modes still step (r multiply-adds each): they tell when to show them, with their motion so far.
#pragma once

#include "modal/modal_body.h"

#include <span>

namespace supermodal::modal
{

/// What an adaptive body should show this substep.
struct ActiveChoice {
    size_t active = 0;       ///< Lowest modes to show [-].
    double truncation = 0.0; ///< Surface displacement the other modes may reach [m] (an upper estimate).
    /// Σ over the shown modes of 2 × (k_lattice_change_safety × lattice_changes[k]) × the displacement
    /// mode k may reach [m]: what the lattice's frequency error may cost them (a mode's static response
    /// goes as 1/ω², so twice the relative frequency error); 0 without changes.
    double lattice_error = 0.0;
};

/// The active count for a body of model m in state s about to step under generalized forces `force` (r,
/// [N/√kg]). Mode k may move the surface by reach_k · max(its amplitude now, 2 |F_k| / ω_k²): twice the
/// static deflection is what a suddenly applied load overshoots to. The body gains modes when the modes left
/// out could reach more than half the tolerance, and then takes enough to leave out at most a quarter;
/// it drops modes only when those left out stay under a quarter, so the count does not chatter. Modes
/// holding a plastic offset stay active.
[[nodiscard]] ActiveChoice choose_active_modes(const ModalModel& m, const ModalState& s,
                                               std::span<const double> force);

} // namespace supermodal::modal
