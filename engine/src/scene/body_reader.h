// SPDX-License-Identifier: MIT
// Reading of the "bodies" array of a scene file (format v1, docs/scene_format.md).
#pragma once

#include "scene/json_reader.h"
#include "supermodal/scene.h"

#include <string>
#include <string_view>

namespace supermodal::scene_io
{

/// Reads root["bodies"] into out_scene.bodies, resolving each body's material and density; expects
/// out_scene.materials to be read already. Errors go to `reader`; an absent "bodies" is no bodies.
void read_bodies(Reader& reader, const Json& root, Scene& out_scene);

/// Reads a string naming a body already in out_scene.bodies; otherwise records
/// "<missing> \"name\"<note>" and a did-you-mean at `where`.
void read_body_name(Reader& reader, const Json& value, const std::string& where, const Scene& scene,
                    std::string& out_name, std::string_view missing, std::string_view note = "");

} // namespace supermodal::scene_io
