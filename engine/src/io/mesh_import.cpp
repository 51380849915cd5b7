// SPDX-License-Identifier: MIT
// Mesh import through assimp: every mesh instance of the node tree is merged into one TriangleMesh,
// then scaled to metres and turned so the file's up axis becomes +Y. assimp's own unit and axis
// post-steps are not used: the file's metadata is read here so the choice is visible (ImportedMesh).
#include "io/mesh_weld.h"
#include "io/ply_header.h"
#include "supermodal/mesh_io.h"

#include <algorithm>
#include <assimp/Importer.hpp>
#include <assimp/config.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <optional>

namespace supermodal
{
namespace
{

std::optional<double> metadata_number(const aiMetadata* meta, const char* key)
{
    if (meta == nullptr)
        return std::nullopt;
    for (unsigned i = 0; i < meta->mNumProperties; ++i) {
        if (std::string(meta->mKeys[i].C_Str()) != key)
            continue;
        const aiMetadataEntry& e = meta->mValues[i];
        switch (e.mType) {
        case AI_INT32:
            return double(*static_cast<const int32_t*>(e.mData));
        case AI_UINT64:
            return double(*static_cast<const uint64_t*>(e.mData));
        case AI_FLOAT:
            return double(*static_cast<const float*>(e.mData));
        case AI_DOUBLE:
            return *static_cast<const double*>(e.mData);
        default:
            return std::nullopt;
        }
    }
    return std::nullopt;
}

/// FBX stores its up axis as an index (0 x, 1 y, 2 z) and a sign.
UpAxis fbx_up_axis(const aiScene& scene)
{
    const auto axis = metadata_number(scene.mMetaData, "UpAxis");
    const auto sign = metadata_number(scene.mMetaData, "UpAxisSign");
    if (!axis)
        return UpAxis::PosY;
    const bool negative = sign && *sign < 0.0;
    switch (int(*axis)) {
    case 0:
        return negative ? UpAxis::NegX : UpAxis::PosX;
    case 2:
        return negative ? UpAxis::NegZ : UpAxis::PosZ;
    default:
        return negative ? UpAxis::NegY : UpAxis::PosY;
    }
}

/// The proper rotation taking the file's up axis to +Y (a quarter or half turn, exact in floating point).
Mat3 up_rotation(UpAxis up)
{
    Mat3 r = Mat3::identity();
    auto set = [&r](Vec3 r0, Vec3 r1, Vec3 r2) {
        for (int j = 0; j < 3; ++j) {
            r.m[0][j] = r0[j];
            r.m[1][j] = r1[j];
            r.m[2][j] = r2[j];
        }
    };
    switch (up) {
    case UpAxis::PosZ: // (x, y, z) → (x, z, −y)
        set({1, 0, 0}, {0, 0, 1}, {0, -1, 0});
        break;
    case UpAxis::NegZ: // (x, y, z) → (x, −z, y)
        set({1, 0, 0}, {0, 0, -1}, {0, 1, 0});
        break;
    case UpAxis::PosX: // (x, y, z) → (−y, x, z)
        set({0, -1, 0}, {1, 0, 0}, {0, 0, 1});
        break;
    case UpAxis::NegX: // (x, y, z) → (y, −x, z)
        set({0, 1, 0}, {-1, 0, 0}, {0, 0, 1});
        break;
    case UpAxis::NegY: // half turn about x
        set({1, 0, 0}, {0, -1, 0}, {0, 0, -1});
        break;
    default:
        break;
    }
    return r;
}

struct Gather {
    TriangleMesh mesh;
    int instances = 0;
    bool finite = true;
    bool look = false;              // ImportDef::keep_look
    std::filesystem::path folder;   // the mesh file's, for texture paths
    MeshLook looks;                 // texcoords, materials, triangle_materials
    bool any_texcoords = false;     // texcoords are kept only when some mesh has them
    std::vector<int> material_slot; // assimp material index → looks.materials index, or −1
};

/// The look's index of assimp material `m`, added on first use; −1 for assimp's stand-in material
/// (a file that names none), so such a mesh takes its colour from elsewhere.
int material_slot(const aiScene& scene, unsigned m, Gather& out)
{
    if (m >= scene.mNumMaterials)
        return -1;
    out.material_slot.resize(scene.mNumMaterials, -2); // −2: not looked at yet
    if (out.material_slot[m] != -2)
        return out.material_slot[m];
    const aiMaterial& src = *scene.mMaterials[m];
    aiString name;
    src.Get(AI_MATKEY_NAME, name);
    if (std::string(name.C_Str()) == AI_DEFAULT_MATERIAL_NAME)
        return out.material_slot[m] = -1;
    MeshMaterial mat;
    mat.name = name.C_Str();
    aiColor4D c(1, 1, 1, 1);
    if (src.Get(AI_MATKEY_BASE_COLOR, c) != AI_SUCCESS) {
        aiColor3D d(1, 1, 1);
        src.Get(AI_MATKEY_COLOR_DIFFUSE, d);
        float opacity = 1.0f;
        src.Get(AI_MATKEY_OPACITY, opacity);
        c = aiColor4D(d.r, d.g, d.b, opacity);
    }
    mat.base_color = {c.r, c.g, c.b, c.a};
    for (aiTextureType type : {aiTextureType_BASE_COLOR, aiTextureType_DIFFUSE}) {
        aiString file;
        if (src.GetTextureCount(type) == 0 || src.GetTexture(type, 0, &file) != AI_SUCCESS)
            continue;
        if (file.length > 0 && file.C_Str()[0] != '*') // "*N": embedded in the file, not read
            mat.base_color_texture = (out.folder / file.C_Str()).lexically_normal().string();
        break;
    }
    out.looks.materials.push_back(std::move(mat));
    return out.material_slot[m] = static_cast<int>(out.looks.materials.size()) - 1;
}

/// The look of one mesh instance: its (u, v) per vertex and its material per triangle.
void gather_look(const aiScene& scene, const aiMesh& mesh, Gather& out)
{
    const aiVector3D* uv = mesh.mTextureCoords[0];
    out.any_texcoords = out.any_texcoords || uv != nullptr;
    for (unsigned v = 0; v < mesh.mNumVertices; ++v)
        out.looks.texcoords.insert(out.looks.texcoords.end(),
                                   {uv ? double(uv[v].x) : 0.0, uv ? double(uv[v].y) : 0.0});
    const int slot = material_slot(scene, mesh.mMaterialIndex, out);
    for (unsigned f = 0; f < mesh.mNumFaces; ++f) {
        const aiFace& face = mesh.mFaces[f];
        if (face.mNumIndices == 3 && face.mIndices[0] < mesh.mNumVertices &&
            face.mIndices[1] < mesh.mNumVertices && face.mIndices[2] < mesh.mNumVertices)
            out.looks.triangle_materials.push_back(slot < 0 ? UINT32_MAX : uint32_t(slot));
    }
}

/// Appends every mesh of node and its children with the accumulated node transform.
void gather(const aiScene& scene, const aiNode& node, const aiMatrix4x4& parent, Gather& out)
{
    const aiMatrix4x4 transform = parent * node.mTransformation;
    aiMatrix3x3 normal_matrix(transform);
    normal_matrix.Inverse().Transpose();
    const bool mirrored = transform.Determinant() < 0.0f; // a mirror flips the winding
    for (unsigned m = 0; m < node.mNumMeshes; ++m) {
        const aiMesh& mesh = *scene.mMeshes[node.mMeshes[m]];
        if (!(mesh.mPrimitiveTypes & aiPrimitiveType_TRIANGLE))
            continue;
        const auto base = uint32_t(out.mesh.positions.size());
        for (unsigned v = 0; v < mesh.mNumVertices; ++v) {
            const aiVector3D p = transform * mesh.mVertices[v];
            out.mesh.positions.push_back({p.x, p.y, p.z});
            out.finite = out.finite && std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z);
            aiVector3D n = mesh.mNormals ? normal_matrix * mesh.mNormals[v] : aiVector3D(0, 0, 0);
            out.mesh.normals.push_back(normalized(Vec3{n.x, n.y, n.z}));
        }
        for (unsigned f = 0; f < mesh.mNumFaces; ++f) {
            const aiFace& face = mesh.mFaces[f];
            if (face.mNumIndices != 3)
                continue;
            const uint32_t a = face.mIndices[0], b = face.mIndices[1], c = face.mIndices[2];
            if (a >= mesh.mNumVertices || b >= mesh.mNumVertices || c >= mesh.mNumVertices)
                continue; // a corrupt file; validation below normally catches it first
            out.mesh.indices.insert(out.mesh.indices.end(),
                                    {base + a, base + (mirrored ? c : b), base + (mirrored ? b : c)});
        }
        if (out.look)
            gather_look(scene, mesh, out);
        ++out.instances;
    }
    for (unsigned c = 0; c < node.mNumChildren; ++c)
        gather(scene, *node.mChildren[c], transform, out);
}

Error fail(const std::string& path, std::string what)
{
    return Error{path, "", std::move(what)};
}

} // namespace

