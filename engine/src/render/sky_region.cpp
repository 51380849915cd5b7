// SPDX-License-Identifier: MIT
#include "render/sky_region.h"

#include <cmath>
#include <cstddef>

namespace supermodal::render
{
namespace
{

// Sutherland–Hodgman: the part of a convex polygon where d(p) >= 0, d linear.
template <class Point, class Dist> std::vector<Point> clip(const std::vector<Point>& poly, Dist d)
{
    std::vector<Point> out;
    for (size_t i = 0; i < poly.size(); ++i) {
        const Point& a = poly[i];
        const Point& b = poly[(i + 1) % poly.size()];
        const double da = d(a), db = d(b);
        if (da >= 0.0)
            out.push_back(a);
        if ((da >= 0.0) != (db >= 0.0)) {
            const double t = da / (da - db);
            Point p = a;
            for (size_t k = 0; k < std::size(a); ++k)
                p[k] = a[k] + t * (b[k] - a[k]);
            out.push_back(p);
        }
    }
    return out;
}

using V2 = std::array<double, 2>;

void fan(const std::vector<V2>& poly, std::vector<float>& out)
{
    for (size_t i = 1; i + 1 < poly.size(); ++i)
        for (const V2& p : {poly[0], poly[i], poly[i + 1]})
            out.insert(out.end(), {static_cast<float>(p[0]), static_cast<float>(p[1])});
}

} // namespace

std::vector<float> sky_triangles(const std::vector<ClipPoint>& ground, double margin)
{
    // GL keeps -w <= z <= w: cut at the near and the far plane, then divide.
    std::vector<ClipPoint> cut = clip(ground, [](const ClipPoint& p) { return p[2] + p[3]; });
    cut = clip(cut, [](const ClipPoint& p) { return p[3] - p[2]; });
    std::vector<V2> poly;
    for (const ClipPoint& p : cut)
        poly.push_back({p[0] / p[3], p[1] / p[3]});
    double area2 = 0.0; // twice the signed area: > 0 when counter-clockwise
    for (size_t i = 0; i < poly.size(); ++i) {
        const V2 &a = poly[i], &b = poly[(i + 1) % poly.size()];
        area2 += a[0] * b[1] - b[0] * a[1];
    }
    const std::vector<V2> viewport = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
    std::vector<float> out;
    if (poly.size() < 3 || std::abs(area2) < 1e-12) {
        fan({{-1, -1}, {3, -1}, {-1, 3}}, out);
        return out;
    }
    const double orient = area2 > 0.0 ? 1.0 : -1.0;
    // Region i: outside edge i, inside every earlier edge (less the margin): disjoint, and together
    // the viewport minus the polygon shrunk by the margin.
    std::vector<V2> inside_earlier = viewport;
    for (size_t i = 0; i < poly.size() && !inside_earlier.empty(); ++i) {
        const V2 &a = poly[i], &b = poly[(i + 1) % poly.size()];
        const double ex = b[0] - a[0], ey = b[1] - a[1];
        const double len = std::hypot(ex, ey);
        if (len < 1e-12)
            continue;
        // Signed distance into the polygon, less the margin: >= 0 well inside this edge.
        const auto inside = [&](const V2& p) {
            return orient * (ex * (p[1] - a[1]) - ey * (p[0] - a[0])) / len - margin;
        };
        fan(clip(inside_earlier, [&](const V2& p) { return -inside(p); }), out);
        inside_earlier = clip(inside_earlier, inside);
    }
    return out;
}

} // namespace supermodal::render
