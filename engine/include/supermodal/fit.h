// SPDX-License-Identifier: MIT
// Superquadric recovery from points or a mesh (Solina & Bajcsy 1990 style): Levenberg–Marquardt on the
// radial distance to the surface, started from the moments of the data, restarted over which principal
// axis is the polar axis. The shape follows ShapeDef/Barr: z is the polar axis, taper then bend.
// See docs/pipeline.md for the residual, the bounds and the measured accuracy.
#pragma once

#include "supermodal/api.h"
#include "supermodal/geometry.h"
#include "supermodal/math.h"
#include "supermodal/result.h"
#include "supermodal/shape.h"

#include <vector>

namespace supermodal
{

/// How to fit. Start from default_fit_def().
struct FitDef {
    bool taper = false;       ///< Also fit Barr taper (kx, ky), bounded to [-0.95, 0.95].
    bool bend = false;        ///< Also fit Barr bend (curvature, angle).
    double epsilon_min = 0.1; ///< Lower bound of ε1, ε2 [-]: below it the surface is a box to 1% of a
                              ///< radius and the exponents 2/ε make the residual badly conditioned.
    double epsilon_max = 2.0; ///< Upper bound [-]: beyond 2 the shape turns concave (not a solid body
                              ///< the convex contact path accepts).
    int max_iterations = 200; ///< Levenberg–Marquardt iterations per start.
    int max_points = 4000;    ///< Points used by the solver; more are thinned evenly (the report still
                              ///< measures every point).
    /// A fit whose rms_relative exceeds this is reported as not acceptable (FitResult::acceptable).
    double acceptable_rms_relative = 0.02;
};

/// The documented defaults: no taper, no bend, ε ∈ [0.1, 2].
[[nodiscard]] SM_API FitDef default_fit_def();

/// A fitted superquadric and how well it fits.
struct FitResult {
    ShapeDef shape;                      ///< Radii [m], exponents, taper, bend; shape frame.
    Vec3 position{};                     ///< Shape origin, frame of the data [m].
    Quat orientation = Quat::identity(); ///< Shape frame → data frame.
    double rms_m = 0.0;        ///< RMS radial distance of the points to the surface [m] (along the ray
                               ///< from the centre, after undoing taper/bend: ≥ the true distance).
    double max_m = 0.0;        ///< Largest radial distance [m].
    double rms_relative = 0.0; ///< rms_m / size, size = RMS distance of the points from their centroid.
    double size_m = 0.0;       ///< That size [m].
    int iterations = 0;        ///< Levenberg–Marquardt iterations, all starts together.
    int starts = 0;            ///< Starting guesses tried.
    bool acceptable = false;   ///< rms_relative ≤ FitDef::acceptable_rms_relative.
};

/// Fits one superquadric to points (equal weights). Needs ≥ 16 finite points that span 3-D space.
[[nodiscard]] SM_API Result<FitResult> fit_superquadric(const std::vector<Vec3>& points,
                                                        const FitDef& def = default_fit_def());
/// Fits one superquadric to a mesh surface: its vertices weighted by their share of triangle area,
/// plus samples inside triangles that are large next to the mean spacing.
[[nodiscard]] SM_API Result<FitResult> fit_superquadric(const TriangleMesh& mesh,
                                                        const FitDef& def = default_fit_def());
/// Splits the mesh surface into `parts` slabs along its longest principal axis (1-D k-means of the
/// surface points' projections) and fits one superquadric to each. parts = 1 is fit_superquadric.
[[nodiscard]] SM_API Result<std::vector<FitResult>>
fit_superquadric_parts(const TriangleMesh& mesh, int parts, const FitDef& def = default_fit_def());

} // namespace supermodal
