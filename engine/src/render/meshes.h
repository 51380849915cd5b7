// SPDX-License-Identifier: MIT
// GPU meshes for the renderer: one tessellation per distinct shape (cached), and per modal body a
// "skin" that moves the rest mesh's vertices by the modal field every frame. Internal to render/.
#pragma once

#include "geometry/aabb.h"
#include "supermodal/geometry.h"
#include "supermodal/modal.h"

#include <GLES3/gl3.h>
#include <cstdint>
#include <map>
#include <memory>
#include <span>
#include <string>
#include <vector>

namespace supermodal::render
{

/// A tessellated shape on the GPU (interleaved position + normal floats, shape frame).
struct GpuMesh {
    GLuint vao = 0, vbo = 0, ibo = 0;
    GLsizei index_count = 0;
    TriangleMesh mesh;                   ///< The CPU copy: modal skins start from it.
    std::vector<Vec3> rest_face_normals; ///< Area-weighted face normals averaged per vertex, unit.
    Aabb bounds;                         ///< Of the vertices, shape frame [m].
};

/// Bytes of every ShapeDef field that changes the surface: equal keys, equal surfaces.
[[nodiscard]] std::string shape_key(const ShapeDef& shape);
/// Per vertex: the unit average of the adjacent faces' normals, weighted by area.
void face_normals_per_vertex(std::span<const Vec3> positions, std::span<const uint32_t> indices,
                             std::vector<Vec3>& out);

/// Tessellations keyed by shape_key; a mesh lives as long as the cache.
class MeshCache
{
  public:
    MeshCache() = default;
    ~MeshCache();
    MeshCache(const MeshCache&) = delete;
    MeshCache& operator=(const MeshCache&) = delete;

    /// The mesh of this shape, tessellated and uploaded on first use.
    const GpuMesh& get(const ShapeDef& shape, int tessellation, MeshSpacing spacing, const std::string& key);
    /// A given mesh (shape frame), uploaded on first use of `key`; per-vertex normals are made from
    /// the faces where the mesh has none.
    const GpuMesh& get(const TriangleMesh& mesh, const std::string& key);
    [[nodiscard]] int size() const { return static_cast<int>(m_meshes.size()); }

  private:
    std::map<std::string, std::unique_ptr<GpuMesh>> m_meshes;
};

/// A modal body's deforming copy of a cached mesh.
class ModalSkin
{
  public:
    /// rest_offsets: per lattice node, how far a remoulded body's rest shape moved [m] (empty: none).
    ModalSkin(const GpuMesh& mesh, const ModalBasis* basis, std::vector<Vec3> rest_offsets = {});
    ~ModalSkin();
    ModalSkin(const ModalSkin&) = delete;
    ModalSkin& operator=(const ModalSkin&) = delete;

    /// Records the amplitudes after step `step_count` (the previous ones are kept for blending) and the
    /// static correction per lattice node [m] (empty: none), shown as it is now.
    void observe(uint64_t step_count, std::span<const double> amplitudes, std::vector<Vec3> correction = {});
    /// Moves the vertices by scale × u(q), q blended by alpha between the last two observed steps, and
    /// uploads them; normals turn with the faces around each vertex.
    void update(double alpha, double scale);
    [[nodiscard]] GLuint vao() const { return m_vao; }
    [[nodiscard]] GLsizei index_count() const { return m_mesh->index_count; }
    [[nodiscard]] const ModalBasis* basis() const { return m_basis; }
    /// Of the vertices as the last update() moved them, shape frame [m].
    [[nodiscard]] const Aabb& bounds() const { return m_bounds; }

  private:
    const GpuMesh* m_mesh;
    const ModalBasis* m_basis;             ///< Owned by the world's basis cache.
    std::vector<LatticeWeights> m_weights; ///< Per vertex, computed once.
    std::vector<double> m_prev_q, m_cur_q, m_q;
    std::vector<Vec3> m_nodal;        ///< Per lattice node, this frame: the modes summed once.
    std::vector<Vec3> m_rest_offsets; ///< Per lattice node, the moulded rest shape's offsets [m].
    std::vector<Vec3> m_correction;   ///< Per lattice node, the static correction last observed [m].
    uint64_t m_step = ~uint64_t{0};
    std::vector<Vec3> m_positions, m_face_normals;
    Aabb m_bounds;
    std::vector<float> m_vertices;
    GLuint m_vao = 0, m_vbo = 0;
};

} // namespace supermodal::render
