// SPDX-License-Identifier: MIT
// Export, part 2: a recording as glTF 2.0 binary (GLB). Layout per the glTF 2.0 specification: a
// 12-byte header (magic "glTF", version 2, total length), a JSON chunk padded with spaces and a BIN
// chunk padded with zeros, each to 4 bytes. One bufferView per accessor, 4-byte aligned, tightly
// packed (so no byteStride); vertex data targets ARRAY_BUFFER, indices ELEMENT_ARRAY_BUFFER, animation
// data no target (the specification forbids a target there). Materials are metallic-roughness ones;
// base colour images go into the BIN chunk with their MIME type.
#include "io/atomic_file.h"
#include "supermodal/export.h"

#include <cmath>
#include <cstring>
#include <fstream>
#include <iterator>
#include <limits>
#include <map>
#include <nlohmann/json.hpp>

namespace supermodal
{
namespace
{

using nlohmann::json;

constexpr int k_float = 5126;
constexpr int k_uint = 5125;
constexpr int k_array_buffer = 34962;
constexpr int k_element_array_buffer = 34963;
constexpr int k_triangles = 4;

class GlbBuilder
{
  public:
    json views = json::array();
    json accessors = json::array();
    std::vector<uint8_t> bin;

    /// A float accessor of `count` elements of `components` each ("SCALAR", "VEC3", "VEC4"), with min
    /// and max (required for POSITION and animation inputs, harmless elsewhere).
    int add_floats(const std::vector<float>& v, int components, const char* type, int target)
    {
        const size_t count = v.size() / static_cast<size_t>(components);
        std::vector<float> lo(components, std::numeric_limits<float>::infinity());
        std::vector<float> hi(components, -std::numeric_limits<float>::infinity());
        for (size_t i = 0; i < v.size(); ++i) {
            const size_t c = i % static_cast<size_t>(components);
            lo[c] = std::min(lo[c], v[i]);
            hi[c] = std::max(hi[c], v[i]);
        }
        json acc = {{"bufferView", add_view(v.data(), v.size() * sizeof(float), target)},
                    {"componentType", k_float},
                    {"count", count},
                    {"type", type}};
        if (count > 0) {
            acc["min"] = lo;
            acc["max"] = hi;
        }
        accessors.push_back(std::move(acc));
        return static_cast<int>(accessors.size()) - 1;
    }

    int add_indices(const std::vector<uint32_t>& idx)
    {
        accessors.push_back({{"bufferView", add_view(idx.data(), idx.size() * 4, k_element_array_buffer)},
                             {"componentType", k_uint},
                             {"count", idx.size()},
                             {"type", "SCALAR"}});
        return static_cast<int>(accessors.size()) - 1;
    }

    /// An image's bytes as a bufferView (no target, as the specification wants for images).
    int add_image_view(const std::vector<uint8_t>& bytes) { return add_view(bytes.data(), bytes.size(), 0); }

