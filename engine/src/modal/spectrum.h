// SPDX-License-Identifier: MIT
// Telling the rigid modes of a free body from its elastic ones, given its lowest eigenvalues.
#pragma once

#include <span>
#include <string>

namespace supermodal::modal
{

/// ω² below this fraction of E/(ρℓ²) counts as zero (a zero-energy mode) [-].
inline constexpr double k_zero_fraction = 1e-8;
/// The six rigid ω² must lie below this fraction of the first elastic one [-].
inline constexpr double k_rigid_gap = 1e-4;

/// The verdict on a spectrum's lowest end.
struct RigidSplit {
    bool ok = false;
    std::string problem;      ///< Why not, when !ok.
    double rigid_ratio = 0.0; ///< max |ω²_rigid| / ω²_first elastic [-].
};

/// Checks that exactly six of the ascending eigenvalues ω² [rad²/s²] are rigid: the seventh must be
/// above k_zero_fraction · eigenvalue_scale (else a seventh zero mode: the material falls apart or has
/// a hinge), and the first six below k_rigid_gap times the seventh (else they do not separate).
/// eigenvalue_scale is E/(ρℓ²) for the body's largest extent ℓ [rad²/s²].
[[nodiscard]] RigidSplit split_rigid_modes(std::span<const double> ascending, double eigenvalue_scale);

} // namespace supermodal::modal
