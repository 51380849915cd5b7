// SPDX-License-Identifier: MIT
// Penalty force of one touching pair: normal spring–dashpot per point, one Cundall–Strack tangential
// spring and one torsional spring at the force centroid. A pure function of the pair's points, the two
// bodies and the pair's old anchor, so pairs can run on any thread; the caller adds the results to the
// bodies in pair order.
#pragma once

#include "contact/broadphase.h"
#include "contact/narrowphase.h"
#include "dynamics/body.h"
#include "supermodal/contact.h"

#include <array>
#include <cstdint>
#include <span>

namespace supermodal
{

/// Friction state of a touching pair: the tangential spring's extension (Cundall–Strack anchor).
struct PairAnchor {
    uint64_t key = 0;       ///< BodyPair::key().
    Vec3 spring{};          ///< Tangential spring extension [m], world, in the contact plane.
    double twist = 0.0;     ///< Torsional spring angle about the contact normal [rad].
    Vec3 roll{};            ///< Rolling spring angle [rad], world, in the contact plane (rotation vector).
    double stiffness = 0.0; ///< Normal spring per point area held while touching [N/m³] (0: Hertz).
    double credit = 0.0;    ///< Energy dissipated by the contact, not yet spent on stiffening it [J].
    // The soft solver's memory: the pair's loads of its last substep, which start the next solve
    // (warm starting). Kept as forces, not impulses, so a change of substep length scales them.
    double normal_load = 0.0; ///< Σ normal force [N].
    Vec3 friction_load{};     ///< Friction force on a [N], world.
    Vec3 roll_load{};         ///< Rolling-resistance torque on a [N·m], world.
};

/// Memo of damping ratios per restitution (a 50-step bisection): a pure function, so hits and misses
/// give the same bits. One per thread part.
struct ZetaCache {
    struct Entry {
        double e = -1.0, zeta = 0.0;
    };
    std::array<Entry, 8> entries{};
    size_t next = 0;
    double get(double e);
};

/// One side of a pair as the penalty force sees it.
struct PenaltyBody {
    const BodyModel* model = nullptr;
    const Pose* pose = nullptr;
    const Velocity* velocity = nullptr;
};

/// What a pair does in one substep; written by one thread, added to the bodies in pair order.
struct PairForce {
    bool touching = false;          ///< The pair had points and a dynamic body.
    bool has_twist = false;         ///< The torsional spring is active (its angle advances).
    bool has_roll = false;          ///< The rolling spring is active (its angle advances).
    bool stiffness_clamped = false; ///< Material stiffness exceeded the stability cap.
    Vec3 force_a{};                 ///< Total force on a [N], world; b gets −force_a.
    Vec3 torque_a{};                ///< Torque on a about its centre of mass [N·m], world.
    Vec3 torque_b{};                ///< Torque on b about its centre of mass [N·m], world.
    double normal_force = 0.0;      ///< Σ of the points' normal forces [N].
    Vec3 friction_force{};          ///< Tangential part of force_a [N], world, at info.point (the centroid).
    PairAnchor anchor{};            ///< The pair's anchor after this substep's forces (before the motion).
    ContactInfo info{};             ///< The pair's summary for world_contacts().
};

/// Normal spring rate ω = 2π f [rad/s], damping override ζ (< 0 = from restitution).
struct PenaltyParams {
    double omega = 0.0;    ///< The rate (frequency mode), or the stability cap (material mode).
    bool material = false; ///< Hertz stiffness from the bodies' materials, capped at omega.
    double damping_ratio = -1.0;
    double h = 0.0; ///< Substep [s].
};

/// The modes of a pair's bodies as its springs feel them: contact knows no modes, the world fills this in.
/// Called from any thread, so it must only read (its scratch belongs to the calling thread).
struct PairModes {
    /// Extra inverse mass of `body` [1/kg] at world point x [m] for a push along unit world direction d
    /// held over the substep (d = 0: the bound over directions); 0 for a rigid body.
    double (*inverse_mass)(void* ctx, Entity body, const Vec3& x, const Vec3& d) = nullptr;
    void* ctx = nullptr;
};

/// The forces of a touching pair given its points (from b towards a); old_anchor is the pair's anchor
/// from the last substep, or null. With `modes`, the bodies' modes join the effective masses; the loads
/// they take are each point's normal force (written to out_point_force, one per point, when given) and
/// PairForce::friction_force at the centroid: the caller adds them to the modes in pair order.
[[nodiscard]] PairForce penalty_pair(const PenaltyParams& params, const BodyPair& pair, const PenaltyBody& a,
                                     const PenaltyBody& b, std::span<const ContactPoint> points,
                                     const PairAnchor* old_anchor, ZetaCache& io_zeta,
                                     const PairModes* modes = nullptr,
                                     std::span<double> out_point_force = {});

/// Velocity of the body point `point` [m/s], world.
[[nodiscard]] inline Vec3 velocity_at(const Velocity& v, const Vec3& centre, const Vec3& point)
{
    return v.linear + cross(v.angular, point - centre);
}

} // namespace supermodal
