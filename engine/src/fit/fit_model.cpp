// SPDX-License-Identifier: MIT
// Residual, parameter vector and Levenberg–Marquardt for superquadric recovery (see fit_model.h).
#include "fit/fit_model.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

namespace supermodal::fit
{
namespace
{

constexpr double k_max_taper = 0.95;
/// Bend limits: σ = 1 − k·u stays ≥ 0.1 over the body's cross-section, and the polar half-axis turns by
/// at most 2.5 rad (< π), so the bent body stays one-to-one (deform.cpp's domain).
constexpr double k_max_bend_section = 0.9;
constexpr double k_max_bend_turn = 2.5;
/// Forward-difference step of every (dimensionless) parameter: ~√(machine ε)·10, so round-off in the
/// difference stays ~1e-9 relative and the truncation error ~1e-6 relative, plenty for the Gauss–Newton
/// model (it sets the convergence rate, not the solution).
constexpr double k_step = 1e-6;
/// A residual at this fraction of the size is exact data: stop.
constexpr double k_exact_rms = 1e-10;
/// Stop when an accepted step lowers the cost by less than this fraction: a creeping solver on data that
/// is no superquadric would otherwise spend every iteration for digits nobody reads (rms changes by
/// half this fraction).
constexpr double k_min_relative_decrease = 1e-7;

/// Residual vector r_i = √w_i · d_i.
Eigen::VectorXd residual_vector(const Model& m, const WeightedPoints& data)
{
    const auto n = Eigen::Index(data.points.size());
    Eigen::VectorXd r(n);
    for (Eigen::Index i = 0; i < n; ++i)
        r[i] = std::sqrt(data.weights[size_t(i)]) * model_distance(m, data.points[size_t(i)]);
    return r;
}

} // namespace

double model_distance(const Model& m, const Vec3& p)
{
    Vec3 s = inv_rotate(m.orientation, p - m.position);
    ShapeDef plain = m.shape;
    if (is_deformed(m.shape)) {
        s = undeform_point(m.shape, s).point;
        plain.taper = {};
        plain.bend = {};
    }
    const double d = radial_distance(plain, s);
    // radial_distance is finite for finite input; a non-finite point counts as far away, not as NaN.
    return std::isfinite(d) ? d : 1e6 * std::max({plain.radii.x, plain.radii.y, plain.radii.z});
}

Eigen::VectorXd to_vector(const Layout& layout, const Model& m)
{
    Eigen::VectorXd x = Eigen::VectorXd::Zero(layout.count());
    for (int i = 0; i < 3; ++i) {
        x[i] = m.position[i] / layout.size;
        x[6 + i] = std::log(m.shape.radii[i]);
    }
    x[9] = m.shape.epsilon1;
    x[10] = m.shape.epsilon2;
    int j = 11;
    if (layout.taper) {
        x[j++] = m.shape.taper.kx;
        x[j++] = m.shape.taper.ky;
    }
    if (layout.bend) {
        x[j++] = m.shape.bend.curvature * std::cos(m.shape.bend.angle) * layout.size;
        x[j++] = m.shape.bend.curvature * std::sin(m.shape.bend.angle) * layout.size;
    }
    return x;
}

Model from_vector(const Layout& layout, const Model& base, const Eigen::VectorXd& x)
{
    Model m = base;
    for (int i = 0; i < 3; ++i) {
        m.position[i] = x[i] * layout.size;
        const double ln_a = std::clamp(x[6 + i], std::log(1e-4 * layout.size), std::log(1e2 * layout.size));
        m.shape.radii[i] = std::exp(ln_a);
    }
    m.orientation = normalized(base.orientation * quat_from_rotation_vector({x[3], x[4], x[5]}));
    m.shape.epsilon1 = std::clamp(x[9], layout.epsilon_min, layout.epsilon_max);
    m.shape.epsilon2 = std::clamp(x[10], layout.epsilon_min, layout.epsilon_max);
    int j = 11;
    if (layout.taper) {
        m.shape.taper.kx = std::clamp(x[j++], -k_max_taper, k_max_taper);
        m.shape.taper.ky = std::clamp(x[j++], -k_max_taper, k_max_taper);
    }
    if (layout.bend) {
        const double bx = x[j++] / layout.size, by = x[j++] / layout.size;
        const Vec3& a = m.shape.radii;
        const double limit = std::min(k_max_bend_section / std::max(a.x, a.y), k_max_bend_turn / a.z);
        const double k = std::hypot(bx, by);
        m.shape.bend.curvature = std::min(k, limit);
        m.shape.bend.angle = k > 0.0 ? std::atan2(by, bx) : 0.0;
    }
    return m;
}

Residuals measure(const Model& m, const WeightedPoints& data)
{
    Residuals out;
    for (size_t i = 0; i < data.points.size(); ++i) {
        const double d = model_distance(m, data.points[i]);
        out.mean_square += data.weights[i] * d * d;
        out.max_abs = std::max(out.max_abs, std::abs(d));
    }
    return out;
}

SolveStats solve(const Layout& layout, const WeightedPoints& data, Model& model, int max_iterations)
{
    const int p = layout.count();
    Eigen::VectorXd r = residual_vector(model, data);
    double cost = r.squaredNorm();
    double lambda = 1e-3;
    SolveStats stats;
    Eigen::MatrixXd jac(r.size(), p);
    for (; stats.iterations < max_iterations; ++stats.iterations) {
        if (cost <= (k_exact_rms * layout.size) * (k_exact_rms * layout.size))
            break;
        const Eigen::VectorXd x = to_vector(layout, model);
        for (int j = 0; j < p; ++j) {
            Eigen::VectorXd xh = x;
            // Step into the box: a step past an ε bound would be clamped away and leave a zero column.
            const bool at_top = (j == 9 || j == 10) && x[j] + k_step > layout.epsilon_max;
            const double h = at_top ? -k_step : k_step;
            xh[j] += h;
            jac.col(j) = (residual_vector(from_vector(layout, model, xh), data) - r) / h;
        }
        const Eigen::MatrixXd a = jac.transpose() * jac;
        const Eigen::VectorXd g = jac.transpose() * r;
        const double floor = 1e-12 * std::max(a.diagonal().maxCoeff(), 1e-300);
        bool accepted = false;
        double decrease = 0.0;
        for (int attempt = 0; attempt < 12 && !accepted; ++attempt) {
            Eigen::MatrixXd damped = a;
            for (int j = 0; j < p; ++j)
                damped(j, j) += lambda * std::max(a(j, j), floor);
            const Eigen::VectorXd step = damped.ldlt().solve(-g);
            if (!step.allFinite()) {
                lambda *= 10.0;
                continue;
            }
            const Model trial = from_vector(layout, model, x + step);
            const Eigen::VectorXd rt = residual_vector(trial, data);
            const double trial_cost = rt.squaredNorm();
            if (std::isfinite(trial_cost) && trial_cost < cost) {
                decrease = cost - trial_cost;
                model = trial;
                r = rt;
                cost = trial_cost;
                lambda = std::max(lambda / 3.0, 1e-12);
                accepted = true;
            } else {
                lambda *= 8.0;
            }
        }
        if (!accepted || decrease < k_min_relative_decrease * (cost + decrease)) {
            ++stats.iterations;
            break;
        }
    }
    stats.cost = cost;
    return stats;
}

} // namespace supermodal::fit
