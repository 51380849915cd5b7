// SPDX-License-Identifier: MIT
// Public fitting API: checks the data, builds the starting guesses from the moments, runs
// Levenberg–Marquardt from each, and reports the best fit measured on every point.
#include "supermodal/fit.h"

#include "fit/fit_model.h"
#include "fit/surface_points.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <string>

namespace supermodal
{
namespace
{

/// Fewer points than this cannot pin down 15 parameters with any redundancy.
constexpr int k_min_points = 16;
/// Initial radii never go below this fraction of the size (a flat point set still gets a body).
constexpr double k_min_initial_radius = 1e-3;
/// Points the starting guesses are compared on: enough to tell the three polar-axis basins apart.
constexpr int k_coarse_points = 500;

Quat quat_from_axes(const Vec3& x, const Vec3& y, const Vec3& z)
{
    Eigen::Matrix3d r;
    r.col(0) = Eigen::Vector3d(x.x, x.y, x.z);
    r.col(1) = Eigen::Vector3d(y.x, y.y, y.z);
    r.col(2) = Eigen::Vector3d(z.x, z.y, z.z);
    const Eigen::Quaterniond q(r);
    return normalized(Quat{q.w(), q.x(), q.y(), q.z()});
}

/// Start with principal axis `polar` as the shape's z: centre and radii from the extents along the
/// principal axes, ε1 = ε2 = 1 (an ellipsoid, as Solina & Bajcsy start).
fit::Model initial_model(const fit::WeightedPoints& data, const fit::Moments& mom, int polar)
{
    const Vec3 z = mom.axes.col(polar), x = mom.axes.col((polar + 1) % 3), y = mom.axes.col((polar + 2) % 3);
    const Vec3 axis[3] = {x, y, z};
    Vec3 lo{1e300, 1e300, 1e300}, hi{-1e300, -1e300, -1e300};
    for (const Vec3& p : data.points)
        for (int i = 0; i < 3; ++i) {
            const double t = dot(p - mom.centroid, axis[i]);
            lo[i] = std::min(lo[i], t);
            hi[i] = std::max(hi[i], t);
        }
    fit::Model m;
    m.orientation = quat_from_axes(x, y, z);
    m.position = mom.centroid;
    for (int i = 0; i < 3; ++i) {
        m.position += 0.5 * (lo[i] + hi[i]) * axis[i];
        m.shape.radii[i] = std::max(0.5 * (hi[i] - lo[i]), k_min_initial_radius * mom.rms_radius);
    }
    m.shape.epsilon1 = m.shape.epsilon2 = 1.0;
    return m;
}

Status check(const FitDef& def)
{
    const bool ok = def.epsilon_min > 0.0 && def.epsilon_min <= def.epsilon_max && def.epsilon_max <= 4.0 &&
                    def.max_iterations > 0 && def.max_points >= k_min_points &&
                    std::isfinite(def.acceptable_rms_relative);
    if (!ok)
        return Error{"", "FitDef",
                     "expected 0 < epsilon_min <= epsilon_max <= 4, max_iterations > 0, "
                     "max_points >= 16 and a finite acceptable_rms_relative"};
    return {};
}

Result<FitResult> fit_points(const fit::WeightedPoints& data, const FitDef& def)
{
    if (Status s = check(def); !s)
        return s.error();
    if (data.points.size() < size_t(k_min_points))
        return Error{"", "",
                     "need at least 16 points to fit a superquadric, found " +
                         std::to_string(data.points.size())};
    for (const Vec3& p : data.points)
        if (!is_finite(p))
            return Error{"", "", "a point is not finite (NaN or Inf)"};
    const fit::Moments mom = fit::moments(data);
    // Relative to the distance from the origin: round-off of the centroid alone leaves ~1e-16 of it.
    if (!(mom.rms_radius > 1e-12 * length(mom.centroid)) || !std::isfinite(mom.rms_radius))
        return Error{"", "", "the points do not span any space (all at one place)"};

    const fit::WeightedPoints solver_data = fit::thin(data, def.max_points);
    // Coarse to fine: the starts race on a few hundred points, the winner is polished on all of them.
    const fit::WeightedPoints coarse = fit::thin(data, k_coarse_points);
    fit::Layout plain{.taper = false,
                      .bend = false,
                      .size = mom.rms_radius,
                      .epsilon_min = def.epsilon_min,
                      .epsilon_max = def.epsilon_max};
    fit::Layout full = plain;
    full.taper = def.taper;
    full.bend = def.bend;
    FitResult best;
    fit::Model best_model;
    double best_cost = 1e300;
    int iterations = 0;
    // Which principal axis is the polar one decides the basin (ε1 and ε2 are not interchangeable):
    // try all three, longest first.
    for (int polar : {0, 1, 2}) {
        fit::Model m = initial_model(solver_data, mom, polar);
        const fit::SolveStats stats = fit::solve(plain, coarse, m, def.max_iterations);
        iterations += stats.iterations;
        if (stats.cost < best_cost) {
            best_cost = stats.cost;
            best_model = m;
        }
        ++best.starts;
    }
    if (def.taper || def.bend)
        iterations += fit::solve(full, coarse, best_model, def.max_iterations).iterations;
    iterations += fit::solve(full, solver_data, best_model, def.max_iterations).iterations;
    best.shape = best_model.shape;
    best.position = best_model.position;
    best.orientation = best_model.orientation;
    best.iterations = iterations;
    const fit::Residuals res =
        fit::measure({.position = best.position, .orientation = best.orientation, .shape = best.shape}, data);
    best.rms_m = std::sqrt(res.mean_square);
    best.max_m = res.max_abs;
    best.size_m = mom.rms_radius;
    best.rms_relative = best.rms_m / mom.rms_radius;
    best.acceptable = best.rms_relative <= def.acceptable_rms_relative;
    return best;
}

fit::WeightedPoints mesh_points(const TriangleMesh& mesh, const FitDef& def)
{
    return fit::mesh_surface_points(mesh, def.max_points);
}

// 1-D k-means of the weighted coordinates t into `parts` clusters, centres started evenly over their
// extent: each coordinate's cluster.
std::vector<int> kmeans_1d(const std::vector<double>& t, const std::vector<double>& weights, int parts)
{
    double lo = 1e300, hi = -1e300;
    for (const double x : t) {
        lo = std::min(lo, x);
        hi = std::max(hi, x);
    }
    std::vector<double> centre(static_cast<size_t>(parts), 0.0);
    for (int k = 0; k < parts; ++k)
        centre[size_t(k)] = lo + (hi - lo) * (k + 0.5) / parts;
    std::vector<int> label(t.size(), 0);
    for (int it = 0; it < 100; ++it) {
        for (size_t i = 0; i < t.size(); ++i) // centres stay sorted, so the nearest is found by a scan
            label[i] = int(std::min_element(
                               centre.begin(), centre.end(),
                               [&](double a, double b) { return std::abs(a - t[i]) < std::abs(b - t[i]); }) -
                           centre.begin());
        std::vector<double> sum(size_t(parts), 0.0), weight(size_t(parts), 0.0);
        for (size_t i = 0; i < t.size(); ++i) {
            sum[size_t(label[i])] += weights[i] * t[i];
            weight[size_t(label[i])] += weights[i];
        }
        bool moved = false;
        for (size_t k = 0; k < centre.size(); ++k)
            if (weight[k] > 0.0 && sum[k] / weight[k] != centre[k]) {
                centre[k] = sum[k] / weight[k];
                moved = true;
            }
        if (!moved)
            break;
    }
    return label;
}

// The points of cluster k, their weights renormalised to sum to 1.
fit::WeightedPoints part_points(const fit::WeightedPoints& data, const std::vector<int>& label, int k)
{
    fit::WeightedPoints part;
    for (size_t i = 0; i < label.size(); ++i)
        if (label[i] == k) {
            part.points.push_back(data.points[i]);
            part.weights.push_back(data.weights[i]);
        }
    double total = 0.0;
    for (double w : part.weights)
        total += w;
    for (double& w : part.weights)
        w /= total;
    return part;
}

} // namespace

FitDef default_fit_def()
{
    return {};
}

Result<FitResult> fit_superquadric(const std::vector<Vec3>& points, const FitDef& def)
{
    fit::WeightedPoints data{points,
                             std::vector<double>(points.size(), points.empty() ? 0.0 : 1.0 / points.size())};
    return fit_points(data, def);
}

Result<FitResult> fit_superquadric(const TriangleMesh& mesh, const FitDef& def)
{
    for (const uint32_t i : mesh.indices)
        if (i >= mesh.positions.size())
            return Error{"", "", "mesh index " + std::to_string(i) + " is out of range"};
    const fit::WeightedPoints data = mesh_points(mesh, def);
    if (data.points.empty())
        return Error{"", "", "the mesh has no surface area"};
    return fit_points(data, def);
}

Result<std::vector<FitResult>> fit_superquadric_parts(const TriangleMesh& mesh, int parts, const FitDef& def)
{
    if (parts < 1 || parts > 64)
        return Error{"", "", "parts must be in [1, 64], found " + std::to_string(parts)};
    for (const uint32_t i : mesh.indices)
        if (i >= mesh.positions.size())
            return Error{"", "", "mesh index " + std::to_string(i) + " is out of range"};
    const fit::WeightedPoints data = mesh_points(mesh, def);
    if (data.points.empty())
        return Error{"", "", "the mesh has no surface area"};
    const fit::Moments mom = fit::moments(data);
    const Vec3 axis = mom.axes.col(0);
    std::vector<double> t(data.points.size());
    for (size_t i = 0; i < t.size(); ++i)
        t[i] = dot(data.points[i] - mom.centroid, axis);
    const std::vector<int> label = kmeans_1d(t, data.weights, parts);
    std::vector<FitResult> out;
    for (int k = 0; k < parts; ++k) {
        Result<FitResult> r = fit_points(part_points(data, label, k), def);
        if (!r)
            return Error{"", "part " + std::to_string(k), r.error().what};
        out.push_back(*r);
    }
    return out;
}

} // namespace supermodal
