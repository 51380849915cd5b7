// SPDX-License-Identifier: MIT
#include "contact/mpr.h"

#include <algorithm>
#include <ccd/ccd.h>
#include <cmath>
#include <limits>

namespace supermodal
{
namespace
{

static_assert(sizeof(ccd_real_t) == sizeof(double), "libccd must be the double build (Debian's is)");

Vec3 from_ccd(const ccd_vec3_t& v)
{
    return {v.v[0], v.v[1], v.v[2]};
}

void to_ccd(const Vec3& p, ccd_vec3_t* out)
{
    out->v[0] = p.x;
    out->v[1] = p.y;
    out->v[2] = p.z;
}

// One side of a query: the body, the pair's shared count of support calls, the pair's budget of them
// and the query's scale (the largest coordinate either body reaches).
struct Side {
    const BodyView* body;
    // world_from_body and its transpose: a query asks for dozens of supports, and a matrix rotates in
    // half a quaternion's operations.
    Mat3 rotation, inverse;
    int* calls;
    int budget;
    double scale;
};

// Past the budget, each side answers a point far behind its centre (object 1 against the search
// direction, object 2 along it: libccd asks object 2 for -dir), so the Minkowski point lies far on
// the origin's wrong side of every portal and each of libccd's loops ends with "no overlap". The
// shape's centre alone did not always: at 1e41 m rounding let a loop accept it and turn forever.
Vec3 give_up_support(const Side& side, const Vec3& dir)
{
    const double len = length(dir);
    const Vec3 unit = len > 0.0 && std::isfinite(len) ? dir / len : Vec3{1.0, 0.0, 0.0};
    return body_shape_centre(*side.body) - (4.0 * side.scale) * unit;
}

// libccd 2.1 caps only MPR's last phase (max_iterations); portal discovery and refinement loop until
// a tolerance test passes, which rounding can forbid (a 1e14 m body beside a 0.03 m one hung a step
// for minutes, found by the fuzzer). Past the budget every support is give_up_support()'s point, which
// each of libccd's loops finds not beyond the portal, and the query reports no overlap.
void support_cb(const void* obj, const ccd_vec3_t* dir, ccd_vec3_t* out)
{
    const Side& side = *static_cast<const Side*>(obj);
    if (++*side.calls > 2 * side.budget) {
        to_ccd(give_up_support(side, from_ccd(*dir)), out);
        return;
    }
    const BodyView& body = *side.body;
    const Collider& c = *body.collider;
    const Vec3 local = support_point(c.shape, side.inverse * from_ccd(*dir)) - c.com_shape;
    to_ccd(body.position + side.rotation * local, out);
}

void centre_cb(const void* obj, ccd_vec3_t* out)
{
    to_ccd(body_shape_centre(*static_cast<const Side*>(obj)->body), out);
}

// Where a body sits and how far its shape reaches from there: its position's largest coordinate and
// its body-frame box's farthest corner [m].
struct Reach {
    double position = 0.0;
    double extent = 0.0;
};

Reach query_reach(const BodyView& a, const BodyView& b)
{
    auto reach = [](const BodyView& v) {
        const Aabb& box = v.collider->local_box;
        const Vec3& p = v.position;
        return Reach{std::max({std::abs(p.x), std::abs(p.y), std::abs(p.z)}),
                     length(Vec3{std::max(std::abs(box.min.x), std::abs(box.max.x)),
                                 std::max(std::abs(box.min.y), std::abs(box.max.y)),
                                 std::max(std::abs(box.min.z), std::abs(box.max.z))})};
    };
    const Reach ra = reach(a), rb = reach(b);
    return {std::max(ra.position, rb.position), std::max(ra.extent, rb.extent)};
}

double smallest_radius(const Collider& c)
{
    const Vec3& r = c.shape.radii;
    return std::min({r.x, r.y, r.z});
}

} // namespace

Vec3 body_support(const BodyView& body, const Vec3& direction)
{
    const Collider& c = *body.collider;
    const Vec3 local = support_point(c.shape, inv_rotate(body.orientation, direction)) - c.com_shape;
    return body.position + rotate(body.orientation, local);
}

Vec3 body_shape_centre(const BodyView& body)
{
    return body.position - rotate(body.orientation, body.collider->com_shape);
}

MprResult mpr_penetration(const BodyView& a, const BodyView& b, int support_budget)
{
    // libccd's portal loops compare with NaN forever; a non-finite pose has no contact.
    if (!is_finite(a.position) || !is_finite(a.orientation) || !is_finite(b.position) ||
        !is_finite(b.orientation))
        return {};
    ccd_t ccd;
    CCD_INIT(&ccd);
    ccd.support1 = support_cb;
    ccd.support2 = support_cb;
    ccd.center1 = centre_cb;
    ccd.center2 = centre_cb;
    ccd.max_iterations = k_mpr_max_iterations;
    ccd.mpr_tolerance =
        k_mpr_tolerance_rel * std::min(smallest_radius(*a.collider), smallest_radius(*b.collider));
    // Rounding must stay under the tolerance, or libccd's tolerance tests cannot pass (a 1e14 m body
    // beside a 3 cm one, or bodies 1e12 m from the origin): no contact, no search.
    const Reach reach = query_reach(a, b);
    const double rounding = std::numeric_limits<double>::epsilon() *
                            (k_mpr_rounding_position * reach.position + k_mpr_rounding_extent * reach.extent);
    if (!(rounding < ccd.mpr_tolerance))
        return {.gave_up = true};
    ccd_real_t depth = 0.0;
    ccd_vec3_t dir, pos;
    MprResult r;
    int calls = 0; // both sides count: two calls per Minkowski support
    const double scale = reach.position + reach.extent;
    const Mat3 ra = to_mat3(a.orientation), rb = to_mat3(b.orientation);
    const Side side_a{&a, ra, transpose(ra), &calls, support_budget, scale};
    const Side side_b{&b, rb, transpose(rb), &calls, support_budget, scale};
    const int status = ccdMPRPenetration(&side_a, &side_b, &ccd, &depth, &dir, &pos);
    r.support_calls = calls / 2;
    r.gave_up = calls > 2 * support_budget;
    if (status != 0 || r.gave_up)
        return r;
    // libccd's dir moves B out of A (from A towards B); a touching contact has depth 0 and dir 0.
    const Vec3 d = from_ccd(dir);
    const double len = length(d);
    if (!(depth > 0.0) || !std::isfinite(depth) || !(len > 0.0) || !std::isfinite(len))
        return r;
    r.hit = true;
    r.depth = depth;
    r.normal = -d / len;
    r.point = from_ccd(pos);
    return r;
}

} // namespace supermodal
