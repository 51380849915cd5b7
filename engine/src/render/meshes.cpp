// SPDX-License-Identifier: MIT
#include "render/meshes.h"

#include <algorithm>
#include <cstring>

namespace supermodal::render
{
namespace
{

void append(std::string& key, const void* data, size_t size)
{
    key.append(static_cast<const char*>(data), size);
}
void append(std::string& key, double v)
{
    append(key, &v, sizeof v);
}

void interleave(std::span<const Vec3> p, std::span<const Vec3> n, std::vector<float>& out)
{
    out.resize(p.size() * 6);
    for (size_t i = 0; i < p.size(); ++i) {
        float* v = out.data() + i * 6;
        v[0] = static_cast<float>(p[i].x);
        v[1] = static_cast<float>(p[i].y);
        v[2] = static_cast<float>(p[i].z);
        v[3] = static_cast<float>(n[i].x);
        v[4] = static_cast<float>(n[i].y);
        v[5] = static_cast<float>(n[i].z);
    }
}

// Vertex layout of every mesh VAO: location 0 position, 1 normal, floats, interleaved.
void set_layout()
{
    glEnableVertexAttribArray(0);
    glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 6 * sizeof(float), nullptr);
    glEnableVertexAttribArray(1);
    glVertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, 6 * sizeof(float),
                          reinterpret_cast<const void*>(3 * sizeof(float)));
}

} // namespace

std::string shape_key(const ShapeDef& s)
{
    std::string key;
    append(key, &s.type, sizeof s.type);
    for (double v : {s.radii.x, s.radii.y, s.radii.z, s.epsilon1, s.epsilon2, s.taper.kx, s.taper.ky,
                     s.bend.curvature, s.bend.angle})
        append(key, v);
    for (const HyperquadricTerm& t : s.terms)
        for (double v : {t.normal.x, t.normal.y, t.normal.z, t.offset, t.exponent})
            append(key, v);
    return key;
}

void face_normals_per_vertex(std::span<const Vec3> p, std::span<const uint32_t> idx, std::vector<Vec3>& out)
{
    out.assign(p.size(), Vec3{});
    for (size_t t = 0; t + 2 < idx.size(); t += 3) {
        // The cross product's length is twice the area: summing it weights by area.
        const Vec3 n = cross(p[idx[t + 1]] - p[idx[t]], p[idx[t + 2]] - p[idx[t]]);
        for (size_t k = 0; k < 3; ++k)
            out[idx[t + k]] += n;
    }
    for (Vec3& n : out) {
        const double len = length(n);
        n = len > 0.0 ? n / len : Vec3{0, 0, 1};
    }
}

MeshCache::~MeshCache()
{
    for (auto& [key, m] : m_meshes) {
        glDeleteVertexArrays(1, &m->vao);
        glDeleteBuffers(1, &m->vbo);
        glDeleteBuffers(1, &m->ibo);
    }
}

const GpuMesh& MeshCache::get(const ShapeDef& shape, int tessellation, MeshSpacing spacing,
                              const std::string& key)
{
    auto it = m_meshes.find(key);
    if (it != m_meshes.end())
        return *it->second;
    return get(tessellate(shape, tessellation, spacing), key);
}

const GpuMesh& MeshCache::get(const TriangleMesh& mesh, const std::string& key)
{
    auto it = m_meshes.find(key);
    if (it != m_meshes.end())
        return *it->second;
    auto m = std::make_unique<GpuMesh>();
    m->mesh = mesh;
    m->bounds = bounds_of(m->mesh.positions);
    face_normals_per_vertex(m->mesh.positions, m->mesh.indices, m->rest_face_normals);
    if (m->mesh.normals.size() != m->mesh.positions.size())
        m->mesh.normals = m->rest_face_normals;
    std::vector<float> vertices;
    interleave(m->mesh.positions, m->mesh.normals, vertices);
    m->index_count = static_cast<GLsizei>(m->mesh.indices.size());
    glGenVertexArrays(1, &m->vao);
    glBindVertexArray(m->vao);
    glGenBuffers(1, &m->vbo);
    glBindBuffer(GL_ARRAY_BUFFER, m->vbo);
    glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(vertices.size() * sizeof(float)), vertices.data(),
                 GL_STATIC_DRAW);
    glGenBuffers(1, &m->ibo);
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, m->ibo);
    glBufferData(GL_ELEMENT_ARRAY_BUFFER, static_cast<GLsizeiptr>(m->mesh.indices.size() * sizeof(uint32_t)),
                 m->mesh.indices.data(), GL_STATIC_DRAW);
    set_layout();
    glBindVertexArray(0);
    return *m_meshes.emplace(key, std::move(m)).first->second;
}

