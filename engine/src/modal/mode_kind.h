// SPDX-License-Identifier: MIT
// A guess at each mode's kind (bend / torsion / axial / other) from its displacement field.
#pragma once

#include "modal/assembly.h"

#include <vector>

namespace supermodal::modal
{

/// Classifies mode shapes (columns of `modes`, 3n rows) about the lattice's longest axis. The nodes are
/// cut into cross-sections (nodes sharing a node-grid index along that axis); in each section the
/// sideways motion is fitted, mass-weighted (diagonal of M), by a translation plus a rotation about the
/// axis. Bend = the translations carry most (> 1/2) of the mode's Σ m|u|², Torsion = the rotations do,
/// Axial = motion along the axis does, Other = none does. A body without a long axis (longest side
/// under 1.5 × the next) gets Other throughout.
[[nodiscard]] std::vector<ModeKind> classify_modes(const LatticeModel& model, const Eigen::MatrixXd& modes);

} // namespace supermodal::modal
