// SPDX-License-Identifier: MIT
// A fill-reducing elimination order for a lattice's stiffness: nested dissection by the lattice's own
// geometry (planes through cell faces), which needs no graph partitioner.
#pragma once

#include "modal/assembly.h"

#include <vector>

namespace supermodal::modal
{

/// The lattice's dofs in elimination order (entry k: the dof eliminated k-th). The nodes are split by
/// a plane of cell faces across the longest extent, the two halves ordered first (recursively) and
/// the plane's nodes last: no cell reaches across a face plane, so the halves do not couple and their
/// factors stay apart. A node's three dofs stay together.
[[nodiscard]] std::vector<int> lattice_dissection(const LatticeModel& model);

} // namespace supermodal::modal
