// SPDX-License-Identifier: MIT
// Reading of the "constraints" array of a scene file (format v1, docs/scene_format.md).
#pragma once

#include "scene/json_reader.h"
#include "supermodal/scene.h"

namespace supermodal::scene_io
{

/// Reads root["constraints"] into out_scene.constraints; expects out_scene.bodies read already, so
/// body names are checked here (with a did-you-mean). An absent "constraints" is no constraints.
void read_constraints(Reader& reader, const Json& root, Scene& out_scene);

} // namespace supermodal::scene_io
