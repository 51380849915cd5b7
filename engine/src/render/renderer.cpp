// SPDX-License-Identifier: MIT
// Renderer: EGL context + framebuffer + programs + mesh cache. One sample: bodies, ground grids, then
// sky. Under MSAA: ground grids and sky at one sample, then the bodies on a multisampled layer.
#include "render/gl_context.h"
#include "render/meshes.h"
#include "render/shaders.h"
#include "render/sky_region.h"
#include "render/view.h"
#include "supermodal/body.h"
#include "supermodal/geometry.h"
#include "supermodal/modal.h"
#include "supermodal/render.h"
#include "supermodal/world.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <map>

namespace supermodal
{

RenderDef default_render_def()
{
    return RenderDef{};
}

Status validate(const RenderDef& d)
{
    const auto bad = [](const char* field, const std::string& what) { return Error{"", field, what}; };
    if (d.width < 16 || d.width > 8192 || d.height < 16 || d.height > 8192)
        return bad("width/height", "expected sizes in [16, 8192] px, found " + std::to_string(d.width) + "x" +
                                       std::to_string(d.height));
    if (d.samples < 1 || d.samples > 16)
        return bad("samples", "expected 1 to 16, found " + std::to_string(d.samples));
    if (d.tessellation < 8 || d.tessellation > 512)
        return bad("tessellation", "expected 8 to 512, found " + std::to_string(d.tessellation));
    if (!(d.gap_pixels == 0.0 || (d.gap_pixels >= 0.01 && d.gap_pixels <= 100.0)))
        return bad("gap_pixels", "expected 0 (off) or 0.01 to 100 px, found " + std::to_string(d.gap_pixels));
    if (!(std::isfinite(d.deformation_scale) && d.deformation_scale >= 0.0))
        return bad("deformation_scale", "expected a finite number >= 0");
    for (const Vec3& c : {d.sky_top, d.sky_bottom})
        if (!is_finite(c))
            return bad("sky", "expected finite colours");
    return {};
}

namespace
{

// Stable colour of the body at entity index i when the host set none: golden-angle hues, soft.
Vec3 index_color(uint32_t i)
{
    const double h = std::fmod(0.08 + 0.618033988749895 * i, 1.0) * 6.0;
    const double x = 1.0 - std::abs(std::fmod(h, 2.0) - 1.0);
    Vec3 rgb;
    switch (static_cast<int>(h)) {
    case 0:
        rgb = {1, x, 0};
        break;
    case 1:
        rgb = {x, 1, 0};
        break;
    case 2:
        rgb = {0, 1, x};
        break;
    case 3:
        rgb = {0, x, 1};
        break;
    case 4:
        rgb = {x, 0, 1};
        break;
    default:
        rgb = {1, 0, x};
        break;
    }
    return 0.35 * Vec3{1, 1, 1} + 0.5 * rgb; // pastel: lighting reads better than on pure hues
}

void set_vec3(GLint loc, const Vec3& v)
{
    glUniform3f(loc, static_cast<float>(v.x), static_cast<float>(v.y), static_cast<float>(v.z));
}

// A vertex array and its buffer, left bound, with attribute 0 of `components` floats at the start of
// each vertex of `stride` floats.
void make_vertex_array(GLuint& vao, GLuint& vbo, int components, int stride)
{
    glGenVertexArrays(1, &vao);
    glGenBuffers(1, &vbo);
    glBindVertexArray(vao);
    glBindBuffer(GL_ARRAY_BUFFER, vbo);
    glEnableVertexAttribArray(0);
    glVertexAttribPointer(0, components, GL_FLOAT, GL_FALSE, stride * static_cast<GLsizei>(sizeof(float)),
                          nullptr);
}

// One body's render-side state: which cached mesh, and a skin when it is modal.
struct BodyEntry {
    std::string key;
    const render::GpuMesh* mesh = nullptr;
    std::unique_ptr<render::ModalSkin> skin;
};

// A body as this frame draws it.
struct DrawItem {
    const BodyEntry* entry = nullptr;
    render::Mat4 model{};
    Vec3 color{};
};

// out = m · v for a column-major GL matrix.
void transform(const render::Mat4& m, const double v[4], double out[4])
{
    for (int r = 0; r < 4; ++r)
        out[r] = m[r] * v[0] + m[4 + r] * v[1] + m[8 + r] * v[2] + m[12 + r] * v[3];
}

// A rectangle of framebuffer pixels, GL's way (origin at the bottom left).
struct GlRect {
    int x = 0, y = 0, width = 0, height = 0;
};

// A view rectangle (rows counted from the top of an image `image_height` tall) GL's way.
GlRect gl_rect(const PixelRect& r, int image_height)
{
    return {r.x, image_height - r.y - r.height, r.width, r.height};
}

void set_viewport(const GlRect& r)
{
    glViewport(r.x, r.y, r.width, r.height);
}

} // namespace

struct Renderer::Impl {
    RenderDef def;
    render::GlContext context;
    render::Framebuffer framebuffer;
    render::Programs programs;
    render::MeshCache meshes;
    std::map<Entity, BodyEntry> bodies;
    std::map<Entity, Vec3> colors;
    std::map<Entity, std::shared_ptr<const TriangleMesh>> custom_meshes; ///< set_body_mesh()
    const World* last_world = nullptr;
    GLuint sky_vao = 0, sky_vbo = 0, grid_vao = 0, grid_vbo = 0, shadow_vao = 0, shadow_vbo = 0;
    std::vector<float> shadow_vertices; ///< Per vertex: position (3), quad (u, v), strength.
    std::vector<DrawItem> items;        ///< This frame's bodies.
    std::map<std::string, double> gaps; ///< tessellation_gap at one segment [m], per shape key.
    std::vector<float> background_key;  ///< What the saved background shows (MSAA only); empty: none.
    std::vector<float> drawn_key;       ///< The background last drawn and not saved.

