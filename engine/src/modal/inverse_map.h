// SPDX-License-Identifier: MIT
// The inverse of a modal body's deformation: which rest point a deformed point came from (Newton's
// method on the deformation field), for inside-outside tests of the deformed body.
#pragma once

#include "supermodal/modal.h"

#include <span>

namespace supermodal::modal
{

struct InverseMap {
    bool converged = false;
    Vec3 rest_point{};          ///< X with X + u(X) = p [m], shape frame.
    Mat3 inverse_deformation{}; ///< F⁻¹ at X, F = I + ∇u: maps deformed-frame vectors back (F⁻ᵀ maps
                                ///< rest-frame gradients forward).
    int iterations = 0;
};
/// Solves X + u(X) = p from X₀ = p − u(p) by Newton's method (12 steps at most, tolerance 1e-10 of the
/// lattice's largest side), u the modes' field plus `nodal` (3 × nodes [m], a static correction; empty:
/// none). Not converged when F turns singular (a folded field) or the steps diverge.
[[nodiscard]] InverseMap invert_deformation(const ModalBasis& basis, std::span<const double> q, const Vec3& p,
                                            std::span<const double> nodal = {});

} // namespace supermodal::modal
