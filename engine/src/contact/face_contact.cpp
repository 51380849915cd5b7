// SPDX-License-Identifier: MIT
#include "contact/face_contact.h"

#include "contact/mpr.h"
#include "geometry/measure_internal.h"

#include <algorithm>
#include <cmath>

namespace supermodal
{
namespace
{

// A body seen in its shape frame (origin at the shape's centre, not the centre of mass).
struct Frame {
    const BodyView* body = nullptr;
    Mat3 r, rt; // world_from_body and its transpose
    Vec3 com{}; // centre of mass in the shape frame [m]

    [[nodiscard]] Vec3 to_shape(const Vec3& w) const { return rt * (w - body->position) + com; }
    [[nodiscard]] Vec3 to_world(const Vec3& s) const { return body->position + r * (s - com); }
    [[nodiscard]] const ShapeDef& shape() const { return body->collider->shape; }
};

Frame frame_of(const BodyView& body)
{
    const Mat3 r = to_mat3(body.orientation);
    return {&body, r, transpose(r), body.collider->com_shape};
}

// The face of a body whose outward normal is most aligned with a world direction.
struct Face {
    int axis = 0;
    double side = 1.0;
    Vec3 normal{}; // outward, world
    Vec3 pole{};   // the face's pole [m], world
};

Face face_towards(const Frame& f, const Vec3& dir)
{
    const Vec3 local = f.rt * dir;
    int k = 0;
    for (int i = 1; i < 3; ++i)
        if (std::abs(local[i]) > std::abs(local[k]))
            k = i;
    Face face;
    face.axis = k;
    face.side = local[k] < 0.0 ? -1.0 : 1.0;
    face.normal = face.side * f.r.col(k);
    Vec3 pole;
    pole[k] = face.side * f.shape().radii[k];
    face.pole = f.to_world(pole);
    return face;
}

// The shape-frame axes of a face's patch, (k + 1) % 3 and (k + 2) % 3.
int patch_axis(int k, int i)
{
    return (k + 1 + i) % 3;
}

// Corners of a face's patch in the pole's tangent plane, in order round the rectangle [m], world;
// centred on the pole, or beside it under `centre` (a world point) when given.
std::array<Vec3, 4> patch_corners(const Frame& f, const Face& face, const PatchSize& size,
                                  const Vec3* centre = nullptr)
{
    std::array<Vec3, 4> out;
    const double signs[4][2] = {{1, 1}, {-1, 1}, {-1, -1}, {1, -1}};
    const Vec3 middle = centre != nullptr ? f.to_shape(*centre) : Vec3{};
    for (int c = 0; c < 4; ++c) {
        Vec3 p;
        p[face.axis] = face.side * f.shape().radii[face.axis];
        for (int i = 0; i < 2; ++i) {
            const int axis = patch_axis(face.axis, i);
            p[axis] = middle[axis] + signs[c][i] * size.half[i];
        }
        out[static_cast<size_t>(c)] = f.to_world(p);
    }
    return out;
}

// A convex polygon of at most 8 vertices (a quad clipped by four half-spaces).
struct Polygon {
    std::array<Vec3, 8> v{};
    int n = 0;
};

// Keeps the part of the polygon with m·x ≤ c (Sutherland–Hodgman).
Polygon clip(const Polygon& in, const Vec3& m, double c)
{
    Polygon out;
    for (int i = 0; i < in.n; ++i) {
        const Vec3& p = in.v[static_cast<size_t>(i)];
        const Vec3& q = in.v[static_cast<size_t>((i + 1) % in.n)];
        const double dp = dot(m, p) - c, dq = dot(m, q) - c;
        if (dp <= 0.0 && out.n < 8)
            out.v[static_cast<size_t>(out.n++)] = p;
        if ((dp <= 0.0) != (dq <= 0.0) && out.n < 8)
            out.v[static_cast<size_t>(out.n++)] = p + (dp / (dp - dq)) * (q - p);
    }
    return out;
}

// A world point moved onto a face's true surface along the face's axis; false beyond its outline.
bool lift(const Frame& f, const Face& face, const Vec3& world, Vec3& out)
{
    Vec3 s = f.to_shape(world);
    if (!face_height(f.shape(), face.axis, face.side, s))
        return false;
    out = f.to_world(s);
    return true;
}

// Newton iterations of a point moved onto a body along a line, and their stopping measure [-].
constexpr int k_line_iterations = 12;
constexpr double k_line_tolerance = 1e-12;

// A world point moved along `dir` onto the body's surface, where the line q + s·dir first enters it
// (from a point outside, on the side `dir` leaves): Newton on the gauge F^(ε1/2) − 1 along the line,
// which is convex for a convex body, so it closes in from outside without overshooting. False when
// the line misses the body.
bool lift_along(const Frame& f, const Vec3& q, const Vec3& dir, Vec3& out)
{
    const Vec3 start = f.to_shape(q), d = f.rt * dir;
    double s = 0.0;
    for (int i = 0; i < k_line_iterations; ++i) {
        const Vec3 p = start + s * d;
        const MeasurePoint at(f.shape(), p); // the slope below reuses the value's terms
        const double m = at.value();
        if (std::abs(m) <= k_line_tolerance) {
            out = f.to_world(p);
            return true;
        }
        const double slope = dot(at.gradient(), d);
        if (!(slope < 0.0) || !std::isfinite(m))
            return false;
        s -= m / slope;
    }
    return false;
}

// Half-length of the flat part of a body's edges along its shape axis `axis` [m]: the face patch's
// extent along that axis for the given drop.
double flat_half_length(const ShapeDef& shape, int axis, double drop)
{
    return face_patch(shape, (axis + 1) % 3, drop).half[1]; // patch axes of face k: k + 1, k + 2
}

// The body's shape axis most nearly perpendicular to a world direction.
int axis_across(const Frame& f, const Vec3& dir)
{
    const Vec3 local = f.rt * dir;
    int k = 0;
    for (int i = 1; i < 3; ++i)
        if (std::abs(local[i]) < std::abs(local[k]))
            k = i;
    return k;
}

void add_point(FaceContact& fc, const Vec3& on_a, const Vec3& on_b, double depth)
{
    if (fc.count < static_cast<int>(fc.points.size()))
        fc.points[static_cast<size_t>(fc.count++)] = {on_a, on_b, depth};
}

// Drops the vertex whose loss shrinks the polygon least until four are left: the clipped patch of a
// twisted face is an octagon whose vertices come in close pairs, and the manifold keeps four points
// anyway, so this spares the lifts of the other four.
void keep_four(Polygon& poly, const Vec3& normal)
{
    while (poly.n > 4) {
        int drop = 0;
        double least = INFINITY;
        for (int i = 0; i < poly.n; ++i) {
            const Vec3& prev = poly.v[static_cast<size_t>((i + poly.n - 1) % poly.n)];
            const Vec3& next = poly.v[static_cast<size_t>((i + 1) % poly.n)];
            const double area =
                std::abs(dot(cross(poly.v[static_cast<size_t>(i)] - prev, next - prev), normal));
            if (area < least) {
                least = area;
                drop = i;
            }
        }
        for (int i = drop; i + 1 < poly.n; ++i)
            poly.v[static_cast<size_t>(i)] = poly.v[static_cast<size_t>(i + 1)];
        --poly.n;
    }
}

// The reference face's side of the query: its body and face, and the other (incident) body.
struct Reference {
    const Frame* ref;
    const Frame* inc;
    Face face;
    double overlap;  // along face.normal [m]
    Vec3 inc_lowest; // the incident body's support point along −face.normal [m], world
    bool ref_is_a;
    double gap;        // points within this gap [m] count (speculative); 0: only touching ones
    double patch_drop; // the patches' least drop [m]
};

// The least drop [m] a speculative caller's patches reach, both faces together, for faces overlapping by
// `overlap` [m] under the pole: its setting `least` while they are apart, and once they touch at most
// nine tenths of the overlap, so the corners touch too. Corners above the other surface are rows with
// free play: a rounded box resting on a 35 µm overlap with corners set 100 µm up stood on its pole
// alone and rocked from one side of it to the other every step (3 mm/s at 1/240 s, measured).
double least_patch_drop(double least, double overlap)
{
    return overlap > 0.0 ? std::min(least, 0.9 * overlap) : least;
}

// Appends a contact seen from the reference and the incident body, in the query's A, B order.
void add_point(const Reference& r, const Vec3& on_ref, const Vec3& on_inc, double depth, FaceContact& fc)
{
    if (r.ref_is_a)
        add_point(fc, on_ref, on_inc, depth);
    else
        add_point(fc, on_inc, on_ref, depth);
}

// Faces side by side turn to each other by at most this (cosine of the angle between the normals) to
// meet on a strip (offset_points); more tilted, a corner or edge meets the face [-].
constexpr double k_offset_parallel = 0.998;

// Appends the incident point above or below `q` (in the reference face's plane) and the reference's
// point over it when the two overlap by more than `keep`; returns whether it did.
bool strip_point(const Reference& r, const Face& inc_face, const Vec3& q, double keep, FaceContact& fc)
{
    Vec3 on_inc, on_ref;
    if (!lift(*r.inc, inc_face, q, on_inc) || !lift(*r.ref, r.face, on_inc, on_ref))
        return false;
    const double depth = dot(r.face.normal, on_ref - on_inc);
    if (!(depth > keep))
        return false;
    add_point(r, on_ref, on_inc, depth, fc);
    return true;
}

// An interval along a world axis [m].
struct Span {
    double lo = INFINITY, hi = -INFINITY;
    [[nodiscard]] double middle() const { return 0.5 * (lo + hi); }
};

// The extent along world axis `e` of a face's patch of half-sizes `size` round its pole (the box of the
// rectangle turned about the normal, for a face nearly parallel to e's plane).
Span patch_span(const Frame& f, const Face& face, const PatchSize& size, const Vec3& e)
{
    double half = 0.0;
    for (int i = 0; i < 2; ++i)
        half += std::abs(dot(e, f.r.col(patch_axis(face.axis, i)))) * size.half[i];
    const double centre = dot(e, face.pole);
    return {centre - half, centre + half};
}

// Where two parallel faces' outlines overlap, along the reference's patch axes: the axes, the spans,
// and the overlap's middle in the incident pole's plane; false when they do not overlap (or are not
// parallel).
struct SideBySide {
    Face inc_face;
    Vec3 axes[2];
    Span outline[2];
    Vec3 middle{};
};

bool outlines_overlap(const Reference& r, const Face& inc_face, SideBySide& out)
{
    out.inc_face = inc_face;
    if (!(dot(out.inc_face.normal, r.face.normal) < -k_offset_parallel))
        return false;
    PatchSize ref_outline, inc_outline;
    for (int i = 0; i < 2; ++i) {
        ref_outline.half[i] = r.ref->shape().radii[patch_axis(r.face.axis, i)];
        inc_outline.half[i] = r.inc->shape().radii[patch_axis(out.inc_face.axis, i)];
    }
    out.middle = dot(r.face.normal, out.inc_face.pole) * r.face.normal;
    for (int i = 0; i < 2; ++i) {
        out.axes[i] = r.ref->r.col(patch_axis(r.face.axis, i));
        const Span a = patch_span(*r.ref, r.face, ref_outline, out.axes[i]);
        const Span b = patch_span(*r.inc, out.inc_face, inc_outline, out.axes[i]);
        out.outline[i] = {std::max(a.lo, b.lo), std::min(a.hi, b.hi)};
        if (!(out.outline[i].hi > out.outline[i].lo))
            return false;
        out.middle = out.middle + out.outline[i].middle() * out.axes[i];
    }
    return true;
}

// Parallel faces side by side, the incident body not under the reference's pole (a box resting across
// two below it). Along each of the reference's patch axes the contact spans where both faces' flat
// parts overlap (a sharp box's whole overlap); where they do not (a rounded box's drops towards its
// edges meet), it narrows to the middle of where the outlines overlap, a strip. The points: that middle,
// and the corners or ends of the span that touch (or lie within the speculative gap). Returns how many.
int offset_points(const Reference& r, const Face& inc_face, FaceContact& fc)
{
    SideBySide sb;
    const int before = fc.count;
    if (!outlines_overlap(r, inc_face, sb) || !strip_point(r, sb.inc_face, sb.middle, -r.gap, fc))
        return 0;
    const double depth = fc.points[static_cast<size_t>(before)].depth;
    const double drop =
        0.5 * std::max(2.0 * k_face_patch_drop * depth, least_patch_drop(2.0 * r.patch_drop, depth));
    const PatchSize ref_flat = face_patch(r.ref->shape(), r.face.axis, drop);
    const PatchSize inc_flat = face_patch(r.inc->shape(), sb.inc_face.axis, drop);
    Span flat[2];
    bool strip[2];
    for (int i = 0; i < 2; ++i) {
        const Span a = patch_span(*r.ref, r.face, ref_flat, sb.axes[i]);
        const Span b = patch_span(*r.inc, sb.inc_face, inc_flat, sb.axes[i]);
        flat[i] = {std::max({a.lo, b.lo, sb.outline[i].lo}), std::min({a.hi, b.hi, sb.outline[i].hi})};
        strip[i] = !(flat[i].hi > flat[i].lo);
        if (strip[i])
            flat[i].lo = flat[i].hi = sb.outline[i].middle();
    }
    // The span's corners; along a strip its two ends (its middle is in already).
    const double keep = std::min(depth, 0.0) - 3.0 * r.patch_drop;
    const Vec3 plane =
        sb.middle - dot(sb.axes[0], sb.middle) * sb.axes[0] - dot(sb.axes[1], sb.middle) * sb.axes[1];
    for (int c = 0; c < 4 && !(strip[0] && strip[1]); ++c) {
        if ((strip[0] && (c & 1) != 0) || (strip[1] && (c & 2) != 0))
            continue;
        const double u = (c & 1) != 0 ? flat[0].hi : flat[0].lo, v = (c & 2) != 0 ? flat[1].hi : flat[1].lo;
        (void)strip_point(r, sb.inc_face, plane + u * sb.axes[0] + v * sb.axes[1], keep, fc);
    }
    return fc.count - before;
}

// Clips the incident patch against the reference patch and appends the corners that touch (or lie
// within r.gap), on both true surfaces; returns how many (0 when the overlap under the reference's
// pole is not positive).
int clipped_points(const Reference& r, FaceContact& fc)
{
    const Face inc_face = face_towards(*r.inc, -1.0 * r.face.normal);
    // The patches' size comes from the overlap under the reference's pole, which a tilt of the
    // incident body barely changes (the overlap at its deepest point grows with the tilt, and patches
    // sized by it made the pair's force fall as a box tipped). Where the incident body does not reach
    // under that pole (the bodies are offset), the overlap along the normal stands in.
    Vec3 under;
    const bool reaches = lift(*r.inc, inc_face, r.face.pole, under);
    if (!reaches) {
        if (offset_points(r, inc_face, fc) >= 2)
            return fc.count;
        fc.count = 0;
    }
    const double under_pole = reaches ? dot(r.face.normal, r.face.pole - under) : r.overlap;
    if (!(under_pole > -r.gap))
        return 0;
    // A speculative caller's patches reach at least its least drop, so a face about to touch stands
    // on its corners (rows that hold once they would close); once touching, only as far as keeps
    // them touching (least_patch_drop).
    const double drop =
        std::max(k_face_patch_drop * under_pole, 0.5 * least_patch_drop(2.0 * r.patch_drop, under_pole));
    // Corners count down to three times that below the faces' own gap (two patches' drops, and one for
    // a slight tilt; none: touching ones only). Parallel faces put their corners at exactly two.
    const double keep = std::min(under_pole, 0.0) - 3.0 * r.patch_drop;
    const PatchSize ref_size = face_patch(r.ref->shape(), r.face.axis, drop);
    const PatchSize inc_size = face_patch(r.inc->shape(), inc_face.axis, drop);
    Polygon poly;
    // The incident patch sits under the incident body's deepest point: a tilted face touches on its
    // low side (the contact rolls towards it, which is what holds a stack upright).
    for (const Vec3& c : patch_corners(*r.inc, inc_face, inc_size, &r.inc_lowest))
        poly.v[static_cast<size_t>(poly.n++)] = c;
    for (int i = 0; i < 2 && poly.n > 0; ++i) {
        const Vec3 e = r.ref->r.col(patch_axis(r.face.axis, i));
        const double centre = dot(e, r.face.pole);
        poly = clip(poly, e, centre + ref_size.half[i]);
        poly = clip(poly, -1.0 * e, -centre + ref_size.half[i]);
    }
    keep_four(poly, r.face.normal);
    int touching = 0;
    for (int i = 0; i < poly.n; ++i) {
        Vec3 on_inc, on_ref;
        if (!lift(*r.inc, inc_face, poly.v[static_cast<size_t>(i)], on_inc) ||
            !lift(*r.ref, r.face, on_inc, on_ref))
            continue;
        const double depth = dot(r.face.normal, on_ref - on_inc);
        if (!(depth > keep))
            continue;
        ++touching;
        add_point(r, on_ref, on_inc, depth, fc);
    }
    return touching;
}

// Appends a point of the incident body at `q` (in the plane through its deepest point, across the
// normal) moved onto both surfaces along the normal, if it touches; returns whether it did.
bool incident_point(const Reference& r, const Vec3& q, FaceContact& fc)
{
    Vec3 on_inc, on_ref;
    if (!lift_along(*r.inc, q, r.face.normal, on_inc) || !lift(*r.ref, r.face, on_inc, on_ref))
        return false;
    const double depth = dot(r.face.normal, on_ref - on_inc);
    if (!(depth > 0.0))
        return false;
    add_point(r, on_ref, on_inc, depth, fc);
    return true;
}

// A rounded edge or corner of the incident body on the reference face: its deepest point lies over the
// reference's flat part (at least half as deep there as the overlap). Adds the deepest point and the
// two ends of the edge's flat part that touch (along the incident axis most across the normal).
bool feature_on_face(const Reference& r, FaceContact& fc)
{
    Vec3 on_ref;
    if (!lift(*r.ref, r.face, r.inc_lowest, on_ref) ||
        !(dot(r.face.normal, on_ref - r.inc_lowest) >= 0.5 * r.overlap))
        return false;
    fc.count = 0;
    const int j = axis_across(*r.inc, r.face.normal);
    const Vec3 e = r.inc->r.col(j);
    const Vec3 t = normalized(e - dot(e, r.face.normal) * r.face.normal);
    const double w = flat_half_length(r.inc->shape(), j, 2.0 * k_face_patch_drop * r.overlap);
    for (double side : {1.0, -1.0})
        (void)incident_point(r, r.inc_lowest + (side * w) * t, fc);
    add_point(r, on_ref, r.inc_lowest, dot(r.face.normal, on_ref - r.inc_lowest), fc);
    return true;
}

// Closest points of the lines p + s·u and q + t·v (u, v unit, not parallel).
void closest_on_lines(const Vec3& p, const Vec3& u, const Vec3& q, const Vec3& v, Vec3& on_p, Vec3& on_q)
{
    const Vec3 w = p - q;
    const double b = dot(u, v), d = dot(u, w), e = dot(v, w);
    const double den = 1.0 - b * b;
    const double s = (b * e - d) / den, t = (e - b * d) / den;
    on_p = p + s * u;
    on_q = q + t * v;
}

// Least sine between two edges for their cross product to be an axis [-]: nearly parallel edges lie
// on each other along a line, which the general path's carried points hold.
constexpr double k_edge_min_sine = 0.05;

// Edge on edge: the axis across A's and B's edges most across `guess`, where two rounded edges (locally
// cylinders) have their common normal. Kind::Apart when it separates them; Kind::Edge with one point
// where the edges' flat parts cross and the overlap along it is below both faces'.
void edge_on_edge(const Frame& fa, const Frame& fb, const Vec3& guess, double face_overlap, FaceContact& fc)
{
    const int i = axis_across(fa, guess), j = axis_across(fb, guess);
    const Vec3 ea = fa.r.col(i), eb = fb.r.col(j);
    Vec3 n = cross(ea, eb);
    const double len = length(n);
    if (!(len > k_edge_min_sine))
        return;
    n = (dot(n, guess) < 0.0 ? -1.0 : 1.0) / len * n;
    const Vec3 sa = body_support(*fa.body, -1.0 * n), sb = body_support(*fb.body, n);
    fc.support_calls += 2;
    const double overlap = dot(n, sb - sa);
    fc.normal = n;
    fc.depth = overlap;
    if (!(overlap > 0.0)) {
        fc.kind = FaceContact::Kind::Apart;
        return;
    }
    if (!(overlap < face_overlap))
        return;
    Vec3 pa, pb;
    closest_on_lines(sa, ea, sb, eb, pa, pb);
    const double drop = 2.0 * k_face_patch_drop * overlap;
    if (std::abs(dot(pa - sa, ea)) > flat_half_length(fa.shape(), i, drop) ||
        std::abs(dot(pb - sb, eb)) > flat_half_length(fb.shape(), j, drop))
        return;
    const Vec3 mid = 0.5 * (pa + pb);
    Vec3 on_a, on_b;
    // A lies on the +n side of its supporting plane through sa, B on the −n side of its plane through sb.
    if (!lift_along(fa, mid - dot(n, mid - sa) * n, n, on_a) ||
        !lift_along(fb, mid - dot(n, mid - sb) * n, -1.0 * n, on_b))
        return;
    const double depth = dot(n, on_b - on_a);
    if (!(depth > 0.0))
        return;
    add_point(fc, on_a, on_b, depth);
    fc.kind = FaceContact::Kind::Edge;
}

} // namespace

bool has_face_patches(const Collider& c)
{
    return c.convex && !c.deformed && c.shape.type == ShapeType::Superquadric &&
           std::max(c.shape.epsilon1, c.shape.epsilon2) <= k_face_max_exponent;
}

PatchSize face_patch(const ShapeDef& shape, int axis, double drop)
{
    PatchSize out;
    const Vec3& a = shape.radii;
    const double rel = std::min(drop / a[axis], 1.0);
    if (!(rel > 0.0))
        return out;
    const double e1 = shape.epsilon1, e2 = shape.epsilon2;
    if (axis == 2) {
        // (X^(2/ε2) + Y^(2/ε2))^(ε2/ε1) = T at the corner, X = Y.
        const double t = -std::expm1((2.0 / e1) * std::log1p(-rel));
        const double u = std::pow(0.5 * std::pow(t, e1 / e2), 0.5 * e2);
        out.half[0] = u * a.x;
        out.half[1] = u * a.y;
        return out;
    }
    // Face on x (or y): X^(2/ε2) = 1 − T; the other inner coordinate takes T/2 of it, and Z the rest:
    // Z^(2/ε1) = 1 − (1 − T/2)^(ε2/ε1).
    const double t = -std::expm1((2.0 / e2) * std::log1p(-rel));
    const double u_inner = std::pow(0.5 * t, 0.5 * e2);
    const double u_z = std::pow(-std::expm1((e2 / e1) * std::log1p(-0.5 * t)), 0.5 * e1);
    const int inner = 1 - axis; // the other of x and y
    // Patch axes (k + 1) % 3 and (k + 2) % 3: (y, z) for the x face, (z, x) for the y face.
    out.half[0] = axis == 0 ? u_inner * a[inner] : u_z * a.z;
    out.half[1] = axis == 0 ? u_z * a.z : u_inner * a[inner];
    return out;
}

bool face_height(const ShapeDef& shape, int axis, double side, Vec3& p)
{
    const Vec3& a = shape.radii;
    const double e1 = shape.epsilon1, e2 = shape.epsilon2;
    // x^(ε2/ε1) is x itself for equal exponents (a rounded box's usual case): one power fewer.
    auto level = [&](double x) { return e1 == e2 ? x : std::pow(x, e2 / e1); };
    auto level_inverse = [&](double x) { return e1 == e2 ? x : std::pow(x, e1 / e2); };
    double h = 0.0;
    if (axis == 2) {
        const double g =
            level(std::pow(std::abs(p.x) / a.x, 2.0 / e2) + std::pow(std::abs(p.y) / a.y, 2.0 / e2));
        if (!(g < 1.0))
            return false;
        h = std::pow(1.0 - g, 0.5 * e1);
    } else {
        const int inner = 1 - axis;
        const double zt = std::pow(std::abs(p.z) / a.z, 2.0 / e1);
        if (!(zt < 1.0))
            return false;
        const double rem = level_inverse(1.0 - zt) - std::pow(std::abs(p[inner]) / a[inner], 2.0 / e2);
        if (!(rem > 0.0))
            return false;
        h = std::pow(rem, 0.5 * e2);
    }
    p[axis] = side * a[axis] * h;
    return true;
}

FaceContact face_contact(const BodyView& a, const BodyView& b, const Vec3& guess, double gap,
                         double patch_drop)
{
    FaceContact fc;
    const Frame fa = frame_of(a), fb = frame_of(b);
    // The faces that look at each other: A's along −guess, B's along +guess (guess is from B to A).
    const Face face_a = face_towards(fa, -1.0 * guess), face_b = face_towards(fb, guess);
    const Vec3 low_b = body_support(b, -1.0 * face_a.normal);
    ++fc.support_calls;
    const double overlap_a = dot(face_a.normal, face_a.pole - low_b);
    if (!(overlap_a > -gap)) {
        fc.kind = FaceContact::Kind::Apart;
        fc.normal = -1.0 * face_a.normal;
        return fc;
    }
    const Vec3 low_a = body_support(a, -1.0 * face_b.normal);
    ++fc.support_calls;
    const double overlap_b = dot(face_b.normal, face_b.pole - low_a);
    if (!(overlap_b > -gap)) {
        fc.kind = FaceContact::Kind::Apart;
        fc.normal = face_b.normal;
        return fc;
    }
    // The face the last normal came from keeps the reference unless the other's overlap is clearly
    // smaller (Box2D's relative tolerance).
    const bool was_a = std::abs(dot(guess, face_a.normal)) >= std::abs(dot(guess, face_b.normal));
    const bool ref_a = was_a ? !(overlap_b < (1.0 - k_face_switch) * overlap_a)
                             : overlap_a < (1.0 - k_face_switch) * overlap_b;
    const Reference r = ref_a ? Reference{&fa, &fb, face_a, overlap_a, low_b, true, gap, patch_drop}
                              : Reference{&fb, &fa, face_b, overlap_b, low_a, false, gap, patch_drop};
    fc.normal = ref_a ? -1.0 * face_a.normal : face_b.normal;
    fc.depth = r.overlap;
    if (clipped_points(r, fc) < 2) {
        if (feature_on_face(r, fc)) {
            fc.kind = FaceContact::Kind::Faces;
            return fc;
        }
        fc.count = 0;
        edge_on_edge(fa, fb, guess, std::min(overlap_a, overlap_b), fc);
        return fc; // Apart, Edge or NotFaces
    }
    // The incident body's deepest point, on the reference's surface above it.
    Vec3 on_ref;
    if (lift(*r.ref, r.face, r.inc_lowest, on_ref)) {
        const double depth = dot(r.face.normal, on_ref - r.inc_lowest);
        if (depth > -gap)
            add_point(r, on_ref, r.inc_lowest, depth, fc);
    }
    fc.kind = FaceContact::Kind::Faces;
    return fc;
}

FaceContact face_contact_plane(const BodyView& body, const Vec3& normal, double offset, double gap,
                               double patch_drop)
{
    FaceContact fc;
    const Frame f = frame_of(body);
    const Vec3 lowest = body_support(body, -1.0 * normal);
    fc.support_calls = 1;
    const double depth = offset - dot(normal, lowest);
    if (!(depth > -gap)) {
        fc.kind = FaceContact::Kind::Apart;
        return fc;
    }
    fc.normal = normal;
    fc.depth = depth;
    // The plane is flat: the body's face takes the whole half of the depth.
    const Face face = face_towards(f, -1.0 * normal);
    const PatchSize size = face_patch(
        f.shape(), face.axis, std::max(2.0 * k_face_patch_drop * depth, least_patch_drop(patch_drop, depth)));
    int touching = 0, near = 0;
    for (const Vec3& corner : patch_corners(f, face, size)) {
        Vec3 p;
        if (!lift(f, face, corner, p))
            continue;
        const double d = offset - dot(normal, p);
        if (d > std::min(depth, 0.0) - 2.0 * patch_drop) {
            ++near;
            touching += d > 0.0 ? 1 : 0;
            add_point(fc, p, p + d * normal, d);
        }
    }
    if (near < 2) {
        // A rounded edge or corner on the plane: the deepest point and the ends of the edge's flat part
        // (along the body's axis most across the normal) moved onto the body along the normal.
        fc.count = 0;
        const int j = axis_across(f, normal);
        const Vec3 e = f.r.col(j);
        const Vec3 t = normalized(e - dot(e, normal) * normal);
        const double w = flat_half_length(f.shape(), j, 2.0 * k_face_patch_drop * depth);
        for (double side : {1.0, -1.0}) {
            Vec3 p;
            if (!lift_along(f, lowest + (side * w) * t, normal, p))
                continue;
            const double d = offset - dot(normal, p);
            if (d > 0.0)
                add_point(fc, p, p + d * normal, d);
        }
    }
    if (touching < 3)
        add_point(fc, lowest, lowest + depth * normal, depth);
    fc.kind = FaceContact::Kind::Faces;
    return fc;
}

} // namespace supermodal
