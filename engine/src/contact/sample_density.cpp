// SPDX-License-Identifier: MIT
#include "contact/sample_density.h"

#include "contact/collider.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

namespace supermodal
{
namespace
{

// Reference sampling: 1/8 of the finest candidate's spacing, so its own gap (quadratic in spacing) is
// 1/64 of that candidate's; capped so a large body does not take long (its reference is then coarser).
constexpr int k_reference_samples = 20000;
constexpr int k_fibonacci_directions = 274; // + 26 box directions = 300

std::vector<Vec3> directions()
{
    std::vector<Vec3> out;
    out.reserve(k_fibonacci_directions + 26);
    const double golden = std::numbers::pi * (3.0 - std::sqrt(5.0));
    for (int i = 0; i < k_fibonacci_directions; ++i) {
        const double y = 1.0 - 2.0 * (i + 0.5) / k_fibonacci_directions;
        const double r = std::sqrt(std::max(0.0, 1.0 - y * y));
        out.push_back({r * std::cos(golden * i), y, r * std::sin(golden * i)});
    }
    for (int x = -1; x <= 1; ++x)
        for (int y = -1; y <= 1; ++y)
            for (int z = -1; z <= 1; ++z)
                if (x != 0 || y != 0 || z != 0)
                    out.push_back(normalized(Vec3{double(x), double(y), double(z)}));
    return out;
}

double reach(std::span<const SurfaceSample> points, const Vec3& n)
{
    double most = -std::numeric_limits<double>::infinity();
    for (const SurfaceSample& s : points)
        most = std::max(most, dot(s.point, n));
    return most;
}

// How far the surface reaches along each direction, from its reference sampling.
std::vector<double> surface_reach(std::span<const SurfaceSample> reference, std::span<const Vec3> dirs)
{
    std::vector<double> out(dirs.size());
    for (size_t i = 0; i < dirs.size(); ++i)
        out[i] = reach(reference, dirs[i]);
    return out;
}

// The largest shortfall of the samples' reach behind the surface's over the directions [m].
double gap_behind(std::span<const double> surface, std::span<const SurfaceSample> samples,
                  std::span<const Vec3> dirs)
{
    if (samples.empty())
        return std::numeric_limits<double>::infinity();
    double gap = 0.0;
    for (size_t i = 0; i < dirs.size(); ++i)
        gap = std::max(gap, surface[i] - reach(samples, dirs[i]));
    return gap;
}

} // namespace

double sampling_gap(std::span<const SurfaceSample> samples, std::span<const SurfaceSample> reference)
{
    if (reference.empty())
        return std::numeric_limits<double>::infinity();
    const std::vector<Vec3> dirs = directions();
    return gap_behind(surface_reach(reference, dirs), samples, dirs);
}

SampleDensityChoice choose_sample_spacing(const ShapeDef& shape, double tolerance, int max_samples)
{
    const double base = default_sample_spacing(shape);
    constexpr double k_factors[] = {4.0, 2.0, 1.0, 0.5, 0.25}; // coarse to fine: the cheapest first
    const std::vector<Vec3> dirs = directions();
    // The reference's reach along each direction once, not once per candidate (the bulk of the work).
    const std::vector<double> surface = surface_reach(
        sample_surface(shape, base * k_factors[std::size(k_factors) - 1] / 8.0, k_reference_samples), dirs);
    SampleDensityChoice choice;
    for (const double f : k_factors) {
        const std::vector<SurfaceSample> samples = sample_surface(shape, base * f, max_samples);
        const double gap = gap_behind(surface, samples, dirs);
        choice = {base * f, static_cast<int>(samples.size()), gap, gap <= tolerance};
        if (choice.met)
            break;
    }
    return choice;
}

} // namespace supermodal