  private:
    int add_view(const void* data, size_t bytes, int target)
    {
        bin.resize((bin.size() + 3) / 4 * 4, 0); // accessors need offsets aligned to their component
        const size_t offset = bin.size();
        bin.resize(offset + bytes);
        if (bytes > 0)
            std::memcpy(bin.data() + offset, data, bytes);
        json view = {{"buffer", 0}, {"byteOffset", offset}, {"byteLength", bytes}};
        if (target != 0)
            view["target"] = target;
        views.push_back(std::move(view));
        return static_cast<int>(views.size()) - 1;
    }
};

std::vector<float> flatten(const std::vector<Vec3>& v)
{
    std::vector<float> out;
    out.reserve(v.size() * 3);
    for (const Vec3& p : v)
        for (double c : {p.x, p.y, p.z})
            out.push_back(static_cast<float>(c));
    return out;
}

// Every value must be a finite float: a double cast out of float range is undefined behaviour.
bool fits(double x)
{
    return std::isfinite(x) && std::fabs(x) <= static_cast<double>(std::numeric_limits<float>::max());
}
bool fits(const Vec3& v)
{
    return fits(v.x) && fits(v.y) && fits(v.z);
}
bool all_fit(const std::vector<Vec3>& v)
{
    for (const Vec3& p : v)
        if (!fits(p))
            return false;
    return true;
}

Status check_look(const ExportBody& b)
{
    const MeshLook& look = b.look;
    const std::string where = "body " + b.name;
    if (!look.texcoords.empty() && look.texcoords.size() != 2 * b.mesh.positions.size())
        return Error{"", where, "expected 2 texture coordinates per vertex"};
    if (look.materials.empty() != look.triangle_materials.empty() ||
        (!look.materials.empty() && look.triangle_materials.size() * 3 != b.mesh.indices.size()))
        return Error{"", where, "expected a material index per triangle, and materials for them"};
    for (uint32_t m : look.triangle_materials)
        if (m >= look.materials.size())
            return Error{"", where, "material index " + std::to_string(m) + " past the materials"};
    for (double c : {b.base_color.x, b.base_color.y, b.base_color.z})
        if (!(c >= 0.0 && c <= 1.0))
            return Error{"", where, "expected base_color values in [0, 1]"};
    for (const MeshMaterial& m : look.materials)
        for (double c : m.base_color)
            if (!(c >= 0.0 && c <= 1.0))
                return Error{"", where + " material " + m.name, "expected base colour values in [0, 1]"};
    return {};
}

Status check(const ExportRecording& rec)
{
    const size_t frames = rec.times.size();
    if (frames == 0 || rec.bodies.empty())
        return Error{"", "", "nothing to export: no samples or no bodies"};
    for (size_t i = 0; i < frames; ++i)
        if (!fits(rec.times[i]) || (i > 0 && !(rec.times[i] > rec.times[i - 1])))
            return Error{"", "times", "expected finite, increasing sample times"};
    for (const ExportBody& b : rec.bodies) {
        const size_t n = b.mesh.positions.size(), r = b.mode_displacements.size();
        if (n == 0 || b.mesh.normals.size() != n || b.mesh.indices.empty() || b.mesh.indices.size() % 3 != 0)
            return Error{"", "body " + b.name, "expected a non-empty triangle mesh with a normal per vertex"};
        for (uint32_t i : b.mesh.indices)
            if (i >= n)
                return Error{"", "body " + b.name,
                             "triangle index " + std::to_string(i) + " past the vertices"};
        for (const std::vector<Vec3>& d : b.mode_displacements)
            if (d.size() != n)
                return Error{"", "body " + b.name, "expected one displacement per vertex in every mode"};
        if (b.positions.size() != frames || b.orientations.size() != frames ||
            b.amplitudes.size() != frames * r)
            return Error{"", "body " + b.name, "expected one pose and r amplitudes per sample"};
        bool ok = all_fit(b.mesh.positions) && all_fit(b.mesh.normals) && all_fit(b.positions);
        for (const std::vector<Vec3>& d : b.mode_displacements)
            ok = ok && all_fit(d);
        for (const Quat& q : b.orientations)
            ok = ok && fits(q.w) && fits(q.x) && fits(q.y) && fits(q.z);
        for (double a : b.amplitudes)
            ok = ok && fits(a);
        for (double t : b.look.texcoords)
            ok = ok && fits(t);
        if (!ok || !fits(b.base_color))
            return Error{"", "body " + b.name,
                         "a value is not finite or does not fit a 32-bit float (|x| > 3.4e38)"};
        if (Status s = check_look(b); !s)
            return s;
    }
    return {};
}

// The glTF materials, images and textures; each image file is embedded once.
struct Materials {
    json materials = json::array(), images = json::array(), textures = json::array();
    std::map<std::string, int> texture_of; // image path → texture index
};

// The texture of image file `path`, embedded on first use.
Result<int> texture(GlbBuilder& g, Materials& m, const std::string& path)
{
    if (const auto it = m.texture_of.find(path); it != m.texture_of.end())
        return it->second;
    std::ifstream in(path, std::ios::binary);
    if (!in)
        return Error{"", "texture " + path, "cannot open the image"};
    const std::vector<uint8_t> bytes{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
    // glTF allows PNG and JPEG; tell them by their signatures, not the file name.
    const bool png =
        bytes.size() > 8 && bytes[0] == 0x89 && bytes[1] == 'P' && bytes[2] == 'N' && bytes[3] == 'G';
    const bool jpeg = bytes.size() > 3 && bytes[0] == 0xFF && bytes[1] == 0xD8 && bytes[2] == 0xFF;
    if (!png && !jpeg)
        return Error{"", "texture " + path, "expected a PNG or JPEG image"};
    m.images.push_back(
        {{"bufferView", g.add_image_view(bytes)}, {"mimeType", png ? "image/png" : "image/jpeg"}});
    m.textures.push_back({{"source", m.images.size() - 1}});
    return m.texture_of[path] = static_cast<int>(m.textures.size()) - 1;
}

json material(const std::string& name, const std::array<double, 4>& rgba, int tex)
{
    json pbr = {{"baseColorFactor", rgba}, {"metallicFactor", 0.0}, {"roughnessFactor", 1.0}};
    if (tex >= 0)
        pbr["baseColorTexture"] = {{"index", tex}};
    json out = {{"name", name}, {"pbrMetallicRoughness", std::move(pbr)}};
    if (rgba[3] < 1.0)
        out["alphaMode"] = "BLEND";
    return out;
}

// The body's materials as glTF material indices: the look's (textures only with texture coordinates,
// which they need), or one of its base colour.
Result<std::vector<int>> body_materials(GlbBuilder& g, Materials& m, const ExportBody& b)
{
    std::vector<int> out;
    if (b.look.materials.empty()) {
        m.materials.push_back(material(b.name, {b.base_color.x, b.base_color.y, b.base_color.z, 1.0}, -1));
        out.push_back(static_cast<int>(m.materials.size()) - 1);
        return out;
    }
    for (const MeshMaterial& mat : b.look.materials) {
        int tex = -1;
        if (!mat.base_color_texture.empty() && !b.look.texcoords.empty()) {
            Result<int> t = texture(g, m, mat.base_color_texture);
            if (!t)
                return Error{"", "body " + b.name + " material " + mat.name + " " + t.error().where,
                             t.error().what};
            tex = *t;
        }
        m.materials.push_back(material(mat.name, mat.base_color, tex));
        out.push_back(static_cast<int>(m.materials.size()) - 1);
    }
    return out;
}

// (u, v) per vertex with glTF's v, which runs down the image.
std::vector<float> gltf_texcoords(const std::vector<double>& uv)
{
    std::vector<float> out(uv.size());
    for (size_t i = 0; i + 1 < uv.size(); i += 2) {
        out[i] = static_cast<float>(uv[i]);
        out[i + 1] = static_cast<float>(1.0 - uv[i + 1]);
    }
    return out;
}

// The body's triangles split by material: one index list per entry of `materials`.
std::vector<std::vector<uint32_t>> indices_by_material(const ExportBody& b, size_t materials)
{
    std::vector<std::vector<uint32_t>> out(materials);
    if (b.look.triangle_materials.empty()) {
        out[0] = b.mesh.indices;
        return out;
    }
    for (size_t t = 0; t < b.look.triangle_materials.size(); ++t) {
        std::vector<uint32_t>& dst = out[b.look.triangle_materials[t]];
        dst.insert(dst.end(), b.mesh.indices.begin() + static_cast<long>(3 * t),
                   b.mesh.indices.begin() + static_cast<long>(3 * t + 3));
    }
    return out;
}

// The body's mesh: a triangle primitive per material used, sharing the vertex accessors, with a morph
// target per mode (named after its frequency).
json body_mesh(GlbBuilder& g, const ExportBody& b, const std::vector<int>& materials)
{
    const size_t r = b.mode_displacements.size();
    json attributes = {{"POSITION", g.add_floats(flatten(b.mesh.positions), 3, "VEC3", k_array_buffer)},
                       {"NORMAL", g.add_floats(flatten(b.mesh.normals), 3, "VEC3", k_array_buffer)}};
    if (!b.look.texcoords.empty())
        attributes["TEXCOORD_0"] = g.add_floats(gltf_texcoords(b.look.texcoords), 2, "VEC2", k_array_buffer);
    json targets = json::array(), names = json::array();
    for (size_t k = 0; k < r; ++k) {
        targets.push_back(
            {{"POSITION", g.add_floats(flatten(b.mode_displacements[k]), 3, "VEC3", k_array_buffer)}});
        char name[64];
        std::snprintf(name, sizeof name, "mode_%zu_%.4gHz", k,
                      k < b.frequencies_hz.size() ? b.frequencies_hz[k] : 0.0);
        names.push_back(name);
    }
    json primitives = json::array();
    const std::vector<std::vector<uint32_t>> parts = indices_by_material(b, materials.size());
    for (size_t m = 0; m < parts.size(); ++m) {
        if (parts[m].empty())
            continue;
        json prim = {{"attributes", attributes},
                     {"indices", g.add_indices(parts[m])},
                     {"material", materials[m]},
                     {"mode", k_triangles}};
        if (r > 0)
            prim["targets"] = targets;
        primitives.push_back(std::move(prim));
    }
    json mesh = {{"name", b.name}};
    if (r > 0) {
        mesh["weights"] = std::vector<double>(r, 0.0);
        mesh["extras"] = {{"targetNames", std::move(names)}}; // the de-facto convention for names
    }
    mesh["primitives"] = std::move(primitives);
    return mesh;
}

// The animation's samplers and channels over the sample times (accessor time_acc).
struct Animation {
    int time_acc = 0;
    json samplers = json::array();
    json channels = json::array();
};

// Body bi's node at the first sample, and its animation: translation, rotation and mode weights.
json body_node(GlbBuilder& g, const ExportBody& b, size_t bi, Animation& anim)
{
    const size_t r = b.mode_displacements.size();
    std::vector<float> translation = flatten(b.positions), rotation;
    rotation.reserve(b.orientations.size() * 4);
    for (const Quat& q : b.orientations) // glTF order: x, y, z, w
        for (double c : {q.x, q.y, q.z, q.w})
            rotation.push_back(static_cast<float>(c));
    json node = {{"name", b.name},
                 {"mesh", bi},
                 {"translation", {translation[0], translation[1], translation[2]}},
                 {"rotation", {rotation[0], rotation[1], rotation[2], rotation[3]}}};
    const auto channel = [&](int output, const char* path) {
        anim.samplers.push_back({{"input", anim.time_acc}, {"output", output}, {"interpolation", "LINEAR"}});
        anim.channels.push_back(
            {{"sampler", anim.samplers.size() - 1}, {"target", {{"node", bi}, {"path", path}}}});
    };
    channel(g.add_floats(translation, 3, "VEC3", 0), "translation");
    channel(g.add_floats(rotation, 4, "VEC4", 0), "rotation");
    if (r > 0) {
        // Weights output: frames × r scalars, frame-major, as the specification lays them out.
        std::vector<float> weights(b.amplitudes.begin(), b.amplitudes.end());
        channel(g.add_floats(weights, 1, "SCALAR", 0), "weights");
        node["weights"] = std::vector<float>(weights.begin(), weights.begin() + static_cast<long>(r));
    }
    return node;
}

// The GLB container: header, JSON chunk (padded with spaces), BIN chunk (padded with zeros).
Result<std::vector<uint8_t>> glb_container(std::string text, std::vector<uint8_t> bin)
{
    text.resize((text.size() + 3) / 4 * 4, ' ');
    bin.resize((bin.size() + 3) / 4 * 4, 0);
    const auto u32 = [](std::vector<uint8_t>& out, uint32_t v) {
        for (int i = 0; i < 4; ++i) // little endian, as the specification wants
            out.push_back(static_cast<uint8_t>(v >> (8 * i)));
    };
    const size_t total = 12 + 8 + text.size() + 8 + bin.size();
    if (total > std::numeric_limits<uint32_t>::max())
        return Error{"", "", "the export is over 4 GiB, the GLB limit: record fewer seconds or frames"};
    std::vector<uint8_t> out;
    out.reserve(total);
    u32(out, 0x46546C67); // "glTF"
    u32(out, 2);
    u32(out, static_cast<uint32_t>(total));
    u32(out, static_cast<uint32_t>(text.size()));
    u32(out, 0x4E4F534A); // "JSON"
    out.insert(out.end(), text.begin(), text.end());
    u32(out, static_cast<uint32_t>(bin.size()));
    u32(out, 0x004E4942); // "BIN\0"
    out.insert(out.end(), bin.begin(), bin.end());
    return out;
}

} // namespace

Result<std::vector<uint8_t>> glb_from_recording(const ExportRecording& rec)
{
    if (Status s = check(rec); !s)
        return s.error();
    GlbBuilder g;
    json nodes = json::array(), meshes = json::array();
    Animation anim;
    std::vector<float> times(rec.times.begin(), rec.times.end());
    anim.time_acc = g.add_floats(times, 1, "SCALAR", 0);
    Materials materials;
    for (size_t bi = 0; bi < rec.bodies.size(); ++bi) {
        Result<std::vector<int>> mats = body_materials(g, materials, rec.bodies[bi]);
        if (!mats)
            return mats.error();
        meshes.push_back(body_mesh(g, rec.bodies[bi], *mats));
        nodes.push_back(body_node(g, rec.bodies[bi], bi, anim));
    }
    json root_nodes = json::array();
    for (size_t i = 0; i < nodes.size(); ++i)
        root_nodes.push_back(i);
    json doc = {
        {"asset", {{"version", "2.0"}, {"generator", "supermodal export"}}},
        {"scene", 0},
        {"scenes", json::array({{{"nodes", root_nodes}}})},
        {"nodes", nodes},
        {"meshes", meshes},
        {"animations",
         json::array({{{"name", "simulation"}, {"samplers", anim.samplers}, {"channels", anim.channels}}})},
        {"buffers", json::array({{{"byteLength", g.bin.size()}}})},
        {"bufferViews", g.views},
        {"accessors", g.accessors},
        {"materials", materials.materials},
    };
    if (!materials.images.empty()) {
        doc["images"] = materials.images;
        doc["textures"] = materials.textures;
    }
    // Body names come from the user: replace invalid UTF-8 rather than throw.
    return glb_container(doc.dump(-1, ' ', false, json::error_handler_t::replace), std::move(g.bin));
}

Status write_glb(const ExportRecording& rec, const std::string& path)
{
    Result<std::vector<uint8_t>> bytes = glb_from_recording(rec);
    if (!bytes)
        return Error{path, bytes.error().where, bytes.error().what};
    return write_file_atomically(path, bytes->data(), bytes->size());
}

} // namespace supermodal
