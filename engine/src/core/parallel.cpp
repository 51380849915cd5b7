// SPDX-License-Identifier: MIT
#include "core/parallel.h"

#include <cmath>

namespace supermodal
{
namespace
{

// Share of the way from the old split to the measured best one taken per run [-].
constexpr double k_balance_step = 0.25;
// Narrowest part, as a share of an even part [-]: a part stays wide enough to be measured.
constexpr double k_narrowest_part = 0.25;

} // namespace

const std::vector<size_t>& PartBalance::split(size_t count, size_t parts)
{
    if (m_bounds.size() != parts + 1) {
        m_bounds.resize(parts + 1);
        for (size_t p = 0; p <= parts; ++p)
            m_bounds[p] = static_cast<double>(p) / static_cast<double>(parts);
        m_seconds.assign(parts, Slot{});
    }
    m_starts.resize(parts + 1);
    for (size_t p = 0; p <= parts; ++p)
        m_starts[p] =
            std::min(count, static_cast<size_t>(std::llround(m_bounds[p] * static_cast<double>(count))));
    m_starts[0] = 0;
    m_starts[parts] = count;
    for (size_t p = 1; p < parts; ++p)
        m_starts[p] = std::max(m_starts[p], m_starts[p - 1]);
    return m_starts;
}

void PartBalance::learn()
{
    const size_t parts = m_seconds.size();
    double total = 0.0;
    for (const Slot& s : m_seconds)
        total += s.value;
    if (parts < 2 || !(total > 0.0) || !std::isfinite(total))
        return;
    // The cumulative time along the old split is piecewise linear; each new bound is where it reaches
    // that bound's share of the total.
    std::vector<double>& target = m_target;
    target.resize(parts + 1);
    target[0] = 0.0;
    target[parts] = 1.0;
    size_t seg = 0;
    double before = 0.0; // time of the parts ahead of seg [s]
    for (size_t k = 1; k < parts; ++k) {
        const double want = total * static_cast<double>(k) / static_cast<double>(parts);
        while (seg + 1 < parts && before + m_seconds[seg].value < want) {
            before += m_seconds[seg].value;
            ++seg;
        }
        const double t = m_seconds[seg].value;
        const double within = t > 0.0 ? std::clamp((want - before) / t, 0.0, 1.0) : 0.0;
        target[k] = m_bounds[seg] + within * (m_bounds[seg + 1] - m_bounds[seg]);
    }
    const double narrowest = k_narrowest_part / static_cast<double>(parts);
    for (size_t k = 1; k < parts; ++k) {
        const double moved = m_bounds[k] + k_balance_step * (target[k] - m_bounds[k]);
        m_bounds[k] = std::max(moved, m_bounds[k - 1] + narrowest);
    }
    for (size_t k = parts - 1; k >= 1; --k)
        m_bounds[k] = std::min(m_bounds[k], m_bounds[k + 1] - narrowest);
}

} // namespace supermodal