ImportDef default_import_def()
{
    return {};
}

const char* up_axis_name(UpAxis axis)
{
    switch (axis) {
    case UpAxis::FromFile:
        return "from_file";
    case UpAxis::PosX:
        return "+x";
    case UpAxis::PosY:
        return "+y";
    case UpAxis::PosZ:
        return "+z";
    case UpAxis::NegX:
        return "-x";
    case UpAxis::NegY:
        return "-y";
    case UpAxis::NegZ:
        return "-z";
    }
    return "unknown";
}

bool parse_up_axis(const std::string& name, UpAxis& out)
{
    for (UpAxis a : {UpAxis::FromFile, UpAxis::PosX, UpAxis::PosY, UpAxis::PosZ, UpAxis::NegX, UpAxis::NegY,
                     UpAxis::NegZ})
        if (name == up_axis_name(a) || (name.size() == 1 && "+" + name == up_axis_name(a))) {
            out = a;
            return true;
        }
    return false;
}

namespace
{
bool has_ply_extension(const std::string& path)
{
    std::string ext = std::filesystem::path(path).extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return char(std::tolower(c)); });
    return ext == ".ply";
}

// Sets each mesh's primitive-type flags from its faces (1, 2, 3 or more indices); false when a face has
// no index at all, which nothing downstream handles (assimp's triangulation asserts on such a mesh
// whatever its flags say).
bool recompute_primitive_types(aiScene& scene)
{
    for (unsigned m = 0; m < scene.mNumMeshes; ++m) {
        aiMesh* mesh = scene.mMeshes[m];
        if (mesh == nullptr)
            continue;
        unsigned types = 0;
        for (unsigned f = 0; f < mesh->mNumFaces; ++f) {
            const unsigned n = mesh->mFaces[f].mNumIndices;
            if (n == 0)
                return false;
            types |= n == 1   ? aiPrimitiveType_POINT
                     : n == 2 ? aiPrimitiveType_LINE
                     : n == 3 ? aiPrimitiveType_TRIANGLE
                              : aiPrimitiveType_POLYGON;
        }
        mesh->mPrimitiveTypes = types;
    }
    return true;
}
// The checks assimp does not make, or makes with a vaguer message: the scale, the file itself and a
// PLY header.
Status check_mesh_file(const std::string& path, const ImportDef& def)
{
    if (!std::isfinite(def.scale) || def.scale < 0.0)
        return fail(path, "import scale must be finite and >= 0 (0: from the file), found " +
                              std::to_string(def.scale));
    namespace fs = std::filesystem;
    std::error_code ec;
    if (!fs::exists(path, ec))
        return fail(path, "file not found");
    if (fs::is_directory(path, ec))
        return fail(path, "is a directory, expected a mesh file");
    if (!std::ifstream(path, std::ios::binary))
        return fail(path, "cannot open for reading");
    if (fs::file_size(path, ec) == 0)
        return fail(path, "file is empty");
    // By extension or content: assimp picks its PLY reader by either.
    if (std::ifstream in(path, std::ios::binary); looks_like_ply(in) || has_ply_extension(path)) {
        in.seekg(0);
        if (const std::optional<std::string> problem = ply_header_problem(in))
            return fail(path, *problem);
    }
    return {};
}

