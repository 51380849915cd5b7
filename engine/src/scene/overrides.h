// SPDX-License-Identifier: MIT
// SceneOverride (supermodal/scene.h): values put into the scene's JSON DOM at a JSON pointer before the
// readers run, so an override is validated exactly like a value written in the file.
#pragma once

#include "scene/json_text.h"
#include "supermodal/result.h"
#include "supermodal/scene.h"

#include <span>
#include <string>

namespace supermodal::scene_io
{

/// Applies the overrides to `root` in order. The first one that cannot be applied (a malformed pointer,
/// a missing parent or array element, value text that is not JSON) is the error: file `source`, where
/// its pointer. `root` may then be partly changed; the caller drops it.
[[nodiscard]] Status apply_overrides(Json& root, std::span<const SceneOverride> overrides,
                                     const std::string& source);

} // namespace supermodal::scene_io