    ~Impl()
    {
        if (context.make_current()) {
            bodies.clear(); // skins hold GL buffers: free them while the context is current
            glDeleteVertexArrays(1, &sky_vao);
            glDeleteBuffers(1, &sky_vbo);
            glDeleteVertexArrays(1, &grid_vao);
            glDeleteBuffers(1, &grid_vbo);
            glDeleteVertexArrays(1, &shadow_vao);
            glDeleteBuffers(1, &shadow_vbo);
            render::delete_programs(programs);
        }
    }

    Status init()
    {
        if (Status s = context.open(); !s)
            return s;
        if (Status s = framebuffer.create(def.width, def.height, def.samples); !s)
            return s;
        if (Status s = render::compile_programs(programs); !s)
            return s;
        make_vertex_array(sky_vao, sky_vbo, 2, 2);
        make_vertex_array(grid_vao, grid_vbo, 3, 3);
        glBufferData(GL_ARRAY_BUFFER, 4 * 3 * sizeof(float), nullptr, GL_DYNAMIC_DRAW);
        make_vertex_array(shadow_vao, shadow_vbo, 3, 6);
        glEnableVertexAttribArray(1);
        glVertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, 6 * sizeof(float),
                              reinterpret_cast<const void*>(3 * sizeof(float)));
        glBindVertexArray(0);
        if (std::string e = render::gl_errors(); !e.empty())
            return Error{"", "render", "setting up: " + e};
        return {};
    }

    // `surface` = shape_key(shape).
    BodyEntry& entry(const World& world, Entity b, const ShapeDef& shape, const std::string& surface,
                     int segments)
    {
        BodyEntry& e = bodies[b];
        auto custom = custom_meshes.find(b);
        const TriangleMesh* given = custom != custom_meshes.end() ? custom->second.get() : nullptr;
        const ModalBasis* basis = body_modal_basis(world, b);
        // A given mesh is keyed by its address (held alive by custom_meshes), a shape by its fields.
        // Rigid bodies take the spacing that gives the closest silhouette for their segments; modal ones
        // keep even triangles, which bend evenly.
        const MeshSpacing spacing = basis == nullptr ? MeshSpacing::Curvature : MeshSpacing::EqualArc;
        std::string key = given != nullptr ? "mesh@" + std::to_string(reinterpret_cast<uintptr_t>(given))
                                           : surface + "/" + std::to_string(segments) +
                                                 (spacing == MeshSpacing::Curvature ? "/curvature" : "");
        if (e.mesh == nullptr || e.key != key) { // new body, a changed shape or a given mesh
            e.mesh = given != nullptr ? &meshes.get(*given, key) : &meshes.get(shape, segments, spacing, key);
            e.key = std::move(key);
            e.skin.reset();
        }
        if (basis == nullptr)
            e.skin.reset();
        else if (!e.skin || e.skin->basis() != basis)
            e.skin = std::make_unique<render::ModalSkin>(*e.mesh, basis, body_remould(world, b).rest_offsets);
        return e;
    }

