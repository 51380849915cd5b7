// SPDX-License-Identifier: MIT
// Geometric nested dissection of a lattice (see dissection.h).
#include "modal/dissection.h"

#include <algorithm>
#include <array>
#include <limits>
#include <numeric>

namespace supermodal::modal
{

namespace
{

/// Parts this small are ordered as they come: splitting them further saves less than it costs.
constexpr std::ptrdiff_t k_leaf_nodes = 32;

struct Dissection {
    const LatticeModel& model;
    int step; ///< node-grid spacing of cell faces (the element order)
    std::vector<int> order;

    /// Orders nodes [first, last) of `nodes` into `order`.
    void dissect(std::vector<int>::iterator first, std::vector<int>::iterator last)
    {
        if (last - first <= k_leaf_nodes)
            return append(first, last);
        std::array<int, 3> lo{}, hi{};
        lo.fill(std::numeric_limits<int>::max());
        hi.fill(std::numeric_limits<int>::min());
        for (auto it = first; it != last; ++it)
            for (int d = 0; d < 3; ++d) {
                lo[d] = std::min(lo[d], model.node_grid[*it][d]);
                hi[d] = std::max(hi[d], model.node_grid[*it][d]);
            }
        int axis = 0;
        for (int d = 1; d < 3; ++d)
            if (hi[d] - lo[d] > hi[axis] - lo[axis])
                axis = d;
        // A face plane strictly inside the extent, near its middle.
        const int plane = (lo[axis] + hi[axis]) / 2 / step * step;
        if (plane <= lo[axis] || plane >= hi[axis])
            return append(first, last);
        const auto below = [&](int n) { return model.node_grid[n][axis] < plane; };
        const auto above = [&](int n) { return model.node_grid[n][axis] > plane; };
        const auto mid = std::stable_partition(first, last, below);
        const auto sep = std::stable_partition(mid, last, above);
        dissect(first, mid);
        dissect(mid, sep);
        append(sep, last);
    }

    void append(std::vector<int>::iterator first, std::vector<int>::iterator last)
    {
        for (auto it = first; it != last; ++it)
            for (int d = 0; d < 3; ++d)
                order.push_back(3 * *it + d);
    }
};

} // namespace

std::vector<int> lattice_dissection(const LatticeModel& model)
{
    std::vector<int> nodes(static_cast<size_t>(model.node_count()));
    std::iota(nodes.begin(), nodes.end(), 0);
    Dissection d{model, std::max(1, model.lattice.order), {}};
    d.order.reserve(static_cast<size_t>(model.dof_count()));
    d.dissect(nodes.begin(), nodes.end());
    return d.order;
}

} // namespace supermodal::modal
