// SPDX-License-Identifier: MIT
#include "render/shaders.h"

#include <string>

namespace supermodal::render
{
namespace
{

// Triangles given in NDC at the far plane (the viewport less the ground grid); vertical gradient.
const char* k_sky_vs = R"(#version 300 es
layout(location = 0) in vec2 a_ndc;
out float v_t;
void main() {
    v_t = a_ndc.y * 0.5 + 0.5;
    gl_Position = vec4(a_ndc, 1.0, 1.0);
})";
const char* k_sky_fs = R"(#version 300 es
precision highp float;
in float v_t;
uniform vec3 u_top, u_bottom;
out vec4 o_color;
void main() { o_color = vec4(mix(u_bottom, u_top, clamp(v_t, 0.0, 1.0)), 1.0); })";

// Bodies: vertices in the shape frame, u_model = world_from_shape (rotation + translation only, so its
// upper 3x3 also turns normals).
const char* k_body_vs = R"(#version 300 es
layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal;
uniform mat4 u_model, u_view_proj;
out vec3 v_world, v_normal;
void main() {
    vec4 w = u_model * vec4(a_position, 1.0);
    v_world = w.xyz;
    v_normal = mat3(u_model) * a_normal;
    gl_Position = u_view_proj * w;
})";
// Key + fill directional lights, hemisphere ambient, a little Blinn-Phong; lit in linear space with
// gamma 2 (square in, square root out) instead of 2.2: pow() costs llvmpipe more than the difference
// shows (the highlight's power of 40 is five squarings and a product for the same reason).
const char* k_body_fs = R"(#version 300 es
precision highp float;
in vec3 v_world, v_normal;
uniform vec3 u_color, u_eye, u_key_dir, u_fill_dir;
uniform int u_flat;
out vec4 o_color;
void main() {
    vec3 base = u_color * u_color;
    if (u_flat != 0) { o_color = vec4(u_color, 1.0); return; }
    vec3 n = normalize(v_normal);
    vec3 v = normalize(u_eye - v_world);
    float key = max(dot(n, u_key_dir), 0.0);
    float fill = max(dot(n, u_fill_dir), 0.0);
    vec3 ambient = mix(vec3(0.30, 0.27, 0.24), vec3(0.55, 0.62, 0.75), 0.5 + 0.5 * n.y);
    vec3 h = normalize(u_key_dir + v);
    float s2 = max(dot(n, h), 0.0);
    s2 *= s2;
    float s8 = s2 * s2;
    s8 *= s8;
    float s32 = s8 * s8;
    s32 *= s32;
    float spec = s32 * s8 * 0.18 * step(0.0, dot(n, u_key_dir)); // (n.h)^40
    float edge = 1.0 - max(dot(n, v), 0.0);
    float rim = edge * edge * edge * 0.08;
    vec3 lit = base * (0.45 * ambient + 0.85 * key * vec3(1.0, 0.97, 0.92) + 0.25 * fill) + spec + rim;
    o_color = vec4(sqrt(lit), 1.0);
})";

