// SPDX-License-Identifier: MIT
// Strain and stress of the modal displacement field: small strain ε = sym ∇u of the lattice field,
// isotropic linear elasticity σ = λ tr(ε) I + 2μ ε, and the von Mises equivalent stress.
#pragma once

#include "supermodal/modal.h"

#include <array>
#include <span>
#include <vector>

namespace supermodal::modal
{

/// Stress in Voigt order (xx, yy, zz, yz, xz, xy) [Pa], shape frame.
using Voigt = std::array<double, 6>;

/// √(½[(σxx−σyy)² + (σyy−σzz)² + (σzz−σxx)²] + 3(σyz² + σxz² + σxy²)) [Pa].
[[nodiscard]] double von_mises(const Voigt& s);

/// Stress [Pa] at a rest point of the shape frame for amplitudes q [√kg·m] (missing ones count as 0),
/// from the field of the point's cell (or its proxy's, extended, like modal_weights).
[[nodiscard]] Voigt stress_at(const ModalBasis& basis, const Vec3& point_shape, std::span<const double> q);

/// Displacement u [m] and its gradient J_ij = ∂u_i/∂x_j [-] at a rest point (shape frame) for amplitudes q,
/// plus a nodal field stored flat (3 × nodes [m], e.g. a static correction; empty: none).
void displacement_and_gradient(const ModalBasis& basis, const Vec3& point_shape, std::span<const double> q,
                               Vec3& out_u, Mat3& out_gradient, std::span<const double> nodal = {});

/// Where a body's stress is checked, and the stress per unit amplitude there: per cell with nodes, the
/// 3×3×3 points ξ ∈ {−1, 0, 1}³ (corners, edge and face midpoints, centre) that lie in the body. The
/// outer ones sit on the lattice box, where bending and torsion stresses peak (Gauss points would sit
/// inside, e.g. at 58% of the half-depth of a one-cell-thick beam). A point on a face shared by two
/// cells is checked once per cell (the field's gradient jumps across faces). Merged slivers are not
/// checked (their proxies' points cover them).
struct StressModel {
    int mode_count = 0;
    std::vector<Vec3> points;         ///< Rest positions [m], shape frame.
    std::vector<double> stress_modes; ///< Per point, 6 × r: entry (point·6 + component)·r + k
                                      ///< [Pa/(√kg·m)].
    /// Per point, ‖W·S_p‖_F with S_p its 6 × r block and W = diag(√1.5 ×3, √3 ×3) [Pa/(√kg·m)]: its
    /// von Mises stress is at most this × ‖q‖ (see max_von_mises_above).
    std::vector<double> point_bounds;
    double max_point_bound = 0.0; ///< Largest of point_bounds [Pa/(√kg·m)].
};
/// Builds the model of a basis over `shape` (the shape it was built for: the inside test picks the
/// points).
[[nodiscard]] StressModel build_stress_model(const ModalBasis& basis, const ShapeDef& shape);

struct StressPeak {
    double von_mises = 0.0; ///< Largest von Mises stress over the points [Pa].
    int point = -1;         ///< Its index into StressModel::points; −1 without points.
};
/// The largest von Mises stress for amplitudes q: 6r multiply-adds per point.
[[nodiscard]] StressPeak max_von_mises(const StressModel& model, std::span<const double> q);

/// The same peak, exactly, where it exceeds `threshold` [Pa]; otherwise some value ≤ threshold (point
/// −1 when no point could reach it). Points whose bound × ‖q‖ cannot exceed the threshold are skipped,
/// and all of them at once when the largest bound cannot: a plastic body well under its yield stress
/// costs r multiply-adds instead of 6r per point.
[[nodiscard]] StressPeak max_von_mises_above(const StressModel& model, std::span<const double> q,
                                             double threshold);

} // namespace supermodal::modal
