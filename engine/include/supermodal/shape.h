// SPDX-License-Identifier: MIT
// Shapes a body can have, and their mass properties. A superquadric's own frame follows Barr:
// z is the polar axis, radii (a1, a2, a3) lie along (x, y, z).
#pragma once

#include "supermodal/api.h"
#include "supermodal/math.h"
#include "supermodal/result.h"

#include <cstdint>
#include <vector>

namespace supermodal
{

/// Which kind of shape a ShapeDef describes.
enum class ShapeType : uint8_t {
    Superquadric, ///< Barr superquadric; ε = 1 ellipsoid, ε → 0 box, ε = 2 octahedron, ε > 2 concave.
    Plane,        ///< Half-space {x : normal·x ≤ offset}; static bodies only.
    Hyperquadric, ///< Σ_i |n_i·x + d_i|^γ_i ≤ 1 (Hanson 1988); any number of terms.
};

/// One term |normal·x + offset|^exponent of a hyperquadric, shape frame.
struct HyperquadricTerm {
    Vec3 normal{1, 0, 0};  ///< [1/m]: its length scales the term (a slab of half-width 1/|n| for one term).
    double offset = 0.0;   ///< [-].
    double exponent = 2.0; ///< γ [-], > 0; γ ≥ 1 keeps the term convex.
};

/// Barr taper along the polar axis (z): x, y scale by (1 + k·z/a3).
struct Taper {
    double kx = 0.0; ///< Taper factor along x [-], valid range [-1, 1].
    double ky = 0.0; ///< Taper factor along y [-], valid range [-1, 1].
};

/// Barr bend of the polar axis (z) in the plane at `angle` from x.
struct Bend {
    double curvature = 0.0; ///< Bend curvature [1/m], ≥ 0.
    double angle = 0.0;     ///< Bending-plane angle about z [rad].
};

/// How to make a shape. Start from default_shape_def() and change what differs.
struct ShapeDef {
    ShapeType type = ShapeType::Superquadric;
    Vec3 radii{0.5, 0.5, 0.5};  ///< Superquadric radii a1, a2, a3 [m], shape frame, each > 0.
    double epsilon1 = 1.0;      ///< Superquadric north-south exponent ε1 [-], in (0, 4].
    double epsilon2 = 1.0;      ///< Superquadric east-west exponent ε2 [-], in (0, 4].
    Taper taper{};              ///< Barr taper; mass properties, bounds and samples include it.
    Bend bend{};                ///< Barr bend; mass properties, bounds and samples include it.
    Vec3 plane_normal{0, 1, 0}; ///< Plane outward normal, world frame, non-zero (normalised on use).
    double plane_offset = 0.0;  ///< Plane offset along the normal [m].
    std::vector<HyperquadricTerm> terms{}; ///< Hyperquadric terms (≥ 3, normals spanning 3-D), shape frame.
};

/// The documented starting point: a unit-diameter sphere.
[[nodiscard]] SM_API ShapeDef default_shape_def();

/// Checks ranges: radii > 0 and finite, ε in (0, 4], taper in [-1, 1], plane normal non-zero.
[[nodiscard]] SM_API Status validate(const ShapeDef& def);

/// Mass, centre of mass and principal inertia of a solid of uniform density.
struct MassProperties {
    double volume = 0.0;   ///< [m³].
    double mass = 0.0;     ///< [kg].
    Vec3 center_of_mass{}; ///< Shape frame [m]; zero for untapered, unbent superquadrics.
    /// Principal moments about the centre of mass [kg·m²]: inertia_diagonal[i] is about the axis
    /// rotate(principal_axes, e_i) of the shape frame.
    Vec3 inertia_diagonal{};
    /// Rotation from the principal frame to the shape frame. Identity for untapered, unbent
    /// superquadrics; a taper plus bend, or a hyperquadric with oblique terms, turns the principal axes.
    /// Each principal axis is matched to the shape axis it is closest to (small deformations keep
    /// the moments in the undeformed shape's slots).
    Quat principal_axes = Quat::identity();
};

/// Closed-form volume of a superquadric: V = 2·a1·a2·a3·ε1·ε2·B(ε1/2+1, ε1)·B(ε2/2, ε2/2) [m³].
[[nodiscard]] SM_API double superquadric_volume(const ShapeDef& def);

/// Closed-form mass properties (Jaklič, Leonardis & Solina 2000, Beta functions) for density ρ [kg/m³].
/// Planes have no finite mass: returns zeros.
[[nodiscard]] SM_API MassProperties compute_mass_properties(const ShapeDef& def, double density);

} // namespace supermodal