    // Drawn last at the far plane with LEQUAL: only pixels nothing else covered are shaded. Under
    // MSAA llvmpipe pays per covered sample even where the depth test fails, so the triangles leave
    // out the grid's square where there is one (sky_triangles).
    void draw_sky(const std::vector<float>& triangles)
    {
        glDepthFunc(GL_LEQUAL);
        glDepthMask(GL_FALSE);
        glUseProgram(programs.sky);
        set_vec3(programs.sky_top, def.sky_top);
        set_vec3(programs.sky_bottom, def.sky_bottom);
        glBindVertexArray(sky_vao);
        glBindBuffer(GL_ARRAY_BUFFER, sky_vbo);
        glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(triangles.size() * sizeof(float)),
                     triangles.data(), GL_STREAM_DRAW);
        glDrawArrays(GL_TRIANGLES, 0, static_cast<GLsizei>(triangles.size() / 2));
        glDepthMask(GL_TRUE);
        glDepthFunc(GL_LESS);
    }

    void clear_image();
    void draw_grid(const render::View& view, const Vec3& normal_in, double offset, const GlRect& viewport);
    void draw_ground_shadows(const std::vector<Aabb>& boxes, const render::View& view,
                             const std::vector<std::pair<Vec3, double>>& planes);
    void draw_background(const render::View& view, const std::vector<std::pair<Vec3, double>>& planes,
                         const GlRect& viewport);
    void draw_ground_depth(const render::View& view, const std::vector<std::pair<Vec3, double>>& planes);
    void draw_shadows(const std::vector<Aabb>& boxes, const render::View& view, const Vec3& n, double offset,
                      const Vec3& a0, const Vec3& a1);
    render::View begin_frame(const std::vector<Aabb>& boxes, const CameraDef& camera_in,
                             const PixelRect& rect);
    [[nodiscard]] int segments_for(const World& world, Entity b, const ShapeDef& shape,
                                   const std::string& surface, const Vec3& position, const render::View& view,
                                   int viewport_height);
    void collect_bodies(const World& world, PoseSource poses, const render::View& view, int viewport_height,
                        std::vector<std::pair<Vec3, double>>& out_planes);
    void draw_bodies() const;
    [[nodiscard]] GlRect layer_rect(const render::View& view, const GlRect& viewport) const;
    void draw_body_layer(const render::View& view, const std::vector<std::pair<Vec3, double>>& planes,
                         const GlRect& viewport);
    void composite_layer(const GlRect& r, const GlRect& viewport);
    Status render(const World& world, const CameraDef& camera, Image& out, PoseSource poses,
                  const std::function<void()>& overlay, const PixelRect& view);
};

namespace
{

// A ground plane's grid: its unit normal, in-plane axes (the world axis least along the normal, made
// perpendicular) and the corners, in order around it, of the square it is drawn on: around the
// target's foot on the plane, past where the grid has faded into the sky.
struct GridSquare {
    Vec3 n, a0, a1;
    Vec3 corners[4];
};

GridSquare grid_square(const render::View& view, const Vec3& normal, double offset)
{
    GridSquare g;
    g.n = normalized(normal);
    const Vec3 pick = std::abs(g.n.x) < 0.9 ? Vec3{1, 0, 0} : Vec3{0, 0, 1};
    g.a0 = normalized(pick - dot(pick, g.n) * g.n);
    g.a1 = cross(g.n, g.a0);
    const Vec3 foot = view.target - (dot(view.target, g.n) - offset) * g.n;
    const double half = 14.0 * view.distance;
    const double corners[4][2] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
    for (int i = 0; i < 4; ++i)
        g.corners[i] = foot + half * corners[i][0] * g.a0 + half * corners[i][1] * g.a1;
    return g;
}

// The square as a triangle strip into the grid's buffer, left bound.
void upload_square(GLuint vao, GLuint vbo, const GridSquare& g)
{
    float quad[12];
    const int strip[4] = {0, 1, 3, 2};
    for (int i = 0; i < 4; ++i)
        for (int k = 0; k < 3; ++k)
            quad[i * 3 + k] = static_cast<float>(g.corners[strip[i]][k]);
    glBindVertexArray(vao);
    glBindBuffer(GL_ARRAY_BUFFER, vbo);
    glBufferSubData(GL_ARRAY_BUFFER, 0, sizeof quad, quad);
}

// NDC triangles for the sky: the viewport less the grid's square when one plane has a grid (with
// more, their squares' union is not convex and the sky covers the viewport).
std::vector<float> sky_for(const render::View& view, const std::vector<std::pair<Vec3, double>>& grids,
                           const GlRect& viewport)
{
    std::vector<render::ClipPoint> ground;
    if (grids.size() == 1) {
        const GridSquare g = grid_square(view, grids[0].first, grids[0].second);
        const render::Mat4& m = view.view_proj;
        for (const Vec3& c : g.corners) {
            render::ClipPoint p{};
            for (size_t r = 0; r < 4; ++r)
                p[r] = m[r] * c.x + m[4 + r] * c.y + m[8 + r] * c.z + m[12 + r];
            ground.push_back(p);
        }
    }
    // One pixel into the square, so that the two edges' rounding leaves no gap.
    return render::sky_triangles(ground, 2.0 / std::min(viewport.width, viewport.height));
}

} // namespace

