// SPDX-License-Identifier: MIT
// Contact sample density from an error budget (scene "dynamics": "auto"). A sampled body meets
// a surface only at its samples, so where the true surface bulges between them it sinks deeper than it
// should, by the gap between the samples' hull and the surface. Pressed on by a plane from direction n
// that gap is (how far the surface reaches along n) − (how far the samples reach along n): the error in
// the body's resting position. It is measured, not modelled, so it holds for any shape and exponent.
#pragma once

#include "supermodal/geometry.h"
#include "supermodal/shape.h"

#include <span>

namespace supermodal
{

/// Largest gap between `samples` and the surface they sample, over 300 directions (a Fibonacci sphere
/// plus the 26 axis, edge and corner directions of the shape frame) [m]; `reference` is a much denser
/// sampling standing in for the surface (the gap is then low by at most the reference's own gap).
[[nodiscard]] double sampling_gap(std::span<const SurfaceSample> samples,
                                  std::span<const SurfaceSample> reference);

/// What choose_sample_spacing() picked.
struct SampleDensityChoice {
    double spacing = 0.0; ///< Requested spacing [m] (sample_surface may widen it to fit max_samples).
    int sample_count = 0; ///< Samples at that spacing [-].
    double gap = 0.0;     ///< Measured sampling gap at that spacing [m].
    bool met = false;     ///< gap ≤ tolerance.
};

/// The coarsest spacing among the default (a quarter of the smallest half-extent) × 4, 2, 1, ½, ¼ whose
/// sampling gap is within `tolerance` [m]; the finest of them when none is (met = false). At most
/// max_samples samples per candidate, as for any collider.
[[nodiscard]] SampleDensityChoice choose_sample_spacing(const ShapeDef& shape, double tolerance,
                                                        int max_samples);

} // namespace supermodal
