// SPDX-License-Identifier: MIT
// The model the fit adjusts: a posed superquadric with optional taper and bend, its parameter vector,
// and the residual per point (radial distance to the surface, after undoing the pose and deformation).
#pragma once

#include "supermodal/fit.h"

#include <Eigen/Core>
#include <vector>

namespace supermodal::fit
{

/// Points with weights that sum to 1, so Σ w·d² is the mean square distance.
struct WeightedPoints {
    std::vector<Vec3> points;
    std::vector<double> weights;
};

/// A posed, possibly deformed superquadric.
struct Model {
    Vec3 position{};
    Quat orientation = Quat::identity();
    ShapeDef shape = default_shape_def();
};

/// Signed radial distance of world point p to the model's surface [m], negative inside.
[[nodiscard]] double model_distance(const Model& m, const Vec3& p);

/// Which parameters move, their bounds, and the scale that makes them comparable.
struct Layout {
    bool taper = false;
    bool bend = false;
    double size = 1.0; ///< Length scale of the data [m].
    double epsilon_min = 0.1, epsilon_max = 2.0;
    [[nodiscard]] int count() const { return 11 + (taper ? 2 : 0) + (bend ? 2 : 0); }
};

/// Parameter vector around a model: [position/size (3), rotation increment (3), ln radii (3), ε1, ε2,
/// (kx, ky), (bend·size along x, along y)]. The rotation increment is a body-frame rotation vector from
/// the model's orientation, so the vector is zero-rotation at every linearisation point.
[[nodiscard]] Eigen::VectorXd to_vector(const Layout& layout, const Model& m);
/// The model a parameter vector stands for (rotation increment applied to base's orientation), with
/// every parameter clamped into its bounds (radii in [1e-4, 1e2]·size, ε in bounds, |taper| ≤ 0.95,
/// bend curvature ≤ 0.9 / max(a1, a2) and ≤ 2.5 / a3 so the bent body stays one-to-one).
[[nodiscard]] Model from_vector(const Layout& layout, const Model& base, const Eigen::VectorXd& x);

/// Outcome of one Levenberg–Marquardt run.
struct SolveStats {
    double cost = 0.0; ///< Weighted mean square distance [m²].
    int iterations = 0;
};
/// Levenberg–Marquardt from `start` (improved in place): forward-difference Jacobian, normal equations
/// (JᵀJ + λ·diag JᵀJ) δ = −Jᵀr solved by Eigen's LDLᵀ, bounds by clamping.
SolveStats solve(const Layout& layout, const WeightedPoints& data, Model& start, int max_iterations);

/// Weighted mean square and the largest |distance| of the points to the model.
struct Residuals {
    double mean_square = 0.0;
    double max_abs = 0.0;
};
[[nodiscard]] Residuals measure(const Model& m, const WeightedPoints& data);

} // namespace supermodal::fit
