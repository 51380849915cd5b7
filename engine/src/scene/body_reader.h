// SPDX-License-Identifier: MIT
// Reading of the "bodies" array of a scene file (format v1, docs/scene_format.md).
#pragma once

#include "scene/json_reader.h"
#include "supermodal/scene.h"

namespace supermodal::scene_io
{

/// Reads root["bodies"] into out_scene.bodies, resolving each body's material and density; expects
/// out_scene.materials to be read already. Errors go to `reader`; an absent "bodies" is no bodies.
void read_bodies(Reader& reader, const Json& root, Scene& out_scene);

} // namespace supermodal::scene_io
