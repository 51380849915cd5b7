// SPDX-License-Identifier: MIT
// Rigid/elastic split of a free body's spectrum (see spectrum.h).
#include "modal/spectrum.h"

#include <algorithm>
#include <cmath>

namespace supermodal::modal
{

RigidSplit split_rigid_modes(std::span<const double> ascending, double eigenvalue_scale)
{
    RigidSplit out;
    if (ascending.size() < 7) {
        out.problem = "fewer than seven eigenvalues: cannot tell rigid from elastic modes";
        return out;
    }
    // Absolute test first: relative tests cannot see a seventh zero mode next to six others.
    const double first = ascending[6];
    if (!(first > k_zero_fraction * eigenvalue_scale)) {
        out.problem = "more than six zero-frequency modes: the material falls apart into pieces or "
                      "hinges on this lattice (refine it)";
        return out;
    }
    double rigid_max = 0.0;
    for (size_t i = 0; i < 6; ++i)
        rigid_max = std::max(rigid_max, std::abs(ascending[i]));
    out.rigid_ratio = rigid_max / first;
    if (!(out.rigid_ratio <= k_rigid_gap)) {
        out.problem = "the six rigid modes do not separate from the elastic ones";
        return out;
    }
    out.ok = true;
    return out;
}

} // namespace supermodal::modal