// Ground grid on a plane, in the plane's (u, v) measured in minor spacings: u_axes = the plane's two
// in-plane unit axes (columns 0, 1); minor lines every unit, major every ten; far away it fades into
// the sky's colour at the same height on screen, so that where the grid ends no edge is left (the sky
// and the ground are drawn at one sample even under MSAA: an edge there would show its steps). It
// covers half the picture at one sample per pixel, so the fragment shader keeps to multiplies: (u, v)
// and the offset from the eye come interpolated, one reciprocal serves both line widths, and the sky's
// height comes from the window row.
const char* k_grid_vs = R"(#version 300 es
layout(location = 0) in vec3 a_position;
uniform mat4 u_view_proj;
uniform vec3 u_eye, u_origin;
uniform mat3 u_axes;
uniform float u_inv_spacing;
out vec2 v_uv;
out vec3 v_from_eye;
void main() {
    vec3 r = a_position - u_origin;
    v_uv = vec2(dot(r, u_axes[0]), dot(r, u_axes[1])) * u_inv_spacing;
    v_from_eye = a_position - u_eye;
    gl_Position = u_view_proj * vec4(a_position, 1.0);
})";
const char* k_grid_fs = R"(#version 300 es
precision highp float;
in vec2 v_uv;
in vec3 v_from_eye;
uniform vec3 u_sky_top, u_sky_bottom;
uniform vec2 u_fade, u_sky_row;
out vec4 o_color;
void main() {
    vec2 per_pixel = 1.0 / max(fwidth(v_uv), vec2(1e-6));
    vec2 minor = abs(fract(v_uv - 0.5) - 0.5) * per_pixel;
    vec2 major = abs(fract(v_uv * 0.1 - 0.5) - 0.5) * (10.0 * per_pixel);
    vec3 c = vec3(0.80, 0.80, 0.78);
    c = mix(c, vec3(0.62, 0.62, 0.60), (1.0 - min(min(minor.x, minor.y), 1.0)) * 0.6);
    c = mix(c, vec3(0.45, 0.45, 0.44), (1.0 - min(min(major.x, major.y), 1.0)) * 0.8);
    float t = clamp(length(v_from_eye) * u_fade.x + u_fade.y, 0.0, 1.0);
    float fade = t * t * (3.0 - 2.0 * t);
    vec3 sky = mix(u_sky_bottom, u_sky_top, clamp(gl_FragCoord.y * u_sky_row.x + u_sky_row.y, 0.0, 1.0));
    o_color = vec4(mix(c, sky, fade), 1.0);
})";

// Blob shadows: one quad per body on the plane, multiplied into the grid (blend DST_COLOR, ZERO);
// a_shadow = (u, v) in [−1, 1] across the quad and the darkening at its centre. One quad per body
// costs its own area instead of every grid pixel looping over every body.
const char* k_shadow_vs = R"(#version 300 es
layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_shadow;
uniform mat4 u_view_proj;
out vec3 v_shadow;
void main() { v_shadow = a_shadow; gl_Position = u_view_proj * vec4(a_position, 1.0); })";
const char* k_shadow_fs = R"(#version 300 es
precision highp float;
in vec3 v_shadow;
out vec4 o_color;
void main() {
    float falloff = 1.0 - smoothstep(0.2, 1.0, length(v_shadow.xy));
    o_color = vec4(vec3(1.0 - v_shadow.z * falloff), 1.0);
})";

// The ground's depth alone, so that bodies under the ground stay hidden in the multisampled body layer.
const char* k_depth_vs = R"(#version 300 es
layout(location = 0) in vec3 a_position;
uniform mat4 u_view_proj;
void main() { gl_Position = u_view_proj * vec4(a_position, 1.0); })";
const char* k_depth_fs = R"(#version 300 es
void main() {})";

// The resolved body layer over the image, pixel for pixel (the layer holds the image's pixels from
// u_layer_origin on): its colours are premultiplied by coverage (cleared to transparent), so blending
// ONE, ONE_MINUS_SRC_ALPHA lays the edges over what is behind.
const char* k_layer_vs = R"(#version 300 es
layout(location = 0) in vec2 a_ndc;
void main() { gl_Position = vec4(a_ndc, 0.0, 1.0); })";
const char* k_layer_fs = R"(#version 300 es
precision highp float;
uniform highp sampler2D u_layer;
uniform ivec2 u_layer_origin;
out vec4 o_color;
void main() { o_color = texelFetch(u_layer, ivec2(gl_FragCoord.xy) - u_layer_origin, 0); })";

