// SPDX-License-Identifier: MIT
#include "modal/plasticity.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace supermodal::modal
{

PlasticStep relieve_plastic(const StressModel& model, const PlasticParams& params, double young,
                            std::span<const double> q, std::span<double> io_q_plastic,
                            double& io_plastic_strain)
{
    PlasticStep out;
    const double current_yield = params.yield_stress + params.hardening * io_plastic_strain;
    const double room = params.max_plastic_strain - io_plastic_strain;
    if (!params.plastic() || !(young > 0.0) || !(room > 0.0))
        return out; // nothing can flow (elastic, or fully worked): no stress is evaluated
    const size_t r = std::min(q.size(), io_q_plastic.size());
    std::vector<double> elastic(r);
    for (size_t k = 0; k < r; ++k)
        elastic[k] = q[k] - io_q_plastic[k];
    // Only a peak above the yield matters: points that cannot reach it are not evaluated.
    out.trial_von_mises = max_von_mises_above(model, elastic, current_yield).von_mises;
    out.von_mises = out.trial_von_mises;
    if (!std::isfinite(out.trial_von_mises) || out.trial_von_mises <= current_yield)
        return out;
    const double d_strain =
        std::min((out.trial_von_mises - current_yield) / (young + params.hardening), room);
    const double target = out.trial_von_mises - young * d_strain;
    const double moved = 1.0 - target / out.trial_von_mises; // in (0, 1]
    for (size_t k = 0; k < r; ++k)
        io_q_plastic[k] += moved * elastic[k];
    io_plastic_strain += d_strain;
    out.von_mises = target;
    out.yielded = true;
    return out;
}

} // namespace supermodal::modal