ModalSkin::ModalSkin(const GpuMesh& mesh, const ModalBasis* basis, std::vector<Vec3> rest_offsets)
    : m_mesh(&mesh), m_basis(basis), m_rest_offsets(std::move(rest_offsets)), m_bounds(mesh.bounds)
{
    m_weights.reserve(mesh.mesh.positions.size());
    for (const Vec3& p : mesh.mesh.positions)
        m_weights.push_back(modal_weights(*m_basis, p));
    glGenVertexArrays(1, &m_vao);
    glBindVertexArray(m_vao);
    glGenBuffers(1, &m_vbo);
    glBindBuffer(GL_ARRAY_BUFFER, m_vbo);
    glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(mesh.mesh.positions.size() * 6 * sizeof(float)),
                 nullptr, GL_STREAM_DRAW);
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, mesh.ibo); // shared with the rest mesh
    set_layout();
    glBindVertexArray(0);
}

ModalSkin::~ModalSkin()
{
    glDeleteVertexArrays(1, &m_vao);
    glDeleteBuffers(1, &m_vbo);
}

void ModalSkin::observe(uint64_t step_count, std::span<const double> q, std::vector<Vec3> correction)
{
    m_correction = std::move(correction);
    // Same step: the amplitudes may still have been set by the host; take them, keep the previous.
    // One step on: the last ones become the previous. A jump of several steps (or the first frame)
    // has no previous step to blend from, so both are set to now.
    const bool same = step_count == m_step;
    const bool one_step = m_step != ~uint64_t{0} && step_count == m_step + 1;
    if (one_step)
        m_prev_q = m_cur_q;
    m_cur_q.assign(q.begin(), q.end());
    if ((!same && !one_step) || m_prev_q.size() != m_cur_q.size())
        m_prev_q = m_cur_q;
    m_step = step_count;
}

void ModalSkin::update(double alpha, double scale)
{
    const TriangleMesh& rest = m_mesh->mesh;
    m_q.resize(m_cur_q.size());
    for (size_t k = 0; k < m_q.size(); ++k)
        m_q[k] = scale * ((1.0 - alpha) * m_prev_q[k] + alpha * m_cur_q[k]);
    m_positions.resize(rest.positions.size());
    modal_nodal_displacements(*m_basis, m_q, m_nodal); // the modes once per node, then 20 weights per vertex
    for (size_t n = 0; n < m_correction.size() && n < m_nodal.size(); ++n)
        m_nodal[n] += scale * m_correction[n];
    for (size_t n = 0; n < m_rest_offsets.size() && n < m_nodal.size(); ++n)
        m_nodal[n] += m_rest_offsets[n]; // a remoulded rest shape, not scaled with the deformation
    for (size_t i = 0; i < rest.positions.size(); ++i)
        m_positions[i] = rest.positions[i] + interpolate_nodal(m_weights[i], m_nodal);
    m_bounds = bounds_of(m_positions);
    // Keep the analytic rest normals (sharp superquadric edges stay sharp) and add how much the faces
    // around each vertex turned.
    face_normals_per_vertex(m_positions, rest.indices, m_face_normals);
    for (size_t i = 0; i < m_face_normals.size(); ++i)
        m_face_normals[i] = normalized(rest.normals[i] + m_face_normals[i] - m_mesh->rest_face_normals[i]);
    interleave(m_positions, m_face_normals, m_vertices);
    glBindBuffer(GL_ARRAY_BUFFER, m_vbo);
    glBufferSubData(GL_ARRAY_BUFFER, 0, static_cast<GLsizeiptr>(m_vertices.size() * sizeof(float)),
                    m_vertices.data());
}

} // namespace supermodal::render
