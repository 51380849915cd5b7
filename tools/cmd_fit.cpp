// SPDX-License-Identifier: MIT
// `supermodal fit`: mesh → superquadric(s) → scene-format v1 bodies plus the fit report.
#include "cmd_fit.h"

#include "cli_common.h"
#include "supermodal/fit.h"
#include "supermodal/mesh_io.h"

#include <chrono>
#include <cstdio>
#include <filesystem>

namespace supermodal::cli
{
namespace
{

nlohmann::json body_json(const FitResult& f, const std::string& name, const std::string& mesh)
{
    const ShapeDef& s = f.shape;
    char note[256];
    std::snprintf(note, sizeof note, "fitted by supermodal fit to %s: rms %.3g m (%.2f %% of size)",
                  mesh.c_str(), f.rms_m, 100.0 * f.rms_relative);
    return {{"name", name},
            {"comment", note},
            {"shape",
             {{"type", "superquadric"},
              {"radii", to_json(s.radii)},
              {"exponents", {s.epsilon1, s.epsilon2}},
              {"taper", {s.taper.kx, s.taper.ky}},
              {"bend", {{"curvature", s.bend.curvature}, {"angle", s.bend.angle}}}}},
            {"position", to_json(f.position)},
            {"orientation", to_json(f.orientation)}};
}

nlohmann::json report_json(const FitResult& f, const std::string& name)
{
    return {{"name", name},       {"rms_m", f.rms_m},          {"rms_relative", f.rms_relative},
            {"max_m", f.max_m},   {"size_m", f.size_m},        {"iterations", f.iterations},
            {"starts", f.starts}, {"acceptable", f.acceptable}};
}

// The mesh in the fitted body's shape frame, p_shape = R⁻¹(p − position), as OBJ text (positions and
// triangles; normals are rebuilt from the faces by whoever reads it).
std::string mesh_in_body_frame_obj(const TriangleMesh& mesh, const FitResult& f)
{
    std::string out = "# mesh in the fitted superquadric's shape frame [m], written by supermodal fit\n";
    char line[128];
    for (const Vec3& p : mesh.positions) {
        const Vec3 q = inv_rotate(f.orientation, p - f.position);
        std::snprintf(line, sizeof line, "v %.9g %.9g %.9g\n", q.x, q.y, q.z);
        out += line;
    }
    for (size_t i = 0; i + 2 < mesh.indices.size(); i += 3) {
        std::snprintf(line, sizeof line, "f %u %u %u\n", mesh.indices[i] + 1, mesh.indices[i + 1] + 1,
                      mesh.indices[i + 2] + 1);
        out += line;
    }
    return out;
}

/// Checks --up, --attach and --scene up front and fills the import's up axis; an error, or empty.
std::string check_fit_options(const FitOptions& o, ImportDef& import_def)
{
    if (!parse_up_axis(o.up, import_def.up_axis))
        return "--up: expected one of from_file, +x, +y, +z, -x, -y, -z, found " + o.up;
    if (o.attach && (o.scene_out.empty() || o.parts != 1))
        return "--attach: needs --scene OUT.json and one part (--parts 1)";
    if (!o.scene_out.empty())
        return check_writable(o.scene_out);
    return {};
}

/// The fitted parts as scene bodies and report rows, and their worst errors.
struct FitTally {
    nlohmann::json bodies = nlohmann::json::array();
    nlohmann::json parts = nlohmann::json::array();
    double worst_rms = 0.0, worst_relative = 0.0;
    int iterations = 0;
    bool acceptable = true;
};

FitTally tally_fits(const std::vector<FitResult>& fits, const std::string& stem, const std::string& mesh)
{
    FitTally t;
    for (size_t k = 0; k < fits.size(); ++k) {
        const FitResult& f = fits[k];
        const std::string name = fits.size() == 1 ? stem : stem + "_" + std::to_string(k);
        t.bodies.push_back(body_json(f, name, mesh));
        t.parts.push_back(report_json(f, name));
        t.worst_rms = std::max(t.worst_rms, f.rms_m);
        t.worst_relative = std::max(t.worst_relative, f.rms_relative);
        t.iterations += f.iterations;
        t.acceptable = t.acceptable && f.acceptable;
    }
    return t;
}

/// --attach: writes the mesh in the fitted body's frame next to the scene and names it as the body's
/// render mesh. Written first: the scene names it, so a scene on disk never points at a missing mesh.
/// An error message, or empty.
std::string attach_mesh(const FitOptions& o, const std::string& stem, const TriangleMesh& mesh,
                        const FitResult& fit, nlohmann::json& body)
{
    const std::filesystem::path scene_path(o.scene_out);
    const std::string file = scene_path.stem().string() + "_" + stem + ".obj";
    const std::string path = (scene_path.parent_path() / file).string();
    if (std::string e = write_file_atomically(path, mesh_in_body_frame_obj(mesh, fit)); !e.empty())
        return e;
    body["mesh"] = file;
    return {};
}

/// With several parts the summary is the worst part's error, so a bad part is never averaged away.
nlohmann::json fit_report(const std::string& mesh_file, const ImportedMesh& mesh, const FitTally& t,
                          const FitDef& def, double seconds)
{
    return {{"mesh", mesh_file},
            {"import",
             {{"format", mesh.format},
              {"scale", mesh.scale},
              {"up_axis", up_axis_name(mesh.up_axis)},
              {"vertices", mesh.mesh.positions.size()},
              {"triangles", mesh.mesh.indices.size() / 3}}},
            {"rms_m", t.worst_rms},
            {"rms_relative", t.worst_relative},
            {"iterations", t.iterations},
            {"acceptable", t.acceptable},
            {"acceptable_rms_relative", def.acceptable_rms_relative},
            {"seconds", seconds},
            {"parts", t.parts}};
}

void print_fit_text(const std::string& mesh_file, const ImportedMesh& mesh,
                    const std::vector<FitResult>& fits, const nlohmann::json& parts, double seconds)
{
    std::printf("%s: %zu vertices, %zu triangles (%s, scale %g m/unit, up %s), fitted in %.3f s\n",
                mesh_file.c_str(), mesh.mesh.positions.size(), mesh.mesh.indices.size() / 3,
                mesh.format.c_str(), mesh.scale, up_axis_name(mesh.up_axis), seconds);
    for (size_t k = 0; k < fits.size(); ++k) {
        const FitResult& f = fits[k];
        std::printf("  %-16s radii [%.4g %.4g %.4g] m, exponents [%.3f %.3f], rms %.3g m (%.2f %%)%s\n",
                    parts[k]["name"].get<std::string>().c_str(), f.shape.radii.x, f.shape.radii.y,
                    f.shape.radii.z, f.shape.epsilon1, f.shape.epsilon2, f.rms_m, 100.0 * f.rms_relative,
                    f.acceptable ? "" : "  NOT a good fit");
    }
}

} // namespace

CLI::App* add_fit_command(CLI::App& app, FitOptions& o)
{
    CLI::App* cmd = app.add_subcommand(
        "fit", "Fit superquadrics to a mesh (OBJ, PLY, STL, glTF/GLB, FBX) and print scene-format bodies");
    cmd->add_option("mesh", o.mesh, "Mesh file")->required();
    cmd->add_option("--parts", o.parts,
                    "Split along the longest axis into K parts (1-D k-means), one body each")
        ->check(CLI::Range(1, 64));
    cmd->add_flag("--taper", o.taper, "Also fit Barr taper (kx, ky)");
    cmd->add_flag("--bend", o.bend, "Also fit Barr bend (curvature, angle)");
    cmd->add_flag("--json", o.json, "Print {\"scene\": ..., \"fit\": ...} as JSON instead of text");
    cmd->add_option("--scene", o.scene_out, "Also write the fitted bodies as a scene file (format v1)");
    cmd->add_option("--scale", o.scale, "Metres per file unit (default: from the file, else 1)")
        ->check(CLI::PositiveNumber);
    cmd->add_option("--up", o.up,
                    "The file's up axis: from_file, +x, +y, +z, -x, -y, -z (default from_file)");
    cmd->add_option("--name", o.name, "Body name (default: the file name without extension)");
    cmd->add_flag("--attach", o.attach,
                  "With --scene and one part: also write the mesh in the fitted body's frame as "
                  "SCENE_STEM_NAME.obj next to the scene and name it as the body's render \"mesh\"");
    return cmd;
}

int fit_command(const FitOptions& o)
{
    ImportDef import_def = default_import_def();
    import_def.scale = o.scale;
    if (const std::string e = check_fit_options(o, import_def); !e.empty()) {
        print_error(e);
        return k_exit_bad_input;
    }
    const Result<ImportedMesh> mesh = import_mesh(o.mesh, import_def);
    if (!mesh) {
        print_error(mesh.error().message());
        return k_exit_bad_input;
    }
    FitDef def = default_fit_def();
    def.taper = o.taper;
    def.bend = o.bend;
    const auto start = std::chrono::steady_clock::now();
    const Result<std::vector<FitResult>> fits = fit_superquadric_parts(mesh->mesh, o.parts, def);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (!fits) {
        print_error(o.mesh + ": " + fits.error().message());
        return k_exit_bad_input;
    }
    const std::string stem = o.name.empty() ? std::filesystem::path(o.mesh).stem().string() : o.name;
    FitTally tally = tally_fits(*fits, stem, o.mesh);
    if (o.attach)
        if (const std::string e = attach_mesh(o, stem, mesh->mesh, fits->front(), tally.bodies[0]);
            !e.empty()) {
            print_error(e);
            return k_exit_internal;
        }
    const nlohmann::json scene = {{"comment", "superquadrics fitted by supermodal fit to " + o.mesh},
                                  {"bodies", tally.bodies}};
    const nlohmann::json report = fit_report(o.mesh, *mesh, tally, def, seconds);
    if (!o.scene_out.empty())
        if (const std::string e = write_file_atomically(o.scene_out, json_text(scene) + "\n"); !e.empty()) {
            print_error(e);
            return k_exit_internal;
        }
    if (o.json)
        std::printf("%s\n", json_text(nlohmann::json{{"scene", scene}, {"fit", report}}).c_str());
    else
        print_fit_text(o.mesh, *mesh, *fits, tally.parts, seconds);
    return k_exit_ok;
}

} // namespace supermodal::cli
