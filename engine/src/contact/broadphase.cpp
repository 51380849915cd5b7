// SPDX-License-Identifier: MIT
#include "contact/broadphase.h"

#include <algorithm>

namespace supermodal
{

bool overlaps(const Aabb& a, const Aabb& b)
{
    return a.min.x <= b.max.x && b.min.x <= a.max.x && a.min.y <= b.max.y && b.min.y <= a.max.y &&
           a.min.z <= b.max.z && b.min.z <= a.max.z;
}

namespace
{

// Sweep along the axis where box centres spread most, so the active list stays short for piles that
// are wide but flat (or tall but thin).
int sweep_axis(std::span<const BroadphaseProxy> proxies)
{
    Vec3 sum{}, sum_sq{};
    for (const BroadphaseProxy& p : proxies) {
        const Vec3 c = 0.5 * (p.box.min + p.box.max);
        sum += c;
        sum_sq += hadamard(c, c);
    }
    const double n = static_cast<double>(proxies.size());
    const Vec3 var = sum_sq / n - hadamard(sum / n, sum / n);
    return var.x >= var.y ? (var.x >= var.z ? 0 : 2) : (var.y >= var.z ? 1 : 2);
}

} // namespace

void find_overlapping_pairs(std::span<const BroadphaseProxy> proxies, BroadphaseScratch& io_scratch,
                            std::vector<BodyPair>& out_pairs)
{
    out_pairs.clear();
    if (proxies.size() < 2)
        return;
    const int axis = sweep_axis(proxies);
    std::vector<uint32_t>& order = io_scratch.order;
    order.resize(proxies.size());
    for (uint32_t i = 0; i < order.size(); ++i)
        order[i] = i;
    // Total order (box min, then entity index): the result cannot depend on sort stability.
    std::sort(order.begin(), order.end(), [&](uint32_t l, uint32_t r) {
        const double lm = proxies[l].box.min[axis], rm = proxies[r].box.min[axis];
        return lm != rm ? lm < rm : proxies[l].entity.index < proxies[r].entity.index;
    });
    for (size_t i = 0; i < order.size(); ++i) {
        const BroadphaseProxy& p = proxies[order[i]];
        const double reach = p.box.max[axis];
        for (size_t j = i + 1; j < order.size(); ++j) {
            const BroadphaseProxy& q = proxies[order[j]];
            if (q.box.min[axis] > reach)
                break;
            if ((p.is_static && q.is_static) || !overlaps(p.box, q.box))
                continue;
            out_pairs.push_back(p.entity.index < q.entity.index ? BodyPair{p.entity, q.entity}
                                                                : BodyPair{q.entity, p.entity});
        }
    }
    std::sort(out_pairs.begin(), out_pairs.end(),
              [](const BodyPair& l, const BodyPair& r) { return l.key() < r.key(); });
}

} // namespace supermodal
