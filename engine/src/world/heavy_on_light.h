// SPDX-License-Identifier: MIT
// Heavy on light: the soft rows of a heavy body resting on a light one, scaled so that Gauss–Seidel
// converges on them like an equal-mass pair.
#pragma once

#include "core/parallel.h"
#include "world/contact_solve.h"

namespace supermodal
{

/// Scales the lower body's inverse mass and inertia in the rows of each pair whose upper body (farther
/// from the ground in the contact graph) is much heavier and rests on it (see heavy_on_light.cpp).
void scale_heavy_on_light(const Parallel& par, SoftContacts& rows);

} // namespace supermodal
