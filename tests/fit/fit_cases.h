// Shared by the fit tests and bench/fit_bench.cpp: posed superquadric meshes with known parameters.
#pragma once

#include "supermodal/geometry.h"

#include <cmath>
#include <random>

namespace supermodal::test
{

/// A shape with its pose: the truth a fit should recover.
struct PosedShape {
    ShapeDef shape;
    Vec3 position{};
    Quat orientation = Quat::identity();
};

/// A random pose: position in [−1, 1]³ m, orientation uniform (normalised Gaussian 4-vector).
inline PosedShape random_pose(const ShapeDef& shape, unsigned seed)
{
    std::mt19937_64 rng(seed);
    std::normal_distribution<double> gauss(0.0, 1.0);
    std::uniform_real_distribution<double> unit(-1.0, 1.0);
    PosedShape s{shape, {unit(rng), unit(rng), unit(rng)}, {}};
    s.orientation = normalized(Quat{gauss(rng), gauss(rng), gauss(rng), gauss(rng)});
    return s;
}

/// tessellate() of the shape moved to its pose: vertices lie exactly on the surface.
inline TriangleMesh posed_mesh(const PosedShape& s, int resolution)
{
    TriangleMesh m = tessellate(s.shape, resolution);
    for (Vec3& p : m.positions)
        p = s.position + rotate(s.orientation, p);
    for (Vec3& n : m.normals)
        n = rotate(s.orientation, n);
    return m;
}

/// Appends b's triangles to a.
inline void append_mesh(TriangleMesh& a, const TriangleMesh& b)
{
    const auto base = uint32_t(a.positions.size());
    a.positions.insert(a.positions.end(), b.positions.begin(), b.positions.end());
    a.normals.insert(a.normals.end(), b.normals.begin(), b.normals.end());
    for (uint32_t i : b.indices)
        a.indices.push_back(base + i);
}

} // namespace supermodal::test
