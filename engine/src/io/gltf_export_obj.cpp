// SPDX-License-Identifier: MIT
// Export, part 3: a recording as one Wavefront OBJ per sample, every body deformed and posed (world).
#include "io/atomic_file.h"
#include "supermodal/export.h"

#include <cstdio>
#include <filesystem>
#include <string>

namespace supermodal
{

Status write_obj_sequence(const ExportRecording& rec, const std::string& dir)
{
    // The GLB check covers the shape of the data (sizes, indices, finite values): reuse it.
    if (Result<std::vector<uint8_t>> probe = glb_from_recording(rec); !probe)
        return Error{dir, probe.error().where, probe.error().what};
    namespace fs = std::filesystem;
    std::error_code ec;
    if (fs::exists(dir, ec) && !fs::is_directory(dir, ec))
        return Error{dir, "", "exists and is not a directory"};
    fs::create_directories(dir, ec);
    if (ec)
        return Error{dir, "", "cannot make the directory: " + ec.message()};
    std::string text;
    char line[160];
    for (size_t f = 0; f < rec.times.size(); ++f) {
        text.clear();
        std::snprintf(line, sizeof line, "# supermodal export, t = %.9g s, metres, world frame (Y up)\n",
                      rec.times[f]);
        text += line;
        size_t base = 1; // OBJ indices are 1-based and count over the whole file
        for (const ExportBody& b : rec.bodies) {
            text += "o " + b.name + "\n";
            for (size_t v = 0; v < b.mesh.positions.size(); ++v) {
                const Vec3 p = exported_vertex(b, f, v);
                std::snprintf(line, sizeof line, "v %.9g %.9g %.9g\n", p.x, p.y, p.z);
                text += line;
            }
            for (size_t t = 0; t + 2 < b.mesh.indices.size(); t += 3) {
                std::snprintf(line, sizeof line, "f %zu %zu %zu\n", base + b.mesh.indices[t],
                              base + b.mesh.indices[t + 1], base + b.mesh.indices[t + 2]);
                text += line;
            }
            base += b.mesh.positions.size();
        }
        std::snprintf(line, sizeof line, "frame_%06zu.obj", f);
        if (Status s = write_file_atomically((fs::path(dir) / line).string(), text.data(), text.size()); !s)
            return s;
    }
    return {};
}

} // namespace supermodal
