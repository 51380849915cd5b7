// SPDX-License-Identifier: MIT
// Support-map narrowphase with a persistent contact manifold (up to 4 points per pair).
//
// The penetration search (penetration.h: Newton from the pair's last normal, MPR when that fails)
// gives one normal and depth per pair; a flat face needs more than one point to rest flat.
// Each substep the manifold (a) keeps its old points, stored as material points of both bodies in
// their body frames so they follow the motion, re-measuring their depth along today's normal and
// dropping those that separated or slid apart; (b) adds the deepest point of A along the normal and,
// for flat-faced bodies, the support points along the normal tilted towards the face's diagonals
// that lie inside the other body (the face's corners on a box, the edge of the patch on a rounded
// box); (c) keeps the deepest point and the three that span the largest area. Every touching point
// carries the weight 1/count, so the pair's stiffness does not depend on the point count. A steady pair
// of bodies with face patches that has barely moved skips (a)–(c) and measures its stored points again
// (k_manifold_steady_queries).
#pragma once

#include "contact/narrowphase.h"

#include <array>
#include <cstdint>
#include <vector>

namespace supermodal
{

/// One persistent point: the same contact seen as a material point of each body.
struct ManifoldPoint {
    Vec3 local_a{}; ///< Point on A [m], A's body frame.
    Vec3 local_b{}; ///< Point on B [m], B's body frame (unused when B is a plane).
};

/// Manifold of one pair; state (hashed, snapshotted), sorted by key in ContactWorld.
struct PairManifold {
    static constexpr int k_capacity = 4;
    uint64_t key = 0; ///< BodyPair::key().
    int count = 0;
    std::array<ManifoldPoint, k_capacity> points{};
    /// The pair's normal (from B towards A) in A's body frame, where the next substep's search starts
    /// (contact/penetration.h). Unit for a body pair, zero for a plane pair.
    Vec3 normal{};
    /// The pair's relative pose at its last full query: B's centre of mass in A's frame [m] and B's
    /// orientation in A's frame (a plane pair: the body's world pose). While the pair stays within the
    /// reuse tolerances of it and its queries have been steady, the query is skipped and the stored
    /// points are measured again where the bodies carried them (manifold_reuse_bound).
    Vec3 query_offset{};
    Quat query_turn{};
    /// Full queries in a row that found the points and normal of the one before, within the reuse
    /// tolerances [-]; 0 for pairs that never reuse.
    int steady = 0;
    /// A cache, not state (neither hashed nor saved: a restored world proves it again): the two bodies
    /// of face-patch shapes found apart along `normal`, and the relative pose then. While the motion
    /// since cannot have closed that gap, the query is skipped; it would have found them apart along
    /// the same normal and changed nothing, so the result is the same bit for bit.
    struct ApartProof {
        const Collider* a = nullptr; ///< The colliders it holds for (a reshaped body gets another).
        const Collider* b = nullptr;
        Vec3 normal{};        ///< The manifold's normal it was made for, A's frame.
        Vec3 offset{};        ///< B's position minus A's [m], A's frame.
        Vec3 normal_b{};      ///< The normal in B's frame [-].
        double overlap = 0.0; ///< The overlap along the normal [m], at most −(the kept gap).
    } apart{};
};

/// A pair of bodies with face patches (or one on a plane) whose relative pose has moved by less than
/// these since its last full query measures its stored points again instead of querying (the idea of
/// Jolt's body-pair cache, with tolerances small enough to bound the error): the move as a fraction of
/// the smaller smallest radius [-], and the turn [rad]. 50 µm and 0.06° for a 5 cm box (Jolt holds
/// 1 mm and 2°); at a fifth of these only a quarter of a settling box pile's pairs were reused.
inline constexpr double k_manifold_reuse_move_rel = 1e-3;
inline constexpr double k_manifold_reuse_turn = 1e-3;
/// ...and only once this many full queries in a row found the same points and normal [-]. A face
/// query's points are not material points: on a rounded face they slide with the patch's edge (0.2 mm
/// for a 5 µm move of a heavy box rocking on a light one, measured). Held through a rocking motion and
/// then queried again they jumped, and each jump kicked the pair: a 1000:1 box pair at 1 ms steps
/// never came to rest with 4 (2–6 mm/s after 3 s), and rested with 16 (< 0.2 mm/s).
inline constexpr int k_manifold_steady_queries = 16;

/// The most a reused point's depth can differ from the separation of the two surfaces along the
/// stored normal where it lies [m], for a pair whose smaller smallest radius is `r` [m] and whose
/// moving body reaches `reach` [m] from its centre of mass: twice (the tolerated move plus the reach
/// times the tolerated turn). Both of its ends are material points, so each stays on its own surface;
/// each has moved by at most that since the query measured it, and so has the other surface under it.
[[nodiscard]] double manifold_reuse_bound(double r, double reach);

/// Updates the manifold of two convex bodies (A = the pair's first body) and appends its touching
/// points (normal from B towards A, weights summing to 1). With `speculative`, also its kept points that
/// do not touch (gap < 2% of the smaller smallest radius), with weight 0 and depth −gap: a solver that
/// stops an approach before it closes keeps a resting face on all its corners. The support-map
/// evaluations it made are added to io_cost when given. Returns the number appended.
int collide_manifold(const BodyView& a, const BodyView& b, PairManifold& io_manifold,
                     std::vector<ContactPoint>& out_points, bool speculative = false,
                     QueryCost* io_cost = nullptr);

/// The gap within which a speculative caller's points of two bodies count [m]: 2% of the smaller
/// smallest radius. Their boxes grown by it are what decides whether the pair is queried.
[[nodiscard]] double speculative_gap(const Collider& a, const Collider& b);

/// Same for a convex body against a plane: the manifold's A is always the body; normals are flipped
/// for the output when body_is_a is false (as collide_plane).
int collide_manifold_plane(const BodyView& body, const BodyView& plane, bool body_is_a,
                           PairManifold& io_manifold, std::vector<ContactPoint>& out_points,
                           bool speculative = false, QueryCost* io_cost = nullptr);

} // namespace supermodal