void Renderer::Impl::draw_grid(const render::View& view, const Vec3& normal_in, double offset,
                               const GlRect& viewport)
{
    const GridSquare g = grid_square(view, normal_in, offset);
    const Vec3 &n = g.n, &a0 = g.a0, &a1 = g.a1;
    const Vec3 origin = offset * n;
    // Minor lines at a power of ten near a tenth of the view distance; major lines every ten.
    const double spacing = std::pow(10.0, std::round(std::log10(view.distance))) / 10.0;
    const float axes[9] = {static_cast<float>(a0.x), static_cast<float>(a0.y), static_cast<float>(a0.z),
                           static_cast<float>(a1.x), static_cast<float>(a1.y), static_cast<float>(a1.z),
                           static_cast<float>(n.x),  static_cast<float>(n.y),  static_cast<float>(n.z)};
    glUseProgram(programs.grid);
    glUniformMatrix4fv(programs.grid_view_proj, 1, GL_FALSE, view.view_proj.data());
    set_vec3(programs.grid_eye, view.eye);
    set_vec3(programs.grid_origin, origin);
    glUniformMatrix3fv(programs.grid_axes, 1, GL_FALSE, axes);
    glUniform1f(programs.grid_inv_spacing, static_cast<float>(1.0 / spacing));
    // The fade runs from 2.5 to 9 view distances: t = dist * x + y.
    const double fade_span = 6.5 * view.distance;
    glUniform2f(programs.grid_fade, static_cast<float>(1.0 / fade_span), static_cast<float>(-2.5 / 6.5));
    // The sky's height, 0 at the viewport's bottom row and 1 at its top: gl_FragCoord.y * x + y.
    glUniform2f(programs.grid_sky_row, 1.0f / static_cast<float>(viewport.height),
                -static_cast<float>(viewport.y) / static_cast<float>(viewport.height));
    set_vec3(programs.grid_sky_top, def.sky_top);
    set_vec3(programs.grid_sky_bottom, def.sky_bottom);
    upload_square(grid_vao, grid_vbo, g);
    // Pulled slightly towards the eye in depth so bodies resting on the plane do not flicker into it.
    glEnable(GL_POLYGON_OFFSET_FILL);
    glPolygonOffset(1.0f, 1.0f);
    glDrawArrays(GL_TRIANGLE_STRIP, 0, 4);
    glDisable(GL_POLYGON_OFFSET_FILL);
}

// Every plane's blob shadows, over the grids already drawn.
void Renderer::Impl::draw_ground_shadows(const std::vector<Aabb>& boxes, const render::View& view,
                                         const std::vector<std::pair<Vec3, double>>& planes)
{
    glEnable(GL_POLYGON_OFFSET_FILL);
    glPolygonOffset(0.5f, 0.5f); // just in front of the grid, still behind resting bodies
    for (const auto& [normal, offset] : planes) {
        const GridSquare g = grid_square(view, normal, offset);
        draw_shadows(boxes, view, g.n, offset, g.a0, g.a1);
    }
    glDisable(GL_POLYGON_OFFSET_FILL);
}

// The ground planes' squares into the depth buffer only, pulled towards the eye as the grid is.
void Renderer::Impl::draw_ground_depth(const render::View& view,
                                       const std::vector<std::pair<Vec3, double>>& planes)
{
    glUseProgram(programs.depth);
    glUniformMatrix4fv(programs.depth_view_proj, 1, GL_FALSE, view.view_proj.data());
    glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
    glEnable(GL_POLYGON_OFFSET_FILL);
    glPolygonOffset(1.0f, 1.0f);
    for (const auto& [normal, offset] : planes) {
        upload_square(grid_vao, grid_vbo, grid_square(view, normal, offset));
        glDrawArrays(GL_TRIANGLE_STRIP, 0, 4);
    }
    glDisable(GL_POLYGON_OFFSET_FILL);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
}