Status compile(GLenum type, const char* source, GLuint& out)
{
    out = glCreateShader(type);
    glShaderSource(out, 1, &source, nullptr);
    glCompileShader(out);
    GLint ok = 0;
    glGetShaderiv(out, GL_COMPILE_STATUS, &ok);
    if (ok)
        return {};
    char log[2048] = {};
    glGetShaderInfoLog(out, sizeof log, nullptr, log);
    return Error{"", "render", std::string("shader compile failed: ") + log};
}

Status link(const char* vs, const char* fs, GLuint& out)
{
    GLuint v = 0, f = 0;
    Status sv = compile(GL_VERTEX_SHADER, vs, v);
    Status sf = sv ? compile(GL_FRAGMENT_SHADER, fs, f) : Status{};
    if (!sv || !sf) {
        glDeleteShader(v);
        glDeleteShader(f);
        return !sv ? sv : sf;
    }
    out = glCreateProgram();
    glAttachShader(out, v);
    glAttachShader(out, f);
    glLinkProgram(out);
    glDeleteShader(v);
    glDeleteShader(f);
    GLint ok = 0;
    glGetProgramiv(out, GL_LINK_STATUS, &ok);
    if (ok)
        return {};
    char log[2048] = {};
    glGetProgramInfoLog(out, sizeof log, nullptr, log);
    return Error{"", "render", std::string("shader link failed: ") + log};
}

} // namespace

Status compile_programs(Programs& p)
{
    if (Status s = link(k_sky_vs, k_sky_fs, p.sky); !s)
        return s;
    if (Status s = link(k_body_vs, k_body_fs, p.body); !s)
        return s;
    if (Status s = link(k_grid_vs, k_grid_fs, p.grid); !s)
        return s;
    if (Status s = link(k_shadow_vs, k_shadow_fs, p.shadow); !s)
        return s;
    if (Status s = link(k_depth_vs, k_depth_fs, p.depth); !s)
        return s;
    if (Status s = link(k_layer_vs, k_layer_fs, p.layer); !s)
        return s;
    p.depth_view_proj = glGetUniformLocation(p.depth, "u_view_proj");
    p.layer_texture = glGetUniformLocation(p.layer, "u_layer");
    p.layer_origin = glGetUniformLocation(p.layer, "u_layer_origin");
    p.shadow_view_proj = glGetUniformLocation(p.shadow, "u_view_proj");
    p.sky_top = glGetUniformLocation(p.sky, "u_top");
    p.sky_bottom = glGetUniformLocation(p.sky, "u_bottom");
    p.model = glGetUniformLocation(p.body, "u_model");
    p.view_proj = glGetUniformLocation(p.body, "u_view_proj");
    p.color = glGetUniformLocation(p.body, "u_color");
    p.eye = glGetUniformLocation(p.body, "u_eye");
    p.key_dir = glGetUniformLocation(p.body, "u_key_dir");
    p.fill_dir = glGetUniformLocation(p.body, "u_fill_dir");
    p.flat = glGetUniformLocation(p.body, "u_flat");
    p.grid_view_proj = glGetUniformLocation(p.grid, "u_view_proj");
    p.grid_eye = glGetUniformLocation(p.grid, "u_eye");
    p.grid_axes = glGetUniformLocation(p.grid, "u_axes");
    p.grid_origin = glGetUniformLocation(p.grid, "u_origin");
    p.grid_inv_spacing = glGetUniformLocation(p.grid, "u_inv_spacing");
    p.grid_sky_row = glGetUniformLocation(p.grid, "u_sky_row");
    p.grid_fade = glGetUniformLocation(p.grid, "u_fade");
    p.grid_sky_top = glGetUniformLocation(p.grid, "u_sky_top");
    p.grid_sky_bottom = glGetUniformLocation(p.grid, "u_sky_bottom");
    return {};
}

void delete_programs(Programs& p)
{
    for (GLuint prog : {p.sky, p.body, p.grid, p.shadow, p.depth, p.layer})
        if (prog != 0)
            glDeleteProgram(prog);
    p = Programs{};
}

} // namespace supermodal::render
