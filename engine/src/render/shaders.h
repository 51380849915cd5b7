// SPDX-License-Identifier: MIT
// The three GLSL ES 3.00 programs a frame uses: sky gradient, lit bodies, ground grid. Internal.
#pragma once

#include "supermodal/result.h"

#include <GLES3/gl3.h>

namespace supermodal::render
{

/// Compiled programs and their uniform locations.
struct Programs {
    GLuint sky = 0, body = 0, grid = 0;
    // sky
    GLint sky_top = -1, sky_bottom = -1;
    // body
    GLint model = -1, view_proj = -1, color = -1, eye = -1, key_dir = -1, fill_dir = -1, flat = -1;
    // grid
    GLint grid_view_proj = -1, grid_eye = -1, grid_axes = -1, grid_origin = -1, grid_spacing = -1,
          grid_fade = -1, grid_fog = -1, grid_blobs = -1, grid_blob_strength = -1, grid_blob_count = -1;
};
/// Largest number of bodies that cast a blob shadow on a grid (uniform array size).
inline constexpr int k_max_blobs = 64;

/// Compiles and links all three; errors carry the compiler's log.
Status compile_programs(Programs& out);
void delete_programs(Programs& programs);

} // namespace supermodal::render