// The sort step leaves each mesh one primitive type; gather() takes the triangle meshes only. (Asking
// assimp to drop points and lines instead fails a lines-only file with a vaguer message.)
// Validation rejects out-of-range indices and similar corruption before anything reads them.
// Read and validate first, then post-process: Debian's assimp 5.2 has its asserts on, and its
// triangulation aborts the process when a reader's primitive-type flags disagree with the faces
// (a malformed PLY did, found by tests/fuzz/mesh_fuzz.cpp); the flags are recomputed in between.
Result<const aiScene*> read_scene(Assimp::Importer& importer, const std::string& path, const std::string& ext,
                                  const ImportDef& def)
{
    const aiScene* scene = importer.ReadFile(path, aiProcess_ValidateDataStructure);
    const std::string cannot =
        std::string("cannot read mesh (") + (ext.empty() ? "no extension" : ext) + "): ";
    if (scene == nullptr)
        return fail(path, cannot + importer.GetErrorString());
    if (!recompute_primitive_types(const_cast<aiScene&>(*scene))) // the importer's own scene, not shared
        return fail(path, cannot + "a face has no vertex indices (malformed file)");
    unsigned flags = aiProcess_Triangulate | aiProcess_SortByPType;
    flags |= def.weld_vertices ? aiProcess_JoinIdenticalVertices : aiProcess_GenSmoothNormals;
    scene = importer.ApplyPostProcessing(flags);
    if (scene == nullptr)
        return fail(path, cannot + importer.GetErrorString());
    if (scene->mRootNode == nullptr)
        return fail(path, "the file has no node tree");
    return scene;
}

