// SPDX-License-Identifier: MIT
#include "fit/surface_points.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>

namespace supermodal::fit
{
namespace
{

/// The i-th point of the additive recurrence with the plastic number (Roberts' R2 sequence): evenly
/// spread in the unit square and the same on every run, unlike a random generator.
void r2_point(int i, double& u, double& v)
{
    u = std::fmod(0.5 + 0.7548776662466927 * i, 1.0);
    v = std::fmod(0.5 + 0.5698402909980532 * i, 1.0);
}

void normalise(WeightedPoints& data)
{
    double total = 0.0;
    for (double w : data.weights)
        total += w;
    for (double& w : data.weights)
        w /= total;
}

} // namespace

WeightedPoints mesh_surface_points(const TriangleMesh& mesh, int target_count)
{
    double total_area = 0.0;
    for (size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
        const Vec3 &a = mesh.positions[mesh.indices[t]], &b = mesh.positions[mesh.indices[t + 1]],
                   &c = mesh.positions[mesh.indices[t + 2]];
        total_area += 0.5 * length(cross(b - a, c - a));
    }
    WeightedPoints out;
    if (!(total_area > 0.0) || !std::isfinite(total_area))
        return out;
    const double cell = total_area / std::max(target_count, 1); // (spacing)²
    std::vector<double> vertex_area(mesh.positions.size(), 0.0);
    for (size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
        const uint32_t ia = mesh.indices[t], ib = mesh.indices[t + 1], ic = mesh.indices[t + 2];
        const Vec3 &a = mesh.positions[ia], &b = mesh.positions[ib], &c = mesh.positions[ic];
        const double area = 0.5 * length(cross(b - a, c - a));
        // Large triangles (a CAD box has twelve) get interior samples so faces weigh as much as corners;
        // a fine mesh keeps its vertices alone (on a tessellated surface they are exact, the facets not).
        const int interior = area > 4.0 * cell ? int(std::min(area / cell, 1e5)) : 0;
        const double share = area / (interior + 3);
        for (uint32_t v : {ia, ib, ic})
            vertex_area[v] += share;
        for (int i = 0; i < interior; ++i) {
            double u, v;
            r2_point(i, u, v);
            if (u + v > 1.0) { // fold the square onto the triangle
                u = 1.0 - u;
                v = 1.0 - v;
            }
            out.points.push_back(a + u * (b - a) + v * (c - a));
            out.weights.push_back(share);
        }
    }
    for (size_t v = 0; v < mesh.positions.size(); ++v)
        if (vertex_area[v] > 0.0) {
            out.points.push_back(mesh.positions[v]);
            out.weights.push_back(vertex_area[v]);
        }
    normalise(out);
    return out;
}

WeightedPoints thin(const WeightedPoints& data, int max_count)
{
    const size_t n = data.points.size();
    if (max_count <= 0 || n <= size_t(max_count))
        return data;
    WeightedPoints out;
    const double stride = double(n) / max_count;
    for (int i = 0; i < max_count; ++i) {
        const auto k = size_t(i * stride);
        out.points.push_back(data.points[k]);
        out.weights.push_back(data.weights[k]);
    }
    normalise(out);
    return out;
}

Moments moments(const WeightedPoints& data)
{
    Moments m;
    for (size_t i = 0; i < data.points.size(); ++i)
        m.centroid += data.weights[i] * data.points[i];
    Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
    for (size_t i = 0; i < data.points.size(); ++i) {
        const Vec3 d = data.points[i] - m.centroid;
        const Eigen::Vector3d e(d.x, d.y, d.z);
        cov += data.weights[i] * e * e.transpose();
    }
    m.rms_radius = std::sqrt(std::max(cov.trace(), 0.0));
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(cov);
    Eigen::Matrix3d v = eig.eigenvectors().rowwise().reverse(); // largest variance first
    if (eig.info() != Eigen::Success || !v.allFinite())
        v.setIdentity();
    if (v.determinant() < 0.0)
        v.col(2) = -v.col(2);
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            m.axes.m[i][j] = v(i, j);
    return m;
}

} // namespace supermodal::fit
