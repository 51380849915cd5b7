// SPDX-License-Identifier: MIT
// Face contact of flat-faced superquadrics (rounded boxes, ε ≤ 0.5): the whole manifold from one query,
// in the manner of Box2D's and Jolt's reference and incident faces.
//
// A face of a superquadric is flat only near its pole; its patch here is a rectangle in the pole's
// tangent plane whose corners lie where the surface has dropped below that plane by a given amount (so
// over a pole-centred patch the surface is within that drop of the plane). The drop is a quarter of the
// pair's overlap under the reference pole per face, so corners are still about half as deep as the
// contact (the rule the tilted supports of manifold.cpp follow).
//
// Per query: the normal is the face axis of A or of B (the one most aligned with the pair's last
// normal) with the smaller overlap; each overlap is exact from one support-map evaluation of the other
// body (a face's own extent along its axis is its radius), and an overlap ≤ 0 proves the bodies apart.
// The reference patch is centred on its pole; the incident patch lies under the incident body's
// deepest point (that support point), since a tilted face touches on its low side. The incident patch is
// clipped against the reference's side planes (Sutherland–Hodgman), and each clipped corner is moved
// onto the true surfaces: along the incident body's axis onto it, then along the reference's onto that,
// so every point is a material point of both bodies and its depth is their overlap along the normal.
// The deepest point joins the corners (at most four of them are kept before the lifts). Parallel faces
// side by side, the incident body not under the reference's pole (a box across two below it), meet on a
// strip across the middle of where their outlines overlap: its middle and ends are the points. A face
// contact needs two touching corners. Otherwise: an edge or corner of the incident body whose deepest point
// lies over the reference's flat part gets that point and the ends of the edge's flat part (moved onto
// the body along the normal); two edges crossing get one point on the axis across both; a pair apart
// keeps its separating direction for the next query; the rest goes to the search of penetration.h.
#pragma once

#include "contact/narrowphase.h"

#include <array>

namespace supermodal
{

/// Flat-faced bodies take the face path when both exponents are at most this [-].
inline constexpr double k_face_max_exponent = 0.5;
/// Each face's patch reaches where its surface has dropped this fraction of the overlap under the
/// reference's pole [-] (a flat plane leaves twice as much to the body's face).
inline constexpr double k_face_patch_drop = 0.25;
/// The reference face changes only when the other face's overlap is smaller by this fraction [-], so
/// nearly parallel faces do not trade the normal back and forth.
inline constexpr double k_face_switch = 0.05;

/// One contact of a face query: the same contact as a point of each surface.
struct FacePoint {
    Vec3 on_a{}, on_b{}; ///< [m], world, each on its body's true surface.
    double depth = 0.0;  ///< Overlap along the normal, (on_b − on_a)·normal [m].
};

/// What a face query found.
struct FaceContact {
    enum class Kind : uint8_t {
        Apart,    ///< `normal` separates the bodies (exact): no contact.
        Faces,    ///< Face, edge or corner on a face: normal and points below.
        NotFaces, ///< Neither proven apart nor a face or edge contact: the general path decides.
        Edge,     ///< Edge across edge: one point where their flat parts cross.
    } kind = Kind::NotFaces;
    Vec3 normal{};      ///< Unit, from B towards A, world (Apart: the direction that separates them).
    double depth = 0.0; ///< Overlap along the normal [m].
    int count = 0;      ///< Touching points.
    std::array<FacePoint, 9> points{}; ///< Clipped corners (at most 8) and the deepest point.
    int support_calls = 0;             ///< Support-map evaluations, one body each [-].
};

/// Whether a collider takes the face path: undeformed superquadric, both exponents ≤ k_face_max_exponent.
[[nodiscard]] bool has_face_patches(const Collider& c);

/// Face query of two bodies with face patches; `guess` is the pair's last normal (from B towards A,
/// world), or the centre line when there is none. With `gap` > 0 [m] (a speculative solver's), bodies
/// apart by less than it are not Apart and their deepest point counts (negative depth); the patches
/// reach at least where the surfaces have dropped by `patch_drop` [m], and corners down to three times
/// that below the faces' own gap count too, so a face resting on a tiny overlap, or about to touch, stands
/// on its corners.
[[nodiscard]] FaceContact face_contact(const BodyView& a, const BodyView& b, const Vec3& guess,
                                       double gap = 0.0, double patch_drop = 0.0);

/// Face query of a body with face patches against the plane {x : normal·x = offset} below it (normal
/// unit, pointing out of the plane's solid towards the body); points' on_b lie on the plane. Never
/// NotFaces: the plane is all face, so an edge or corner on it gets its deepest point and the ends of
/// the edge's flat part. `gap` and `patch_drop` as for face_contact.
[[nodiscard]] FaceContact face_contact_plane(const BodyView& body, const Vec3& normal, double offset,
                                             double gap = 0.0, double patch_drop = 0.0);

/// Patch half-sizes [m] of a face of an undeformed superquadric, along the shape axes (k + 1) % 3 and
/// (k + 2) % 3 for the face on axis k: where the surface has dropped by `drop` [m] below the pole's
/// tangent plane. Zero when drop ≤ 0; the whole face's half-sizes at drop ≥ the radius.
struct PatchSize {
    double half[2] = {0.0, 0.0};
};
[[nodiscard]] PatchSize face_patch(const ShapeDef& shape, int axis, double drop);

/// The point of the face on axis k (sign `side`, ±1) above shape-frame point p: p with its k coordinate
/// replaced by the surface's, or false when p lies beyond the face's outline [m], shape frame.
[[nodiscard]] bool face_height(const ShapeDef& shape, int axis, double side, Vec3& io_point);

} // namespace supermodal
