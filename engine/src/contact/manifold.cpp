// SPDX-License-Identifier: MIT
#include "contact/manifold.h"

#include "contact/face_contact.h"
#include "contact/mpr.h"
#include "contact/penetration.h"

#include <algorithm>
#include <cmath>
#include <span>

namespace supermodal
{
namespace
{

// Two points closer than this (fraction of the smaller body's smallest radius) are the same contact:
// a fresh one replaces the old. Old points that slid apart by more than this are dropped.
constexpr double k_merge_rel = 0.1;
// Old points lifted off by more than this (fraction of the smallest radius) are dropped.
constexpr double k_separate_rel = 0.02;
// A speculative caller's face patches reach where the surfaces have dropped by this (fraction of the
// smaller smallest radius) [-] while apart, and once touching at most nine tenths of the overlap
// (face_contact.cpp, least_patch_drop): a face resting on the tiny overlap of a stiff soft contact still
// stands on its corners (one point at its pole let a resting ε = 0.5 body rock and gain energy at a
// 0.2 ms step, measured). Its points within k_separate_rel of touching are rows, also of bodies not touching
// yet: boxes of a column placed touching fell freely until each pair overlapped, a cascade that took
// 14 steps to reach the top at 1/60 s (measured).
constexpr double k_face_patch_rel = 1e-3;
// Tilts of the support direction towards a face diagonal, largest first: on an ε = 0.3 face they reach
// 1.0, 0.67, 0.44, 0.30 of the way to the edge (x/a = t^(ε/(2−ε))), so the outermost point still inside
// the other body marks the edge of the patch; on a sharp box (ε ≤ 0.1) every tilt gives the corner.
constexpr double k_tilts[] = {1.0, 0.1, 0.01, 0.001};
// A tilted candidate counts only if it is at least this fraction of the pair's depth deep: the
// outermost points of a patch barely touch (a rounded corner sits above the face), and four of them
// would carry the body's weight at a sink far below the face. With it the pair's weighted mean depth
// is within a factor 2 of the deepest.
constexpr double k_min_depth_ratio = 0.5;
// Bodies with an exponent below this have flat faces and get tilted candidates; rounder ones touch in
// one point (a sphere's tilted supports only crowd the deepest point).
constexpr double k_flat_exponent = 0.8;

struct Candidate {
    Vec3 pa, pb;  // the contact as a point of A and of B [m], world
    double depth; // along the normal [m]
};

double smallest_radius(const Collider& c)
{
    const Vec3& r = c.shape.radii;
    return std::min({r.x, r.y, r.z});
}

bool has_flat_faces(const Collider& c)
{
    return std::min(c.shape.epsilon1, c.shape.epsilon2) < k_flat_exponent;
}

// Points carried from earlier substeps steady a flat face: its corners rest on springs of their own.
// A smooth body touches at its support point alone, whose spring is the gradient of ½k·depth² (the
// support point's motion is the depth's rate). Carried points there are the earlier deepest points,
// rolled aside: springs that join deep and leave shallow, not the gradient of any potential. A thin
// ε = 1.5 disc landing on its rim gained up to 63% of its drop energy with them (docs/stability.md).
bool keeps_old_points(const Collider& a, const Collider* b)
{
    return has_flat_faces(a) || (b != nullptr && has_flat_faces(*b));
}

Vec3 to_world(const BodyView& body, const Vec3& local)
{
    return body.position + rotate(body.orientation, local);
}

Vec3 to_body(const BodyView& body, const Vec3& world)
{
    return inv_rotate(body.orientation, world - body.position);
}

// Calls accept(support point) along `dir` tilted towards each of the four diagonals of the body's face
// that faces `dir`, largest tilt first, until accept says the point is in contact.
template <class Accept>
void tilted_supports(const BodyView& body, const Vec3& dir, int& calls, Accept&& accept)
{
    const Vec3 axes[3] = {rotate(body.orientation, {1, 0, 0}), rotate(body.orientation, {0, 1, 0}),
                          rotate(body.orientation, {0, 0, 1})};
    int k = 0;
    for (int i = 1; i < 3; ++i)
        if (std::abs(dot(axes[i], dir)) > std::abs(dot(axes[k], dir)))
            k = i;
    const Vec3 e = axes[(k + 1) % 3];
    const Vec3 u = normalized(e - dot(e, dir) * dir), v = cross(dir, u);
    for (int s = 0; s < 4; ++s) {
        const Vec3 diagonal = ((s & 1) != 0 ? u : -u) + ((s & 2) != 0 ? v : -v);
        for (double t : k_tilts) {
            ++calls;
            if (accept(body_support(body, dir + t * diagonal)))
                break;
        }
    }
}

// Depth of a world point inside a convex body along its own surface normal (first order), or < 0.
double depth_inside(const BodyView& body, const Vec3& p)
{
    const Collider& c = *body.collider;
    const InsideTest t = test_point(c, to_body(body, p) + c.com_shape);
    return t.inside ? t.depth : -1.0;
}

void add_unique(std::vector<Candidate>& list, const Candidate& c, double merge)
{
    for (const Candidate& other : list)
        if (length(other.pa - c.pa) < merge)
            return;
    list.push_back(c);
}

// Whether p (in the contact plane with normal n) lies in the triangle abc, edges included.
bool in_triangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& n)
{
    const double s1 = dot(cross(b - a, p - a), n), s2 = dot(cross(c - b, p - b), n);
    const double s3 = dot(cross(a - c, p - c), n);
    return (s1 >= 0.0 && s2 >= 0.0 && s3 >= 0.0) || (s1 <= 0.0 && s2 <= 0.0 && s3 <= 0.0);
}

// Keeps the deepest point and the three that span the largest area with it in the contact plane;
// then, if a fourth spare point makes a quadrilateral with those three that contains the deepest (a
// flat face's centre inside its corners) and touches, the spare replaces it: the patch's outline holds
// the body better than its middle.
void reduce(std::vector<Candidate>& pts, const Vec3& n)
{
    if (pts.size() <= PairManifold::k_capacity)
        return;
    auto plane = [&](const Vec3& p) { return p - dot(p, n) * n; };
    auto pick = [&](auto&& score) {
        size_t best = 0;
        double best_score = -1.0;
        for (size_t i = 0; i < pts.size(); ++i)
            if (const double s = score(plane(pts[i].pa)); s > best_score) {
                best = i;
                best_score = s;
            }
        return best;
    };
    std::vector<Candidate> kept;
    auto take = [&](size_t i) {
        kept.push_back(pts[i]);
        pts.erase(pts.begin() + static_cast<std::ptrdiff_t>(i));
    };
    size_t deepest = 0;
    for (size_t i = 1; i < pts.size(); ++i)
        if (pts[i].depth > pts[deepest].depth)
            deepest = i;
    take(deepest);
    const Vec3 p0 = plane(kept[0].pa);
    take(pick([&](const Vec3& p) { return dot(p - p0, p - p0); }));
    const Vec3 p1 = plane(kept[1].pa);
    take(pick([&](const Vec3& p) { return length(cross(p1 - p0, p - p0)); }));
    const Vec3 p2 = plane(kept[2].pa);
    auto quad_score = [&](const Vec3& a, const Vec3& b, const Vec3& c) {
        return [&, a, b, c](const Vec3& p) {
            return length(cross(a - p, b - p)) + length(cross(b - p, c - p)) + length(cross(c - p, a - p));
        };
    };
    take(pick(quad_score(p0, p1, p2)));
    const Vec3 p3 = plane(kept[3].pa);
    if (!pts.empty()) {
        const Candidate spare = pts[pick(quad_score(p1, p2, p3))];
        const Vec3 q = plane(spare.pa);
        // Only a touching spare: a speculative corner in place of the deepest would leave nothing
        // touching, and the body would sink until its corners close their gap.
        if (spare.depth > 0.0 && (in_triangle(p0, p1, p2, p3, n) || in_triangle(p0, p1, p2, q, n) ||
                                  in_triangle(p0, p2, p3, q, n) || in_triangle(p0, p1, p3, q, n)))
            kept[0] = spare;
    }
    pts.swap(kept);
}

// Orders the kept points so that a contact the manifold held before keeps its place among them (points
// matched by their material point on A within `merge`, in the old order; new points after), so a
// solver can carry per-point data from one substep to the next.
void keep_slots(const BodyView& a, const PairManifold& old, std::vector<Candidate>& pts, double merge)
{
    std::array<int, 16> rank{};
    for (size_t i = 0; i < pts.size() && i < rank.size(); ++i) {
        const Vec3 local = to_body(a, pts[i].pa);
        rank[i] = PairManifold::k_capacity + static_cast<int>(i);
        for (int s = 0; s < old.count; ++s)
            if (length(local - old.points[static_cast<size_t>(s)].local_a) < merge) {
                rank[i] = s;
                break;
            }
    }
    std::vector<size_t> order(pts.size());
    for (size_t i = 0; i < order.size(); ++i)
        order[i] = i;
    std::stable_sort(order.begin(), order.end(), [&](size_t x, size_t y) { return rank[x] < rank[y]; });
    std::vector<Candidate> sorted;
    sorted.reserve(pts.size());
    for (size_t i : order)
        sorted.push_back(pts[i]);
    pts.swap(sorted);
}

// Appends the touching points with equal weights (and, with `speculative`, the others with weight 0 and
// their gap as a negative depth), in order; returns how many.
int append_points(std::span<const Candidate> pts, const Vec3& n, bool flip, bool speculative,
                  std::vector<ContactPoint>& out)
{
    int touching = 0;
    for (const Candidate& c : pts)
        touching += c.depth > 0.0 ? 1 : 0;
    for (const Candidate& c : pts)
        if (c.depth > 0.0)
            out.push_back({0.5 * (c.pa + c.pb), flip ? -n : n, c.depth, 1.0 / touching, 1.0});
        else if (speculative)
            out.push_back({0.5 * (c.pa + c.pb), flip ? -n : n, c.depth, 0.0, 1.0});
    return speculative ? static_cast<int>(pts.size()) : touching;
}

// Merges fresh candidates with the surviving old points, reduces to capacity, stores, and appends the
// touching points with equal weights (and, with `speculative`, the kept points not touching, with
// weight 0 and their gap as a negative depth).
int finish(const BodyView& a, const BodyView* b, std::vector<Candidate>& fresh, std::vector<Candidate>& old,
           const Vec3& n, double merge, bool flip, bool speculative, PairManifold& io,
           std::vector<ContactPoint>& out)
{
    for (const Candidate& c : old)
        add_unique(fresh, c, merge);
    reduce(fresh, n);
    io.count = static_cast<int>(fresh.size());
    for (size_t i = 0; i < fresh.size(); ++i) {
        io.points[i].local_a = to_body(a, fresh[i].pa);
        io.points[i].local_b = b != nullptr ? to_body(*b, fresh[i].pb) : Vec3{};
    }
    return append_points(fresh, n, flip, speculative, out);
}

// The manifold's points that still touch (or nearly): material points of both bodies, re-measured along
// today's normal, dropped once lifted off or slid apart. None when `keep` is false (smooth pairs).
std::vector<Candidate> carried_points(const BodyView& a, const BodyView& b, const PairManifold& io,
                                      const Vec3& n, double r, bool keep)
{
    std::vector<Candidate> old;
    const double merge = k_merge_rel * r;
    for (int i = 0; keep && i < io.count; ++i) {
        const Vec3 pa = to_world(a, io.points[i].local_a), pb = to_world(b, io.points[i].local_b);
        const double depth = dot(pb - pa, n);
        const Vec3 slide = (pb - pa) - depth * n;
        if (depth > -k_separate_rel * r && length(slide) < merge)
            old.push_back({pa, pb, depth});
    }
    return old;
}

// A face query's points (with `speculative`, also the carried points `old` that no longer touch) as the
// manifold: reduced to capacity, in their old slots, stored, appended.
int finish_faces(const BodyView& a, const BodyView* b, const FaceContact& fc, std::vector<Candidate>& old,
                 double merge, bool flip, bool speculative, PairManifold& io, std::vector<ContactPoint>& out)
{
    std::vector<Candidate> fresh, none;
    for (int i = 0; i < fc.count; ++i) {
        const FacePoint& p = fc.points[static_cast<size_t>(i)];
        add_unique(fresh, {p.on_a, p.on_b, p.depth}, merge);
    }
    for (const Candidate& c : old)
        if (speculative && !(c.depth > 0.0))
            add_unique(fresh, c, merge);
    if (fresh.empty()) {
        io.count = 0;
        return 0;
    }
    reduce(fresh, fc.normal);
    keep_slots(a, io, fresh, merge);
    return finish(a, b, fresh, none, fc.normal, merge, flip, speculative, io, out);
}

// A body's extent along a world direction, h(d) = max d·x [m]: from its pole when d is one of its face
// axes (no evaluation: a face found apart is stored as exactly its axis), else its support point.
double extent_along(const BodyView& body, const Vec3& d, int& calls)
{
    const Collider& c = *body.collider;
    const Vec3 local = inv_rotate(body.orientation, d);
    for (int k = 0; k < 3; ++k) {
        const Vec3 rest = local - local[k] * Vec3{k == 0 ? 1.0 : 0.0, k == 1 ? 1.0 : 0.0, k == 2 ? 1.0 : 0.0};
        if (length(rest) < 1e-12) {
            Vec3 pole;
            pole[k] = (local[k] < 0.0 ? -1.0 : 1.0) * c.shape.radii[k];
            return dot(d, to_world(body, pole - c.com_shape));
        }
    }
    ++calls;
    return dot(d, body_support(body, d));
}

// Overlap of the two bodies along n (from B towards A): h_B(n) + h_A(−n) [m]; ≤ 0 proves them apart.
double overlap_along(const BodyView& a, const BodyView& b, const Vec3& n, int& calls)
{
    return extent_along(b, n, calls) + extent_along(a, -1.0 * n, calls);
}

// Largest distance of a body's surface from its centre of mass [m]: its support function changes by at
// most this times the turn of the direction (in radians, for small turns the chord).
double reach(const Collider& c)
{
    const Vec3 far{std::max(std::abs(c.local_box.min.x), std::abs(c.local_box.max.x)),
                   std::max(std::abs(c.local_box.min.y), std::abs(c.local_box.max.y)),
                   std::max(std::abs(c.local_box.min.z), std::abs(c.local_box.max.z))};
    return length(far);
}

// Relative round-off allowed in a proof's bound, of the positions' and bodies' scale [-].
constexpr double k_proof_round_off = 1e-12;

// Whether the pair's proof still holds: the overlap along the normal, n·(B's offset in A's frame) plus
// each body's extent along it, can have grown since by at most the offset's change along n plus B's
// reach times the normal's turn in B's frame (A's extent along its own frame's normal is unchanged).
// A proof of the pair apart by `overlap` along `normal` (A's frame) at the bodies' present pose: B's
// offset in A's frame and the normal in B's frame.
PairManifold::ApartProof proof_at(const BodyView& a, const BodyView& b, const Vec3& normal, double overlap)
{
    return {a.collider,
            b.collider,
            normal,
            to_body(a, b.position),
            inv_rotate(b.orientation, rotate(a.orientation, normal)),
            overlap};
}

bool still_apart(const BodyView& a, const BodyView& b, const PairManifold& io, double gap)
{
    const PairManifold::ApartProof& p = io.apart;
    if (p.a != a.collider || p.b != b.collider || !(p.normal == io.normal))
        return false;
    const PairManifold::ApartProof now = proof_at(a, b, io.normal, 0.0);
    const double reach_b = reach(*b.collider);
    const double scale = length(a.position) + length(b.position) + reach(*a.collider) + reach_b;
    const double bound = p.overlap + dot(io.normal, now.offset - p.offset) +
                         reach_b * length(now.normal_b - p.normal_b) + k_proof_round_off * scale;
    return bound < -gap;
}

// Two bodies with face patches (face_contact.h). A pair found apart at the last substep first tries the
// direction that separated it (two evaluations, none while its proof holds). Returns the points
// appended, or −1 when the general path must decide.
int collide_faces(const BodyView& a, const BodyView& b, double r, bool speculative, PairManifold& io,
                  std::vector<ContactPoint>& out, int& calls)
{
    const double gap = speculative ? k_separate_rel * r : 0.0;
    const Vec3 stored = rotate(a.orientation, io.normal);
    const bool has_normal = length(io.normal) > 0.0;
    if (io.count == 0 && has_normal) {
        if (still_apart(a, b, io, gap))
            return 0;
        if (const double overlap = overlap_along(a, b, stored, calls); !(overlap > -gap)) {
            io.apart = proof_at(a, b, io.normal, overlap);
            return 0; // still apart along it
        }
    }
    const Vec3 guess = has_normal ? stored : body_shape_centre(a) - body_shape_centre(b);
    const FaceContact fc =
        face_contact(a, b, normalized(guess), gap, speculative ? k_face_patch_rel * r : 0.0);
    calls += fc.support_calls;
    // A speculative solver keeps the corners that lifted by less than the kept gap as rows: a resting
    // face whose corners flicker between touching and not keeps its support on all of them.
    std::vector<Candidate> old;
    if (speculative && fc.kind != FaceContact::Kind::NotFaces)
        old = carried_points(a, b, io, fc.normal, r, true);
    switch (fc.kind) {
    case FaceContact::Kind::Apart:
    case FaceContact::Kind::Faces: {
        const int n = finish_faces(a, &b, fc, old, k_merge_rel * r, false, speculative, io, out);
        io.normal = inv_rotate(a.orientation, fc.normal);
        return n;
    }
    case FaceContact::Kind::Edge: {
        // Edges crossing touch in one point; points carried from earlier substeps hold edges that lie
        // along each other.
        std::vector<Candidate> old = carried_points(a, b, io, fc.normal, r, true);
        std::vector<Candidate> fresh{{fc.points[0].on_a, fc.points[0].on_b, fc.points[0].depth}};
        io.normal = inv_rotate(a.orientation, fc.normal);
        return finish(a, &b, fresh, old, fc.normal, k_merge_rel * r, false, speculative, io, out);
    }
    case FaceContact::Kind::NotFaces:
        break;
    }
    return -1;
}

// B's pose in A's frame (the body's world pose when B is a plane).
struct RelativePose {
    Vec3 offset{}; // [m]
    Quat turn{};
};

RelativePose relative_pose(const BodyView& a, const BodyView* b)
{
    if (b == nullptr)
        return {a.position, a.orientation};
    return {to_body(a, b->position), conjugate(a.orientation) * b->orientation};
}

// Whether the pair is still within the reuse tolerances of its last full query.
bool within_reuse(const PairManifold& io, const RelativePose& now, double r)
{
    if (io.steady < k_manifold_steady_queries || io.count == 0)
        return false;
    const double move = k_manifold_reuse_move_rel * r;
    const Vec3 d = now.offset - io.query_offset;
    const Quat turn = conjugate(io.query_turn) * now.turn; // sin(angle/2) is its vector part's length
    const double half_sin = std::sin(0.5 * k_manifold_reuse_turn);
    return dot(d, d) <= move * move &&
           turn.x * turn.x + turn.y * turn.y + turn.z * turn.z <= half_sin * half_sin;
}

// After a full query: the pose it was made at, and whether it found the points and normal the one
// before it did (k_manifold_steady_queries).
void remember_query(PairManifold& io, const PairManifold& before, const RelativePose& now, double r)
{
    const double move = k_manifold_reuse_move_rel * r;
    bool same = io.count > 0 && io.count == before.count;
    for (int i = 0; same && i < io.count; ++i) {
        const Vec3 d =
            io.points[static_cast<size_t>(i)].local_a - before.points[static_cast<size_t>(i)].local_a;
        const Vec3 e =
            io.points[static_cast<size_t>(i)].local_b - before.points[static_cast<size_t>(i)].local_b;
        same = dot(d, d) <= move * move && dot(e, e) <= move * move;
    }
    const Vec3 dn = io.normal - before.normal;
    io.steady = same && dot(dn, dn) <= k_manifold_reuse_turn * k_manifold_reuse_turn ? io.steady + 1 : 0;
    io.query_offset = now.offset;
    io.query_turn = now.turn;
}

// The stored points where the bodies carried them, measured along the stored normal n (from B towards
// A, world; against the plane n·x = plane_offset when b is null), appended as finish does.
int remeasure(const BodyView& a, const BodyView* b, const Vec3& n, double plane_offset, bool flip,
              bool speculative, const PairManifold& io, std::vector<ContactPoint>& out)
{
    std::array<Candidate, PairManifold::k_capacity> pts{};
    for (int i = 0; i < io.count; ++i) {
        const ManifoldPoint& m = io.points[static_cast<size_t>(i)];
        Candidate& c = pts[static_cast<size_t>(i)];
        c.pa = to_world(a, m.local_a);
        if (b != nullptr) {
            c.pb = to_world(*b, m.local_b);
            c.depth = dot(c.pb - c.pa, n);
        } else {
            c.depth = plane_offset - dot(n, c.pa);
            c.pb = c.pa + c.depth * n;
        }
    }
    return append_points(std::span<const Candidate>(pts.data(), static_cast<size_t>(io.count)), n, flip,
                         speculative, out);
}

int query_manifold(const BodyView& a, const BodyView& b, PairManifold& io, std::vector<ContactPoint>& out,
                   bool speculative, QueryCost* io_cost)
{
    QueryCost unused;
    int& calls = (io_cost != nullptr ? *io_cost : unused).support_calls;
    const double r = std::min(smallest_radius(*a.collider), smallest_radius(*b.collider));
    if (has_face_patches(*a.collider) && has_face_patches(*b.collider)) {
        const int done = collide_faces(a, b, r, speculative, io, out, calls);
        if (done >= 0)
            return done;
    }
    // Every pair searches from its last normal (penetration.h; MPR where there is none or that fails):
    // a resting or slowly turning pair converges in a few evaluations where MPR takes dozens (the
    // ellipsoid pile: 38.8 → 4.9 evaluations per touching pair), and its normal is the exact one (libccd's
    // is off it by up to 0.4 rad at 1 mm overlaps of the pile's ellipsoids).
    const bool flat = keeps_old_points(*a.collider, b.collider);
    // Bodies with face patches get here on rounded edges and corners, where the least overlap is the
    // contact's own normal and MPR's centre ray often leaves through another face of B − A. A flat pair
    // apart starts from its separating direction only with face patches; a smooth one always does.
    const bool faces = has_face_patches(*a.collider) && has_face_patches(*b.collider);
    const bool warm_start = flat ? io.count > 0 || faces : true;
    const Vec3 warm = warm_start ? rotate(a.orientation, io.normal) : Vec3{};
    const PenetrationTarget target = faces ? PenetrationTarget::LeastOverlap : PenetrationTarget::RayExit;
    const Penetration pen = find_penetration(a, b, warm, target);
    calls += pen.support_calls;
    if (!pen.hit) {
        io.count = 0;
        // A direction the search found apart is where the pair's next query starts.
        io.normal = length(pen.normal) > 0.0 ? inv_rotate(a.orientation, pen.normal) : Vec3{};
        return 0;
    }
    const Vec3 n = pen.normal;
    const double merge = k_merge_rel * r;

    // Old points: material points of both bodies, re-measured along today's normal.
    std::vector<Candidate> old = carried_points(a, b, io, n, r, flat);

    // Fresh points: the deepest point of each body along the normal (the search's last supports), if
    // it lies inside the other (an overhanging face's centre may not), then the tilted supports of flat
    // faces. At the minimum of the overlap the two are one contact, sb = sa + depth·n.
    std::vector<Candidate> fresh;
    const Vec3 sa = pen.on_a, sb = pen.on_b;
    const double depth = pen.depth;
    if (depth_inside(b, sa) > 0.0)
        add_unique(fresh, {sa, sa + depth * n, depth}, merge);
    if (depth_inside(a, sb) > 0.0)
        add_unique(fresh, {sb - depth * n, sb, depth}, merge);
    if (fresh.empty()) // edge on edge: the search's point, halfway between the surfaces
        fresh.push_back({pen.point - 0.5 * depth * n, pen.point + 0.5 * depth * n, depth});
    const double min_depth = k_min_depth_ratio * depth;
    // Tilted candidates every substep, even for a full manifold: keeping only the old material points
    // (refilling when one drops) left points from the first touch near the face centres, and a
    // ten-box stack with them buckled even at 100 Hz (measured). The plane through the other body's
    // support point bounds that body (convex), so a candidate less than min_depth below it cannot be
    // min_depth deep: its inside test is skipped. Two bodies with face patches get here only touching
    // on an edge or a corner (face_contact.h took faces and edges across edges), where the tilted
    // supports add nothing the carried points do not.
    const bool tilt = !(has_face_patches(*a.collider) && has_face_patches(*b.collider));
    if (tilt && has_flat_faces(*a.collider))
        tilted_supports(a, -n, calls, [&](const Vec3& p) {
            if (dot(sb - p, n) < min_depth)
                return false;
            const double d = depth_inside(b, p);
            if (d >= min_depth)
                add_unique(fresh, {p, p + d * n, d}, merge);
            return d >= min_depth;
        });
    if (tilt && has_flat_faces(*b.collider))
        tilted_supports(b, n, calls, [&](const Vec3& p) {
            if (dot(p - sa, n) < min_depth)
                return false;
            const double d = depth_inside(a, p);
            if (d >= min_depth)
                add_unique(fresh, {p - d * n, p, d}, merge);
            return d >= min_depth;
        });
    io.normal = inv_rotate(a.orientation, n);
    return finish(a, &b, fresh, old, n, merge, false, speculative, io, out);
}

int query_manifold_plane(const BodyView& body, const BodyView& plane, bool body_is_a, PairManifold& io,
                         std::vector<ContactPoint>& out, bool speculative, QueryCost* io_cost)
{
    QueryCost unused;
    int& calls = (io_cost != nullptr ? *io_cost : unused).support_calls;
    // The plane's support along −n is exact: no MPR. Depths are exact for every material point.
    const Vec3 n = normalized(plane.collider->shape.plane_normal);
    const double offset = plane.collider->shape.plane_offset;
    const double r = smallest_radius(*body.collider);
    const double merge = k_merge_rel * r;
    auto candidate = [&](const Vec3& p) {
        return Candidate{p, p + (offset - dot(n, p)) * n, offset - dot(n, p)};
    };
    std::vector<Candidate> old;
    const int carried = keeps_old_points(*body.collider, nullptr) ? io.count : 0;
    for (int i = 0; i < carried; ++i) {
        const Candidate c = candidate(to_world(body, io.points[i].local_a));
        if (c.depth > -k_separate_rel * r)
            old.push_back(c);
    }
    if (has_face_patches(*body.collider)) {
        const FaceContact fc = face_contact_plane(body, n, offset, speculative ? k_separate_rel * r : 0.0,
                                                  speculative ? k_face_patch_rel * r : 0.0);
        calls += fc.support_calls;
        if (fc.kind == FaceContact::Kind::Apart || fc.kind == FaceContact::Kind::Faces)
            return finish_faces(body, nullptr, fc, old, merge, !body_is_a, speculative, io, out);
    }
    // The support point is the body's deepest: when it is out (by more than the kept gap, speculative),
    // every point is.
    const Candidate deepest = candidate(body_support(body, -n));
    ++calls;
    if (!(deepest.depth > (speculative ? -k_separate_rel * r : 0.0))) {
        io.count = 0;
        return 0;
    }
    std::vector<Candidate> fresh{deepest};
    if (has_flat_faces(*body.collider))
        tilted_supports(body, -n, calls, [&](const Vec3& p) {
            const Candidate c = candidate(p);
            const bool deep = c.depth >= k_min_depth_ratio * deepest.depth;
            if (deep)
                add_unique(fresh, c, merge);
            return deep;
        });
    return finish(body, nullptr, fresh, old, n, merge, !body_is_a, speculative, io, out);
}

} // namespace

