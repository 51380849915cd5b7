// SPDX-License-Identifier: MIT
// Golden-image specs (tests/golden/<name>.json) and rendering one: see docs/rendering.md.
#pragma once

#include "supermodal/render.h"

#include <string>
#include <vector>

namespace supermodal::golden
{

/// One golden image: what to render and how close a new render must stay to the reference PNG.
struct Spec {
    std::string name;        ///< File stem: tests/golden/<name>.json and <name>.png.
    std::string scene;       ///< Scene path, relative to the repository root.
    bool has_camera = false; ///< True: `camera` replaces the scene's camera.
    CameraDef camera;        ///< Same fields as a scene's "camera".
    int width = 320, height = 240;
    long long steps = 0; ///< Fixed steps run before the frame.
    double deformation_scale = 1.0;
    int tolerance = 16;         ///< Per-channel difference [0, 255] still counted as equal.
    double max_fraction = 0.01; ///< Largest fraction of differing pixels that passes [-].
};

/// Every tests/golden/*.json, sorted by name.
[[nodiscard]] std::vector<std::string> spec_names();
[[nodiscard]] Result<Spec> load_spec(const std::string& name);
/// Loads the scene, steps it and renders the frame (with an optional deliberate fault).
[[nodiscard]] Result<Image> render_spec(const Spec& spec, RenderFault fault = RenderFault::None);

} // namespace supermodal::golden
