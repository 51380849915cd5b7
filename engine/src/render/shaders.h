// SPDX-License-Identifier: MIT
// The GLSL ES 3.00 programs a frame uses: sky gradient, lit bodies, ground grid, blob shadows, the
// ground's depth and the body layer's composite. Internal.
#pragma once

#include "supermodal/result.h"

#include <GLES3/gl3.h>

namespace supermodal::render
{

/// Compiled programs and their uniform locations.
struct Programs {
    GLuint sky = 0, body = 0, grid = 0, shadow = 0, depth = 0, layer = 0;
    // sky
    GLint sky_top = -1, sky_bottom = -1;
    // body
    GLint model = -1, view_proj = -1, color = -1, eye = -1, key_dir = -1, fill_dir = -1, flat = -1;
    // grid
    GLint grid_view_proj = -1, grid_eye = -1, grid_axes = -1, grid_origin = -1, grid_inv_spacing = -1,
          grid_fade = -1, grid_sky_top = -1, grid_sky_bottom = -1, grid_sky_row = -1;
    // shadow
    GLint shadow_view_proj = -1;
    // ground depth, body layer
    GLint depth_view_proj = -1, layer_texture = -1, layer_origin = -1;
};

/// Compiles and links them all; errors carry the compiler's log.
Status compile_programs(Programs& out);
void delete_programs(Programs& programs);

} // namespace supermodal::render
