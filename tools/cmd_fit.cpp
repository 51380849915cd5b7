// SPDX-License-Identifier: MIT
// `supermodal fit`: mesh → superquadric(s) → scene-format v1 bodies plus the fit report.
#include "cmd_fit.h"

#include "cli_common.h"
#include "supermodal/fit.h"
#include "supermodal/mesh_io.h"

#include <algorithm>
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

// Material k's name in OBJ and MTL, which split names at spaces: its own name made safe, or
// "material_K" when that is empty or an earlier material's.
std::string obj_material_name(const MeshLook& look, size_t k)
{
    const auto safe = [&](size_t i) {
        std::string name = look.materials[i].name;
        for (char& c : name)
            if (c == ' ' || c == '\t' || c == '#')
                c = '_';
        return name;
    };
    const std::string name = safe(k);
    for (size_t i = 0; i < k; ++i)
        if (safe(i) == name)
            return "material_" + std::to_string(k);
    return name.empty() ? "material_" + std::to_string(k) : name;
}

// The look's materials as MTL text: base colour (Kd), opacity (d) and the base colour image (map_Kd),
// relative to the folder the MTL is written to.
std::string materials_mtl(const MeshLook& look, const std::filesystem::path& folder)
{
    std::string out = "# materials of the attached mesh, written by supermodal fit\n";
    char line[160];
    for (size_t k = 0; k < look.materials.size(); ++k) {
        const MeshMaterial& m = look.materials[k];
        out += "newmtl " + obj_material_name(look, k) + "\n";
        std::snprintf(line, sizeof line, "Kd %.6g %.6g %.6g\nd %.6g\n", m.base_color[0], m.base_color[1],
                      m.base_color[2], m.base_color[3]);
        out += line;
        if (!m.base_color_texture.empty()) {
            std::error_code ec;
            const std::filesystem::path rel = std::filesystem::relative(m.base_color_texture, folder, ec);
            out += "map_Kd " + (ec || rel.empty() ? m.base_color_texture : rel.generic_string()) + "\n";
        }
    }
    return out;
}

// The mesh in the fitted body's shape frame, p_shape = R⁻¹(p − position), as OBJ text: positions,
// texture coordinates and triangles grouped by material (`mtllib` names the MTL file; empty: none).
// Normals are rebuilt from the faces by whoever reads it.
std::string mesh_in_body_frame_obj(const TriangleMesh& mesh, const MeshLook& look, const std::string& mtllib,
                                   const FitResult& f)
{
    std::string out = "# mesh in the fitted superquadric's shape frame [m], written by supermodal fit\n";
    if (!mtllib.empty())
        out += "mtllib " + mtllib + "\n";
    char line[128];
    for (const Vec3& p : mesh.positions) {
        const Vec3 q = inv_rotate(f.orientation, p - f.position);
        std::snprintf(line, sizeof line, "v %.9g %.9g %.9g\n", q.x, q.y, q.z);
        out += line;
    }
    const bool uv = !look.texcoords.empty();
    for (size_t i = 0; uv && i + 1 < look.texcoords.size(); i += 2) {
        std::snprintf(line, sizeof line, "vt %.9g %.9g\n", look.texcoords[i], look.texcoords[i + 1]);
        out += line;
    }
    const size_t groups = std::max<size_t>(1, look.materials.size());
    for (size_t m = 0; m < groups; ++m) {
        if (!look.materials.empty())
            out += "usemtl " + obj_material_name(look, m) + "\n";
        for (size_t i = 0; i + 2 < mesh.indices.size(); i += 3) {
            if (!look.triangle_materials.empty() && look.triangle_materials[i / 3] != m)
                continue;
            const uint32_t a = mesh.indices[i] + 1, b = mesh.indices[i + 1] + 1, c = mesh.indices[i + 2] + 1;
            if (uv)
                std::snprintf(line, sizeof line, "f %u/%u %u/%u %u/%u\n", a, a, b, b, c, c);
            else
                std::snprintf(line, sizeof line, "f %u %u %u\n", a, b, c);
            out += line;
        }
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

/// --attach: writes the mesh in the fitted body's frame next to the scene, with its texture coordinates
/// and materials (an MTL beside it), and names it as the body's render mesh. Written first: the scene
/// names it, so a scene on disk never points at a missing mesh. An error message, or empty.
std::string attach_mesh(const FitOptions& o, const ImportDef& import_def, const std::string& stem,
                        const FitResult& fit, nlohmann::json& body)
{
    // Read again with the look: welding then keeps UV seams apart, which the fit does not need.
    ImportDef def = import_def;
    def.keep_look = true;
    const Result<ImportedMesh> mesh = import_mesh(o.mesh, def);
    if (!mesh)
        return mesh.error().message();
    const std::filesystem::path scene_path(o.scene_out);
    const std::filesystem::path folder = scene_path.parent_path();
    const std::string base = scene_path.stem().string() + "_" + stem;
    std::string mtllib;
    if (!mesh->look.materials.empty()) {
        mtllib = base + ".mtl";
        const std::filesystem::path dir = folder.empty() ? std::filesystem::path(".") : folder;
        if (std::string e = write_file_atomically((folder / mtllib).string(), materials_mtl(mesh->look, dir));
            !e.empty())
            return e;
    }
    const std::string file = base + ".obj";
    if (std::string e = write_file_atomically((folder / file).string(),
                                              mesh_in_body_frame_obj(mesh->mesh, mesh->look, mtllib, fit));
        !e.empty())
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
                  "SCENE_STEM_NAME.obj (with its texture coordinates, and its materials in "
                  "SCENE_STEM_NAME.mtl) next to the scene and name it as the body's render \"mesh\"");
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
        if (const std::string e = attach_mesh(o, import_def, stem, fits->front(), tally.bodies[0]);
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
