// SPDX-License-Identifier: MIT
#include "modal/adaptive.h"

#include "modal/auto_lattice.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace supermodal::modal
{
namespace
{

// Fractions of the tolerance: a body gains modes when those left out could reach past half of it, and
// then takes (or later drops to) as many as leave out a quarter. The estimate is per substep and the
// loads grow during a strike, so the margin keeps the error measured against all modes under the whole
// tolerance (tests/modal/adaptive_test.cpp).
constexpr double k_gain_fraction = 0.5;
constexpr double k_target_fraction = 0.25;

// How far mode k may move the surface [m].
double mode_reach(const ModalModel& m, const ModalState& s, size_t k, double force)
{
    const double w = m.omega[k];
    if (!(w > 0.0))
        return std::numeric_limits<double>::infinity(); // no spring to bound it: keep the mode
    const double elastic = s.q[k] - s.q_plastic[k];
    const double rate = s.q_dot[k] / w;
    const double amplitude = std::sqrt(elastic * elastic + rate * rate);
    const double overshoot = 2.0 * std::abs(force) / (w * w);
    return m.surface->mode_reach[k] * std::max(amplitude, overshoot);
}

} // namespace

ActiveChoice choose_active_modes(const ModalModel& m, const ModalState& s, std::span<const double> force)
{
    const size_t r = s.q.size();
    const double tol = m.adaptive_tolerance;
    std::array<double, k_max_modes> reach; // per mode, computed once for both sums below
    for (size_t k = 0; k < r; ++k)
        reach[k] = mode_reach(m, s, k, force[k]);
    // Going down from the highest mode: the first count whose left-out modes reach past the gain
    // threshold, and past the target (also the drop threshold).
    double tail = 0.0;
    size_t need = 0, target = 0;
    bool found_target = false;
    for (size_t k = r; k-- > 0;) {
        tail += reach[k];
        if (!found_target && !(tail <= k_target_fraction * tol)) {
            target = k + 1;
            found_target = true;
        }
        if (!(tail <= k_gain_fraction * tol)) {
            need = k + 1;
            break;
        }
    }
    size_t active = s.active;
    if (need > active || target < active)
        active = target;
    for (size_t k = r; k-- > active;)
        if (s.q_plastic[k] != 0.0) {
            active = k + 1;
            break;
        }
    ActiveChoice out;
    out.active = active;
    for (size_t k = active; k < r; ++k)
        out.truncation += reach[k];
    if (m.lattice_changes.size() == r)
        for (size_t k = 0; k < active; ++k)
            out.lattice_error += 2.0 * k_lattice_change_safety * m.lattice_changes[k] * reach[k];
    return out;
}

} // namespace supermodal::modal