void Renderer::Impl::draw_shadows(const std::vector<Aabb>& boxes, const render::View& view, const Vec3& n,
                                  double offset, const Vec3& a0, const Vec3& a1)
{
    // Each body's box centre dropped onto the plane; wider, softer and fainter the higher it is.
    shadow_vertices.clear();
    const double corners[6][2] = {{-1, -1}, {1, -1}, {1, 1}, {-1, -1}, {1, 1}, {-1, 1}};
    for (const Aabb& box : boxes) {
        const Vec3 c = 0.5 * (box.min + box.max);
        const Vec3 h = 0.5 * (box.max - box.min);
        // Extent across the plane: the box's half-size with the part along the normal removed.
        const Vec3 across = h - Vec3{std::abs(n.x) * h.x, std::abs(n.y) * h.y, std::abs(n.z) * h.z};
        const double radius = length(across) + 1e-6;
        const double height = dot(c, n) - offset;
        if (height < 0.0 || length(c - view.target) > 12.0 * view.distance)
            continue; // under the plane, or too far to see (and off the grid's square, 14 distances wide)
        const double strength = 0.5 * std::clamp(1.0 - height / (4.0 * radius + 0.2), 0.0, 1.0);
        if (strength <= 0.0)
            continue;
        const double r = 1.2 * radius + 0.5 * height;
        const Vec3 drop = c - height * n;
        for (const auto& k : corners) {
            const Vec3 p = drop + r * k[0] * a0 + r * k[1] * a1;
            shadow_vertices.insert(shadow_vertices.end(),
                                   {static_cast<float>(p.x), static_cast<float>(p.y), static_cast<float>(p.z),
                                    static_cast<float>(k[0]), static_cast<float>(k[1]),
                                    static_cast<float>(strength)});
        }
    }
    if (shadow_vertices.empty())
        return;
    glUseProgram(programs.shadow);
    glUniformMatrix4fv(programs.shadow_view_proj, 1, GL_FALSE, view.view_proj.data());
    glBindVertexArray(shadow_vao);
    glBindBuffer(GL_ARRAY_BUFFER, shadow_vbo);
    glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(shadow_vertices.size() * sizeof(float)),
                 shadow_vertices.data(), GL_STREAM_DRAW);
    glDepthMask(GL_FALSE);
    glEnable(GL_BLEND);
    glBlendFunc(GL_DST_COLOR, GL_ZERO); // multiply: darken what the grid drew
    glDrawArrays(GL_TRIANGLES, 0, static_cast<GLsizei>(shadow_vertices.size() / 6));
    glDisable(GL_BLEND);
    glDepthMask(GL_TRUE);
}

// The whole image to the sky's bottom colour and the far plane.
void Renderer::Impl::clear_image()
{
    glClearColor(static_cast<float>(def.sky_bottom.x), static_cast<float>(def.sky_bottom.y),
                 static_cast<float>(def.sky_bottom.z), 1.0f);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
}

// Frames the camera (over the bodies' boxes), binds the image (cleared at one sample; under MSAA
// draw_background clears it when it draws) and sets up the body program: the view of this frame.
render::View Renderer::Impl::begin_frame(const std::vector<Aabb>& boxes, const CameraDef& camera_in,
                                         const PixelRect& rect)
{
    const double aspect = static_cast<double>(rect.width) / rect.height;
    CameraDef camera = render::frame_boxes(boxes, camera_in, aspect);
    if (def.fault == RenderFault::FlippedYaw)
        camera.yaw_deg += 180.0;
    const CameraDef framed =
        render::frame_boxes(boxes, CameraDef{.target = std::nullopt, .fov_deg = camera.fov_deg}, aspect);
    const render::View view = render::make_view(camera, aspect, framed.distance);

    framebuffer.bind();
    glDepthMask(GL_TRUE);
    if (framebuffer.samples() == 1) // under MSAA the background is cleared only when it is drawn
        clear_image();
    set_viewport(gl_rect(rect, def.height));
    glEnable(GL_DEPTH_TEST);
    glEnable(GL_CULL_FACE);
    glCullFace(GL_BACK);
    glFrontFace(GL_CCW);

    glUseProgram(programs.body);
    glUniformMatrix4fv(programs.view_proj, 1, GL_FALSE, view.view_proj.data());
    set_vec3(programs.eye, view.eye);
    // Lights move with the camera (key above-left-front of the view, fill from the right), so every
    // view is lit from the front whatever its yaw.
    const Vec3 fwd = normalized(view.target - view.eye);
    const Vec3 right = normalized(cross(fwd, Vec3{0, 1, 0}));
    set_vec3(programs.key_dir, normalized(-0.55 * right + Vec3{0, 1.1, 0} - 0.6 * fwd));
    set_vec3(programs.fill_dir, normalized(0.8 * right + Vec3{0, 0.2, 0} - 0.5 * fwd));
    glUniform1i(programs.flat, def.fault == RenderFault::FlatShading ? 1 : 0);
    return view;
}

