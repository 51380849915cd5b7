// SPDX-License-Identifier: MIT
// Export, part 1: meshes with per-mode displacements, and sampling a run (supermodal/export.h).
#include "supermodal/body.h"
#include "supermodal/export.h"
#include "supermodal/modal.h"
#include "supermodal/world.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

namespace supermodal
{
namespace
{

Error bad(const std::string& where, const std::string& what)
{
    return Error{"", where, what};
}

std::string num(double x)
{
    char buf[32];
    std::snprintf(buf, sizeof buf, "%g", x);
    return buf;
}

bool finite(const Vec3& v)
{
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

// Morph target k of a mesh: u(p) for q = e_k, read straight off the mass-normalised mode shapes
// (entry (node·3 + axis)·r + k) so r targets cost one pass over the weights, not r.
std::vector<std::vector<Vec3>> mode_displacements(const ModalBasis& basis, const TriangleMesh& mesh)
{
    const size_t r = static_cast<size_t>(basis.mode_count);
    std::vector<std::vector<Vec3>> out(r, std::vector<Vec3>(mesh.positions.size()));
    for (size_t i = 0; i < mesh.positions.size(); ++i) {
        const LatticeWeights w = modal_weights(basis, mesh.positions[i]);
        for (int j = 0; j < w.count; ++j) {
            const double* phi = basis.mode_shapes.data() + static_cast<size_t>(w.nodes[j]) * 3 * r;
            for (size_t k = 0; k < r; ++k) {
                out[k][i].x += w.weights[j] * phi[k];
                out[k][i].y += w.weights[j] * phi[r + k];
                out[k][i].z += w.weights[j] * phi[2 * r + k];
            }
        }
    }
    return out;
}

Status sample(const World& world, const std::vector<Entity>& bodies, ExportRecording& rec, double t)
{
    char when[64];
    std::snprintf(when, sizeof when, " at t = %.6g s (the run diverged?)", t);
    for (size_t i = 0; i < bodies.size(); ++i) {
        ExportBody& out = rec.bodies[i];
        const Vec3 p = body_position(world, bodies[i]);
        Quat q = body_orientation(world, bodies[i]);
        if (!finite(p) ||
            !(std::isfinite(q.w) && std::isfinite(q.x) && std::isfinite(q.y) && std::isfinite(q.z)))
            return bad("body " + out.name, std::string("non-finite pose") + when);
        // q and −q are the same rotation; keep neighbours in one hemisphere so interpolation takes the
        // short way.
        if (!out.orientations.empty()) {
            const Quat& prev = out.orientations.back();
            if (prev.w * q.w + prev.x * q.x + prev.y * q.y + prev.z * q.z < 0.0)
                q = Quat{-q.w, -q.x, -q.y, -q.z};
        }
        out.positions.push_back(p);
        out.orientations.push_back(q);
        if (out.mode_displacements.empty())
            continue;
        const BodyModalState s = body_modal_state(world, bodies[i]);
        for (size_t k = 0; k < out.mode_displacements.size(); ++k) {
            const double a = k < s.amplitudes.size() ? s.amplitudes[k] : 0.0;
            if (!std::isfinite(a))
                return bad("body " + out.name, std::string("non-finite modal amplitude") + when);
            out.amplitudes.push_back(a);
        }
    }
    rec.times.push_back(t);
    return {};
}

} // namespace

ExportDef default_export_def()
{
    return ExportDef{};
}

Status validate(const ExportDef& def)
{
    if (!(std::isfinite(def.seconds) && def.seconds > 0.0 && def.seconds <= 3600.0))
        return bad("seconds", "expected a number in (0, 3600] s, found " + num(def.seconds));
    if (!(std::isfinite(def.fps) && def.fps > 0.0))
        return bad("fps", "expected a number > 0, found " + num(def.fps));
    if (def.tessellation < 8 || def.tessellation > 512)
        return bad("tessellation",
                   "expected an integer in [8, 512], found " + std::to_string(def.tessellation));
    return {};
}

Result<ExportRecording> record_animation(World& world, const ExportDef& def,
                                         std::span<const ExportBodyMesh> meshes)
{
    if (Status s = validate(def); !s)
        return s.error();
    const double dt = world.settings().dt;
    // Each sample must be its own step, or two keys would share a time.
    if (def.fps * dt > 1.0 + 1e-9)
        return bad("fps", "expected at most the step rate 1/dt = " + num(1.0 / dt) + " per s, found " +
                              num(def.fps));
    for (const ExportBodyMesh& m : meshes) {
        const Entity b = find_body(world, m.body);
        if (b.is_null())
            return bad("body " + m.body, "a render mesh was given for a body that is not in the world");
        if (!m.mesh || m.mesh->positions.empty() || m.mesh->indices.empty())
            return bad("body " + m.body, "the render mesh has no triangles");
        if (body_shape(world, b).type == ShapeType::Plane)
            return bad("body " + m.body, "a plane has no render mesh");
    }
    ExportRecording rec;
    std::vector<Entity> bodies;
    for (Entity b : world_bodies(world)) {
        const ShapeDef& shape = body_shape(world, b);
        if (shape.type == ShapeType::Plane)
            continue;
        ExportBody out;
        out.name = body_name(world, b);
        if (out.name.empty())
            out.name = "body_" + std::to_string(b.index);
        const auto given = std::find_if(meshes.begin(), meshes.end(),
                                        [&](const ExportBodyMesh& m) { return m.body == out.name; });
        out.mesh = given != meshes.end() ? *given->mesh : tessellate(shape, def.tessellation);
        if (given != meshes.end() && given->look)
            out.look = *given->look;
        if (const ModalBasis* basis = body_modal_basis(world, b); basis != nullptr && def.morph_targets) {
            out.mode_displacements = mode_displacements(*basis, out.mesh);
            out.frequencies_hz = basis->frequencies_hz;
        }
        rec.bodies.push_back(std::move(out));
        bodies.push_back(b);
    }
    if (bodies.empty())
        return bad("", "nothing to export: the world has no bodies other than planes");
    // Small slack so that seconds·fps = 6.0000000001 still gives 7 samples, not 8.
    const double frame_count = std::floor(def.seconds * def.fps + 1e-9) + 1.0;
    // A million samples of even one small body is hundreds of MB: surely a typo in seconds or fps.
    if (frame_count > 1e6)
        return bad("fps", "seconds × fps gives " + num(frame_count) + " samples; at most 1e6");
    const auto frames = static_cast<size_t>(frame_count);
    const double t0 = world.time();
    for (size_t k = 0; k < frames; ++k) {
        // The step nearest k/fps (half a step of slack), and never the previous sample's step.
        const double target = static_cast<double>(k) / def.fps;
        while (world.time() - t0 < target - 0.5 * dt)
            world.step();
        if (k > 0 && world.time() - t0 <= rec.times.back())
            world.step();
        if (Status s = sample(world, bodies, rec, world.time() - t0); !s)
            return s.error();
    }
    return rec;
}

Vec3 exported_vertex(const ExportBody& body, size_t frame, size_t vertex)
{
    Vec3 p = body.mesh.positions[vertex];
    const size_t r = body.mode_displacements.size();
    for (size_t k = 0; k < r; ++k)
        p += body.mode_displacements[k][vertex] * body.amplitudes[frame * r + k];
    return body.positions[frame] + rotate(body.orientations[frame], p);
}

} // namespace supermodal
