// SPDX-License-Identifier: MIT
// Mass properties by quadrature for the shapes that have no closed form: tapered or bent superquadrics
// and hyperquadrics. compute_mass_properties (mass_properties.cpp) dispatches here.
#pragma once

#include "supermodal/math.h"
#include "supermodal/shape.h"

namespace supermodal
{

/// Quadrature mass properties with the full inertia tensor.
struct QuadratureMass {
    /// inertia_diagonal holds the principal moments about the centre of mass, each in the slot of the
    /// shape axis its principal axis is closest to; properties.principal_axes is principal_axes.
    MassProperties properties;
    Mat3 inertia_tensor{}; ///< About the centre of mass, shape axes [kg·m²].
    Mat3 principal_axes{}; ///< Column i: unit principal axis of inertia_diagonal[i], shape frame; det +1.
};

/// Mass properties of a superquadric (deformed or not) or hyperquadric of density ρ [kg/m³] by
/// quadrature; zeros for planes and for empty or unbounded hyperquadrics. The node count grows with
/// `order` (≥ 1): superquadrics use (8·order + 1)² tanh-sinh nodes over each half quadrant of the
/// cross-section and 8 Gauss nodes along z; hyperquadrics use (12·order)² ray directions per cube face.
/// Accuracy and cost against order: docs/geometry.md.
[[nodiscard]] QuadratureMass quadrature_mass(const ShapeDef& def, double density, int order);

/// The default order: ≤ 1e-10 relative for superquadrics with ε in [0.01, 4], ≤ 1e-10 for smooth
/// hyperquadrics (2 ≤ γ ≤ 10), 1e-6 to 1e-5 for polytope-like ones (γ = 1 or γ ≥ 40).
inline constexpr int k_default_mass_order = 8;

} // namespace supermodal