// Every body but the planes, deformed by its modes, into `items`; the planes go to out_planes (normal,
// offset).
void Renderer::Impl::collect_bodies(const World& world, PoseSource poses, const render::View& view,
                                    int viewport_height, std::vector<std::pair<Vec3, double>>& out_planes)
{
    const double alpha = poses == PoseSource::Interpolated ? world.interpolation_alpha() : 1.0;
    items.clear();
    for (Entity b : world_bodies(world)) {
        const ShapeDef& shape = body_shape(world, b);
        if (shape.type == ShapeType::Plane) {
            out_planes.emplace_back(shape.plane_normal, shape.plane_offset);
            continue;
        }
        const bool interpolated = poses == PoseSource::Interpolated;
        const Vec3 position = interpolated ? body_interpolated_position(world, b) : body_position(world, b);
        const std::string surface = render::shape_key(shape);
        BodyEntry& e = entry(world, b, shape, surface,
                             segments_for(world, b, shape, surface, position, view, viewport_height));
        const render::Mat4 model = render::model_matrix(
            position, interpolated ? body_interpolated_orientation(world, b) : body_orientation(world, b));
        auto color = colors.find(b);
        if (e.skin) {
            const BodyModalState state = body_modal_state(world, b);
            e.skin->observe(world.step_count(), state.amplitudes, body_static_correction(world, b));
            e.skin->update(alpha, def.deformation_scale);
        }
        items.push_back({&e, model, color != colors.end() ? color->second : index_color(b.index)});
    }
}

// Segments for a body's tessellation: for a rigid superquadric the fewest of the levels whose gap to
// the surface (tessellation_gap, per shape once) stays within gap_pixels on screen at the depth of the
// body's nearest possible point; otherwise tessellation (modal skins are made per mesh, so a modal body
// keeps one). Levels, not a continuous count, so that few meshes are cached and a body changes mesh
// only where it crosses a level.
int Renderer::Impl::segments_for(const World& world, Entity b, const ShapeDef& shape,
                                 const std::string& surface, const Vec3& position, const render::View& view,
                                 int viewport_height)
{
    if (def.gap_pixels <= 0.0 || shape.type != ShapeType::Superquadric || custom_meshes.count(b) != 0 ||
        body_modal_basis(world, b) != nullptr)
        return def.tessellation;
    const double reach = length(shape.radii);
    const double depth = dot(position - view.eye, view.forward);
    if (!(depth > reach))
        return def.tessellation; // reaches the eye's plane: no size on screen to go by
    const double pixels_per_metre = view.fy * 0.5 * viewport_height / (depth - reach);
    auto [it, fresh] = gaps.try_emplace(surface, 0.0);
    if (fresh)
        it->second = tessellation_gap(shape, 1); // [m], falls as 1 / segments²
    for (int level : {8, 12, 16, 20, 24, 32, 48, 64, 96, 128, 192, 256, 384, 512})
        if (level >= def.tessellation || it->second * pixels_per_metre <= def.gap_pixels * level * level)
            return std::min(level, def.tessellation);
    return def.tessellation;
}

// With the body program in use and its frame uniforms set.
void Renderer::Impl::draw_bodies() const
{
    for (const DrawItem& item : items) {
        glUniformMatrix4fv(programs.model, 1, GL_FALSE, item.model.data());
        set_vec3(programs.color, item.color);
        if (item.entry->skin) {
            glBindVertexArray(item.entry->skin->vao());
            glDrawElements(GL_TRIANGLES, item.entry->skin->index_count(), GL_UNSIGNED_INT, nullptr);
        } else {
            glBindVertexArray(item.entry->mesh->vao);
            glDrawElements(GL_TRIANGLES, item.entry->mesh->index_count, GL_UNSIGNED_INT, nullptr);
        }
    }
}

// The pixels the bodies can cover: their drawn vertices' boxes projected, a pixel more on each side,
// within the viewport; all of it when a box reaches behind the eye; empty without bodies.
GlRect Renderer::Impl::layer_rect(const render::View& view, const GlRect& viewport) const
{
    double lo[2] = {1e300, 1e300}, hi[2] = {-1e300, -1e300};
    for (const DrawItem& item : items) {
        const Aabb& box = item.entry->skin ? item.entry->skin->bounds() : item.entry->mesh->bounds;
        for (int c = 0; c < 8; ++c) {
            const double local[4] = {(c & 1) ? box.max.x : box.min.x, (c & 2) ? box.max.y : box.min.y,
                                     (c & 4) ? box.max.z : box.min.z, 1.0};
            double world_point[4], clip[4];
            transform(item.model, local, world_point);
            transform(view.view_proj, world_point, clip);
            if (!(clip[3] > 1e-9))
                return viewport;
            for (int k = 0; k < 2; ++k) {
                lo[k] = std::min(lo[k], clip[k] / clip[3]);
                hi[k] = std::max(hi[k], clip[k] / clip[3]);
            }
        }
    }
    if (items.empty())
        return {};
    const auto pixel = [](double ndc, int start, int size) { return start + (0.5 * ndc + 0.5) * size; };
    const double x0 = std::max(pixel(lo[0], viewport.x, viewport.width) - 1.0, double(viewport.x));
    const double y0 = std::max(pixel(lo[1], viewport.y, viewport.height) - 1.0, double(viewport.y));
    const double x1 =
        std::min(pixel(hi[0], viewport.x, viewport.width) + 1.0, double(viewport.x + viewport.width));
    const double y1 =
        std::min(pixel(hi[1], viewport.y, viewport.height) + 1.0, double(viewport.y + viewport.height));
    if (!(x1 > x0 && y1 > y0))
        return {};
    const int ix = static_cast<int>(std::floor(x0)), iy = static_cast<int>(std::floor(y0));
    return {ix, iy, static_cast<int>(std::ceil(x1)) - ix, static_cast<int>(std::ceil(y1)) - iy};
}

