// Fuzz target for engine/src/io mesh import (libFuzzer): the files `fit`, `fit --attach` and a scene's
// "mesh" read. The first byte picks the file extension (assimp chooses its reader by it), the rest is
// the file. Any bytes in: never a crash, hang or sanitizer report; an accepted mesh must be well formed
// (finite positions, a normal per position, whole triangles, indices in range). Every other value of
// the first byte's sixes reads the look too (a scene's "mesh" does): texture coordinates per vertex
// or none, a material per triangle and in range, or none.
#include "supermodal/mesh_io.h"

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <unistd.h>

namespace
{
const char* const k_extensions[] = {"obj", "stl", "ply", "gltf", "glb", "fbx"};
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
    if (size < 1)
        return 0;
    const std::string path = "/tmp/supermodal_mesh_fuzz_" + std::to_string(::getpid()) + "." +
                             k_extensions[data[0] % (sizeof k_extensions / sizeof k_extensions[0])];
    if (std::FILE* f = std::fopen(path.c_str(), "wb")) {
        std::fwrite(data + 1, 1, size - 1, f);
        std::fclose(f);
    } else {
        return 0;
    }
    supermodal::ImportDef def = supermodal::default_import_def();
    def.keep_look = (data[0] / (sizeof k_extensions / sizeof k_extensions[0])) % 2 == 1;
    const supermodal::Result<supermodal::ImportedMesh> mesh = supermodal::import_mesh(path, def);
    std::remove(path.c_str());
    if (!mesh) {
        if (mesh.error().what.empty())
            std::abort(); // a refusal must say why
        return 0;
    }
    const supermodal::TriangleMesh& m = mesh->mesh;
    if (m.indices.empty() || m.indices.size() % 3 != 0 || m.normals.size() != m.positions.size())
        std::abort();
    for (const supermodal::Vec3& p : m.positions)
        if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
            std::abort();
    for (const uint32_t i : m.indices)
        if (i >= m.positions.size())
            std::abort();
    const supermodal::MeshLook& look = mesh->look;
    if (!look.texcoords.empty() && look.texcoords.size() != 2 * m.positions.size())
        std::abort();
    if (!look.triangle_materials.empty() && look.triangle_materials.size() * 3 != m.indices.size())
        std::abort();
    for (const uint32_t k : look.triangle_materials)
        if (k >= look.materials.size())
            std::abort();
    return 0;
}