// Texture coordinates only when some mesh had them; materials only when every triangle has one (a
// mesh with assimp's stand-in material among named ones takes a plain white one).
void finish_look(Gather& g)
{
    if (!g.any_texcoords)
        g.looks.texcoords.clear();
    if (g.looks.materials.empty()) {
        g.looks.triangle_materials.clear();
        return;
    }
    uint32_t white = UINT32_MAX;
    for (uint32_t& m : g.looks.triangle_materials)
        if (m == UINT32_MAX) {
            if (white == UINT32_MAX) {
                g.looks.materials.push_back({"default", {1.0, 1.0, 1.0, 1.0}, ""});
                white = static_cast<uint32_t>(g.looks.materials.size()) - 1;
            }
            m = white;
        }
}

// The gathered triangles in metres, Y up, welded when asked for.
Result<ImportedMesh> to_metres_y_up(const std::string& path, const ImportDef& def, const aiScene& scene,
                                    const std::string& ext, Gather& g)
{
    ImportedMesh out;
    out.format = ext;
    out.source_meshes = g.instances;
    const bool fbx = ext == "fbx";
    if (def.scale > 0.0)
        out.scale = def.scale;
    else if (fbx) // FBX units are centimetres per file unit
        out.scale = 0.01 * metadata_number(scene.mMetaData, "UnitScaleFactor").value_or(1.0);
    if (!(std::isfinite(out.scale) && out.scale > 0.0))
        return fail(path, "the file's unit scale is not a positive number");
    out.up_axis = def.up_axis != UpAxis::FromFile ? def.up_axis : (fbx ? fbx_up_axis(scene) : UpAxis::PosY);

    const Mat3 r = up_rotation(out.up_axis);
    for (Vec3& p : g.mesh.positions)
        p = r * p * out.scale;
    for (Vec3& n : g.mesh.normals)
        n = r * n;
    if (g.look)
        finish_look(g);
    out.mesh = def.weld_vertices ? weld_mesh(g.mesh, g.look ? &g.looks : nullptr) : std::move(g.mesh);
    out.look = std::move(g.looks);
    if (out.mesh.indices.empty())
        return fail(path, "no triangles with three distinct vertices");
    return out;
}

} // namespace

Result<ImportedMesh> import_mesh(const std::string& path, const ImportDef& def)
{
    if (Status status = check_mesh_file(path, def); !status)
        return status.error();
    std::string ext = std::filesystem::path(path).extension().string();
    if (!ext.empty())
        ext.erase(0, 1);
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return char(std::tolower(c)); });

    Assimp::Importer importer;
    const Result<const aiScene*> scene = read_scene(importer, path, ext, def);
    if (!scene)
        return scene.error();
    Gather g;
    g.look = def.keep_look;
    g.folder = std::filesystem::path(path).parent_path();
    gather(**scene, *(*scene)->mRootNode, aiMatrix4x4(), g);
    if (!g.finite)
        return fail(path, "a vertex coordinate is not finite (NaN or Inf)");
    if (g.mesh.indices.empty())
        return fail(path, "no triangles (the file holds " + std::to_string((*scene)->mNumMeshes) +
                              " meshes, none with triangle faces)");
    return to_metres_y_up(path, def, **scene, ext, g);
}

} // namespace supermodal