double manifold_reuse_bound(double r, double reach)
{
    return 2.0 * (k_manifold_reuse_move_rel * r + reach * k_manifold_reuse_turn);
}

double speculative_gap(const Collider& a, const Collider& b)
{
    return k_separate_rel * std::min(smallest_radius(a), smallest_radius(b));
}

int collide_manifold(const BodyView& a, const BodyView& b, PairManifold& io, std::vector<ContactPoint>& out,
                     bool speculative, QueryCost* io_cost)
{
    // Bodies with face patches rest on their stored points while the pair barely moves; smooth bodies
    // roll their contact along, which a fixed pair of material points does not follow.
    if (!(has_face_patches(*a.collider) && has_face_patches(*b.collider)))
        return query_manifold(a, b, io, out, speculative, io_cost);
    const double r = std::min(smallest_radius(*a.collider), smallest_radius(*b.collider));
    const RelativePose now = relative_pose(a, &b);
    if (within_reuse(io, now, r))
        return remeasure(a, &b, rotate(a.orientation, io.normal), 0.0, false, speculative, io, out);
    const PairManifold before = io;
    const int appended = query_manifold(a, b, io, out, speculative, io_cost);
    remember_query(io, before, now, r);
    return appended;
}

int collide_manifold_plane(const BodyView& body, const BodyView& plane, bool body_is_a, PairManifold& io,
                           std::vector<ContactPoint>& out, bool speculative, QueryCost* io_cost)
{
    if (!has_face_patches(*body.collider))
        return query_manifold_plane(body, plane, body_is_a, io, out, speculative, io_cost);
    const RelativePose now = relative_pose(body, nullptr);
    const double r = smallest_radius(*body.collider);
    if (within_reuse(io, now, r))
        return remeasure(body, nullptr, normalized(plane.collider->shape.plane_normal),
                         plane.collider->shape.plane_offset, !body_is_a, speculative, io, out);
    const PairManifold before = io;
    const int appended = query_manifold_plane(body, plane, body_is_a, io, out, speculative, io_cost);
    remember_query(io, before, now, r);
    return appended;
}

} // namespace supermodal
