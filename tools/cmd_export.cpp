// SPDX-License-Identifier: MIT
// `supermodal export`: scene → run → glTF 2.0 binary with node and morph-target animation, or OBJs.
#include "cmd_export.h"

#include "cli_common.h"
#include "supermodal/export.h"

#include <chrono>
#include <cstdio>
#include <filesystem>

namespace supermodal::cli
{
namespace
{

double seconds_since(std::chrono::steady_clock::time_point start)
{
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// Bad paths fail before the run, so a long export never ends in an unwritable file. An error, or empty.
std::string check_export_options(const ExportOptions& o)
{
    if (o.out.empty() && o.obj_dir.empty())
        return "export: nothing to write: give --out FILE.glb and/or --obj DIR";
    if (!o.out.empty())
        if (std::string e = check_writable(o.out); !e.empty())
            return e;
    if (!o.obj_dir.empty()) {
        std::error_code ec;
        if (std::filesystem::exists(o.obj_dir, ec) && !std::filesystem::is_directory(o.obj_dir, ec))
            return o.obj_dir + ": exists and is not a directory";
    }
    return {};
}

// Writes the GLB and/or the OBJ sequence; sets glb_bytes. An error message, or empty.
std::string write_export(const ExportOptions& o, const ExportRecording& rec, size_t& glb_bytes)
{
    if (!o.out.empty()) {
        if (Status s = write_glb(rec, o.out); !s)
            return s.error().message();
        glb_bytes = static_cast<size_t>(std::filesystem::file_size(o.out));
    }
    if (!o.obj_dir.empty())
        if (Status s = write_obj_sequence(rec, o.obj_dir); !s)
            return s.error().message();
    return {};
}

struct ExportTimes {
    double record_seconds = 0.0, write_seconds = 0.0; ///< Wall time [s].
};

void print_export_report(const ExportOptions& o, const ExportRecording& rec, size_t glb_bytes,
                         const ExportTimes& times)
{
    size_t targets = 0, vertices = 0;
    for (const ExportBody& b : rec.bodies) {
        targets += b.mode_displacements.size();
        vertices += b.mesh.positions.size();
    }
    if (o.json) {
        const nlohmann::json report = {{"scene", o.scene},
                                       {"glb", o.out},
                                       {"obj_dir", o.obj_dir},
                                       {"bodies", rec.bodies.size()},
                                       {"frames", rec.times.size()},
                                       {"last_time", rec.times.back()},
                                       {"vertices", vertices},
                                       {"morph_targets", targets},
                                       {"glb_bytes", glb_bytes},
                                       {"record_seconds", times.record_seconds},
                                       {"write_seconds", times.write_seconds}};
        std::printf("%s\n", json_text(report).c_str());
        return;
    }
    std::printf("%s: %zu bodies, %zu vertices, %zu morph targets, %zu frames over %.4g s; run %.3f s, "
                "written %.3f s",
                o.scene.c_str(), rec.bodies.size(), vertices, targets, rec.times.size(), rec.times.back(),
                times.record_seconds, times.write_seconds);
    if (!o.out.empty())
        std::printf("; %s %zu bytes", o.out.c_str(), glb_bytes);
    std::printf("\n");
}

// The scene's body colours (as the renderer draws them) for the GLB's materials. The recording has the
// scene's bodies in order, planes left out.
void set_base_colors(const Scene& scene, ExportRecording& rec)
{
    const std::vector<Vec3> colors = scene_body_colors(scene);
    size_t next = 0;
    for (size_t i = 0; i < scene.bodies.size() && next < rec.bodies.size(); ++i)
        if (scene.bodies[i].def.shape.type != ShapeType::Plane)
            rec.bodies[next++].base_color = colors[i];
}

} // namespace

CLI::App* add_export_command(CLI::App& app, ExportOptions& o)
{
    CLI::App* cmd = app.add_subcommand(
        "export", "Run a scene and write the animation: glTF 2.0 binary (nodes, morph targets for the "
                  "modes) and/or an OBJ per frame");
    cmd->add_option("scene", o.scene, "Scene file (JSON, format v1)")->required();
    cmd->add_option("--seconds", o.seconds, "Simulated time to record [s] (default: settings.duration)")
        ->check(CLI::PositiveNumber);
    cmd->add_option("--fps", o.fps, "Samples per second (default 30; at most 1/dt)")
        ->check(CLI::PositiveNumber);
    cmd->add_option("--out", o.out, "Write the animation as a GLB file here");
    cmd->add_option("--obj", o.obj_dir,
                    "Write frame_000000.obj, ... (deformed, world frame) into this directory");
    cmd->add_option("--tessellation", o.tessellation, "Mesh segments around each body's equator (8 to 512)")
        ->check(CLI::Range(8, 512));
    cmd->add_flag("--no-morph", o.no_morph, "Export modal bodies rigid, without morph targets");
    cmd->add_flag("--json", o.json, "Print the report as JSON");
    return cmd;
}

int export_command(const ExportOptions& o)
{
    if (const std::string e = check_export_options(o); !e.empty()) {
        print_error(e);
        return k_exit_bad_input;
    }
    const Result<Scene> scene = load_scene(o.scene);
    if (!scene) {
        print_error(scene.error().message());
        return k_exit_bad_input;
    }
    Result<World> world = build_world(*scene);
    if (!world) {
        print_error(world.error().message());
        return k_exit_bad_input;
    }
    ExportDef def = default_export_def();
    def.seconds = o.seconds > 0.0 ? o.seconds : scene->duration;
    def.fps = o.fps;
    def.tessellation = o.tessellation;
    def.morph_targets = !o.no_morph;
    auto start = std::chrono::steady_clock::now();
    std::vector<ExportBodyMesh> meshes; // the scene's "mesh" files replace the tessellation
    for (const SceneBody& b : scene->bodies)
        if (b.render_mesh)
            meshes.push_back({b.def.name, b.render_mesh, b.render_look});
    Result<ExportRecording> rec = record_animation(*world, def, meshes);
    if (rec)
        set_base_colors(*scene, *rec);
    ExportTimes times;
    times.record_seconds = seconds_since(start);
    if (!rec) {
        print_error(o.scene + ": " + rec.error().message());
        return k_exit_bad_input;
    }
    start = std::chrono::steady_clock::now();
    size_t glb_bytes = 0;
    if (const std::string e = write_export(o, *rec, glb_bytes); !e.empty()) {
        print_error(e);
        return k_exit_internal;
    }
    times.write_seconds = seconds_since(start);
    print_export_report(o, *rec, glb_bytes, times);
    return k_exit_ok;
}

} // namespace supermodal::cli