// Under MSAA only the bodies are drawn at every sample (the ground and sky shade smoothly at one, and
// were already drawn into the image): the pixels they can cover, over the ground's depth, into a
// transparent multisampled target of that rectangle's size, resolved and blended over the image.
void Renderer::Impl::draw_body_layer(const render::View& view,
                                     const std::vector<std::pair<Vec3, double>>& planes,
                                     const GlRect& viewport)
{
    const GlRect r = layer_rect(view, viewport);
    if (r.width <= 0 || r.height <= 0)
        return;
    framebuffer.begin_layer(r.width, r.height);
    // The layer's lower left pixel is the image's pixel (r.x, r.y).
    set_viewport({viewport.x - r.x, viewport.y - r.y, viewport.width, viewport.height});
    glEnable(GL_SCISSOR_TEST);
    glScissor(0, 0, r.width, r.height);
    draw_ground_depth(view, planes);
    glEnable(GL_CULL_FACE);
    glUseProgram(programs.body);
    draw_bodies();
    glDisable(GL_CULL_FACE);
    glDisable(GL_SCISSOR_TEST);
    framebuffer.resolve(r.width, r.height);
    composite_layer(r, viewport);
}

// The resolved layer blended over the image inside r.
void Renderer::Impl::composite_layer(const GlRect& r, const GlRect& viewport)
{
    framebuffer.bind();
    set_viewport(viewport);
    glEnable(GL_SCISSOR_TEST);
    glScissor(r.x, r.y, r.width, r.height);
    glDisable(GL_DEPTH_TEST);
    glEnable(GL_BLEND);
    glBlendFunc(GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
    glUseProgram(programs.layer);
    glActiveTexture(GL_TEXTURE0);
    glBindTexture(GL_TEXTURE_2D, framebuffer.layer_texture());
    glUniform1i(programs.layer_texture, 0);
    glUniform2i(programs.layer_origin, r.x, r.y);
    const float cover[6] = {-1, -1, 3, -1, -1, 3}; // one triangle over the viewport
    glBindVertexArray(sky_vao);
    glBindBuffer(GL_ARRAY_BUFFER, sky_vbo);
    glBufferData(GL_ARRAY_BUFFER, sizeof cover, cover, GL_STREAM_DRAW);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glBindTexture(GL_TEXTURE_2D, 0);
    glDisable(GL_BLEND);
    glEnable(GL_DEPTH_TEST);
    glDisable(GL_SCISSOR_TEST);
}

// Under MSAA: the grids and the sky, which depend only on the view, saved (colour and depth) once
// the camera, the view rectangle and the planes have stayed the same for two frames, and copied back
// while they stay so: a still camera then pays for neither, a moving one for no copy. Shadows and
// bodies are drawn over it every frame.
void Renderer::Impl::draw_background(const render::View& view,
                                     const std::vector<std::pair<Vec3, double>>& planes,
                                     const GlRect& viewport)
{
    std::vector<float> key(view.view_proj.begin(), view.view_proj.end());
    for (int v : {viewport.x, viewport.y, viewport.width, viewport.height})
        key.push_back(static_cast<float>(v));
    for (const auto& [normal, offset] : planes)
        key.insert(key.end(), {static_cast<float>(normal.x), static_cast<float>(normal.y),
                               static_cast<float>(normal.z), static_cast<float>(offset)});
    if (key == background_key) {
        framebuffer.restore_background();
    } else {
        clear_image();
        for (const auto& [normal, offset] : planes)
            draw_grid(view, normal, offset, viewport);
        draw_sky(sky_for(view, planes, viewport));
        if (key == drawn_key) {
            framebuffer.save_background();
            background_key = std::move(key);
            drawn_key.clear();
        } else {
            drawn_key = std::move(key);
        }
    }
    framebuffer.bind();
    set_viewport(viewport);
}

Status Renderer::Impl::render(const World& world, const CameraDef& camera_in, Image& out, PoseSource poses,
                              const std::function<void()>& overlay, const PixelRect& view_in)
{
    PixelRect rect = view_in;
    if (rect.width == 0 && rect.height == 0)
        rect = {0, 0, def.width, def.height};
    if (rect.width < 1 || rect.height < 1 || rect.x < 0 || rect.y < 0 || rect.x + rect.width > def.width ||
        rect.y + rect.height > def.height)
        return Error{"", "render/view",
                     "expected a rectangle inside the " + std::to_string(def.width) + "x" +
                         std::to_string(def.height) + " image, found " + std::to_string(rect.width) + "x" +
                         std::to_string(rect.height) + " at (" + std::to_string(rect.x) + ", " +
                         std::to_string(rect.y) + ")"};
    if (Status s = context.make_current(); !s)
        return s;
    if (last_world != &world) { // another world: its handles mean other bodies
        bodies.clear();
        last_world = &world;
    }
    // The bodies' boxes once a frame: for the framing and, unless the poses are interpolated, the shadows.
    const std::vector<Aabb> boxes = render::body_boxes(world);
    const render::View view = begin_frame(boxes, camera_in, rect);
    const std::vector<Aabb> shadow_boxes =
        poses == PoseSource::Interpolated ? render::body_boxes(world, poses) : std::vector<Aabb>{};
    const std::vector<Aabb>& shadowed = poses == PoseSource::Interpolated ? shadow_boxes : boxes;
    const GlRect viewport = gl_rect(rect, def.height);
    std::vector<std::pair<Vec3, double>> planes;
    collect_bodies(world, poses, view, rect.height, planes);
    if (!def.grid)
        planes.clear();
    else if (planes.empty())
        planes.emplace_back(Vec3{0, 1, 0}, 0.0);
    glDisable(GL_CULL_FACE);
    if (framebuffer.samples() > 1) {
        draw_background(view, planes, viewport);
        draw_ground_shadows(shadowed, view, planes);
        draw_body_layer(view, planes, viewport);
    } else {
        glEnable(GL_CULL_FACE);
        draw_bodies(); // first: the ground and the sky then shade only what they show
        glDisable(GL_CULL_FACE);
        for (const auto& [normal, offset] : planes)
            draw_grid(view, normal, offset, viewport);
        draw_ground_shadows(shadowed, view, planes);
        draw_sky(sky_for(view, planes, viewport));
    }
    glBindVertexArray(0);
    out.width = def.width;
    out.height = def.height;
    if (overlay) {
        framebuffer.bind(); // the viewport back to the whole image
        overlay();
        framebuffer.bind(); // the overlay may have bound something else
    }
    framebuffer.read(out.rgba);
    if (std::string e = render::gl_errors(); !e.empty())
        return Error{"", "render", "drawing a frame: " + e};
    return {};
}

Renderer::Renderer(std::unique_ptr<Impl> impl) : m_impl(std::move(impl)) {}
Renderer::~Renderer() = default;
Renderer::Renderer(Renderer&&) noexcept = default;
Renderer& Renderer::operator=(Renderer&&) noexcept = default;

Result<Renderer> Renderer::create(const RenderDef& def)
{
    if (Status s = validate(def); !s)
        return Error{"", "render/" + s.error().where, s.error().what};
    auto impl = std::make_unique<Impl>();
    impl->def = def;
    if (Status s = impl->init(); !s)
        return s.error();
    return Renderer(std::move(impl));
}

const RenderDef& Renderer::settings() const
{
    return m_impl->def;
}
std::string Renderer::device_name() const
{
    return m_impl->context.device_name();
}
void Renderer::set_body_color(Entity body, const Vec3& rgb)
{
    m_impl->colors[body] =
        Vec3{std::clamp(rgb.x, 0.0, 1.0), std::clamp(rgb.y, 0.0, 1.0), std::clamp(rgb.z, 0.0, 1.0)};
}

void Renderer::set_body_mesh(Entity body, std::shared_ptr<const TriangleMesh> mesh)
{
    if (mesh)
        m_impl->custom_meshes[body] = std::move(mesh);
    else
        m_impl->custom_meshes.erase(body);
}
Status Renderer::render(const World& world, const CameraDef& camera, Image& out, PoseSource poses)
{
    return m_impl->render(world, camera, out, poses, {}, {});
}
Status Renderer::render(const World& world, const CameraDef& camera, Image& out, PoseSource poses,
                        const std::function<void()>& overlay, const PixelRect& view)
{
    return m_impl->render(world, camera, out, poses, overlay, view);
}
int Renderer::cached_mesh_count() const
{
    return m_impl->meshes.size();
}

} // namespace supermodal
