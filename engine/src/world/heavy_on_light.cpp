// SPDX-License-Identifier: MIT
#include "world/heavy_on_light.h"

#include "contact/radix_sort.h"

#include <algorithm>
#include <cmath>

namespace supermodal
{
namespace
{

// A pair's upper body at least this much heavier than its lower one (their masses along the normal at
// its first point) has the lower one's mass scaled up in its rows (scale_heavy_on_light).
constexpr double k_heavy_mass_ratio = 4.0;
// ... and resting on it: the normal (from the lower body to the upper one) at most 60° from up.
constexpr double k_heavy_min_uprightness = 0.5;

// A side's own mass along d at its anchor [kg] (the other side held still).
double side_mass_along(const Side& s, const Vec3& d)
{
    return inverse_along(point_mass_inverse(s, Side{}), d);
}

// Each node's place in `nodes` (sorted, no repeats), by node: a table instead of a binary search per
// lookup (two per pair, twice).
std::vector<uint32_t> node_places(const std::vector<uint32_t>& nodes)
{
    std::vector<uint32_t> place(nodes.empty() ? 0 : static_cast<size_t>(nodes.back()) + 1, 0);
    for (size_t i = 0; i < nodes.size(); ++i)
        place[nodes[i]] = static_cast<uint32_t>(i);
    return place;
}

// Levels of the contact graph [-]: 1 for a body touching something that takes no impulse (the ground,
// a kinematic body), n + 1 for one touching a level-n body; 0 where not grounded. Breadth
// first in pair order, so the result does not depend on threads.
std::vector<uint32_t> contact_levels(const SoftContacts& rows, const std::vector<uint32_t>& nodes,
                                     const std::vector<uint32_t>& place)
{
    auto id = [&](uint32_t node) { return static_cast<size_t>(place[node]); };
    std::vector<uint32_t> start(nodes.size() + 1, 0), edges, level(nodes.size(), 0), queue;
    for (const SoftPair& sp : rows.pairs)
        if (sp.count > 0 && sp.node_a != k_no_node && sp.node_b != k_no_node) {
            ++start[id(sp.node_a) + 1];
            ++start[id(sp.node_b) + 1];
        }
    for (size_t i = 0; i < nodes.size(); ++i)
        start[i + 1] += start[i];
    edges.resize(start.back());
    std::vector<uint32_t> fill(start.begin(), start.end() - 1);
    for (const SoftPair& sp : rows.pairs) {
        if (sp.count == 0)
            continue;
        const bool a = sp.node_a != k_no_node, b = sp.node_b != k_no_node;
        if (a && b) {
            edges[fill[id(sp.node_a)]++] = static_cast<uint32_t>(id(sp.node_b));
            edges[fill[id(sp.node_b)]++] = static_cast<uint32_t>(id(sp.node_a));
        } else if (a != b) {
            const size_t i = id(a ? sp.node_a : sp.node_b);
            if (level[i] == 0) {
                level[i] = 1;
                queue.push_back(static_cast<uint32_t>(i));
            }
        }
    }
    for (size_t q = 0; q < queue.size(); ++q)
        for (uint32_t e = start[queue[q]]; e < start[queue[q] + 1]; ++e)
            if (level[edges[e]] == 0) {
                level[edges[e]] = level[queue[q]] + 1;
                queue.push_back(edges[e]);
            }
    return level;
}

// A rigid side's own mass along d at its anchor [kg]: side_mass_along's value without the matrix,
// 1 / (1/m + (r×d)·I⁻¹(r×d)), equal to it up to rounding.
double rigid_mass_along(const Side& s, const Vec3& d)
{
    const Vec3 arm = cross(s.r, d);
    const double w = s.inv_mass + dot(arm, s.inv_inertia * arm);
    return w > 0.0 ? 1.0 / w : 0.0;
}

// Whether any pair of two moving rigid bodies has masses along its normal near k_heavy_mass_ratio apart
// or more (a slack of 1e-9 over the rounding between the two formulas), on the threads: a pile of like
// bodies has none, and skips the rest.
bool any_uneven_pair(const Parallel& par, const SoftContacts& rows)
{
    std::vector<uint8_t> uneven(par.part_capacity(), 0);
    par.for_parts(rows.pairs.size(), k_min_rows_per_part, [&](size_t part, size_t begin, size_t end) {
        for (size_t i = begin; i < end && uneven[part] == 0; ++i) {
            const SoftPair& sp = rows.pairs[i];
            if (sp.count == 0 || sp.node_a == k_no_node || sp.node_b == k_no_node)
                continue;
            const SoftPoint& first = rows.points[sp.first];
            if (first.a.modal.active() || first.b.modal.active())
                continue;
            const double ma = rigid_mass_along(first.a, first.normal);
            const double mb = rigid_mass_along(first.b, first.normal);
            if (!(std::max(ma, mb) < (1.0 - 1e-9) * k_heavy_mass_ratio * std::min(ma, mb)))
                uneven[part] = 1;
        }
    });
    return std::find(uneven.begin(), uneven.end(), 1) != uneven.end();
}

} // namespace

// Heavy on light: a pair whose upper body (the one farther from the ground in the contact graph, and
// above the other along the normal) is at least k_heavy_mass_ratio times heavier than its lower one along
// the normal has the lower body's
// inverse mass and inertia in its rows scaled down to look as heavy as the upper one. Gauss–Seidel moves
// a heavy body on a light one by the light one's effective mass per pass (it converges by the mass ratio
// per pass, 0.999 at 1000), so an impact is never stopped and the light body is squeezed out; scaled,
// the pair converges like an equal-mass one. The lower body then carries the upper one as part of the
// ground: it is pushed by the upper body's change of velocity, not its momentum.
void scale_heavy_on_light(const Parallel& par, SoftContacts& rows)
{
    if (!(rows.gravity > 0.0))
        return;
    if (!any_uneven_pair(par, rows))
        return; // no body rests on a much lighter one: the contact graph is not walked
    std::vector<uint32_t>& nodes = rows.nodes;
    nodes.clear();
    for (const SoftPair& sp : rows.pairs) {
        if (sp.count == 0)
            continue;
        if (sp.node_a != k_no_node)
            nodes.push_back(sp.node_a);
        if (sp.node_b != k_no_node)
            nodes.push_back(sp.node_b);
    }
    radix_sort(nodes, rows.nodes_other, [](uint32_t n) { return uint64_t{n}; });
    nodes.erase(std::unique(nodes.begin(), nodes.end()), nodes.end());
    const std::vector<uint32_t> place = node_places(nodes);
    auto id = [&](uint32_t node) { return static_cast<size_t>(place[node]); };
    const std::vector<uint32_t> level = contact_levels(rows, nodes, place);
    for (SoftPair& sp : rows.pairs) {
        if (sp.count == 0 || sp.node_a == k_no_node || sp.node_b == k_no_node)
            continue;
        const uint32_t la = level[id(sp.node_a)], lb = level[id(sp.node_b)];
        const SoftPoint& first = rows.points[sp.first];
        if (la == 0 || lb == 0 || la == lb || first.a.modal.active() || first.b.modal.active())
            continue;
        const bool a_lower = la < lb;
        if (dot(first.normal, rows.up) * (a_lower ? -1.0 : 1.0) < k_heavy_min_uprightness)
            continue; // not resting on it: a body thrown against a light one keeps its momentum
        const double ratio = side_mass_along(a_lower ? first.b : first.a, first.normal) /
                             side_mass_along(a_lower ? first.a : first.b, first.normal);
        if (!(ratio >= k_heavy_mass_ratio) || !std::isfinite(ratio))
            continue;
        for (uint32_t i = 0; i < sp.count; ++i) {
            SoftPoint& p = rows.points[sp.first + i];
            Side& lower = a_lower ? p.a : p.b;
            lower.inv_mass /= ratio;
            lower.inv_inertia = add_scaled(Mat3{}, lower.inv_inertia, 1.0 / ratio);
            set_point_masses(p); // both rigid here (modal pairs are not scaled)
        }
    }
}

} // namespace supermodal
