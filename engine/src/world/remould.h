// SPDX-License-Identifier: MIT
// Remoulding: when plastic flow has moved a body's rest shape far enough, its modes are rebuilt for the
// moulded shape on a thread of their own and swapped in at a step boundary fixed when the rebuild was
// asked for, the amplitudes carried over by least squares (docs/modal.md "Remoulding").
#pragma once

#include "world/world_impl.h"

namespace supermodal
{

/// At the end of a step, on the stepping thread: swaps in the rebuilds due at this step count (waiting for
/// them if they are not done), then asks for rebuilds where the rest shape has moved past the threshold.
void remould_modal_bodies(World::Impl& w);
/// After restore: gives each body the model its restored rest offsets name (built now, or found in the
/// world's basis cache) and asks again for a rebuild that was pending when the snapshot was taken.
void restore_remould(World::Impl& w);
/// The largest rest offset of a lattice node since the last build over the lattice's largest side [-].
[[nodiscard]] double rest_shape_change(const ModalBody& b);

} // namespace supermodal
