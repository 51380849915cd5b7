// SPDX-License-Identifier: MIT
// The contact stages of the step: pairs once per step from swept boxes (which also decides how many
// substeps a fast body needs so it cannot tunnel), contact points per substep, penalty forces.
#pragma once

#include "contact/broadphase.h"
#include "contact/manifold.h"
#include "contact/narrowphase.h"
#include "supermodal/contact.h"
#include "supermodal/world.h"
#include "world/components.h"

#include <array>
#include <vector>

namespace supermodal
{

struct StepContext;

/// Friction state of a touching pair: the tangential spring's extension (Cundall–Strack anchor).
struct PairAnchor {
    uint64_t key = 0;   ///< BodyPair::key().
    Vec3 spring{};      ///< Tangential spring extension [m], world, in the contact plane.
    double twist = 0.0; ///< Torsional spring angle about the contact normal [rad].
};

/// Memo of damping ratios per restitution (a 50-step bisection): a pure function, so hits and misses
/// give the same bits.
struct ZetaCache {
    struct Entry {
        double e = -1.0, zeta = 0.0;
    };
    std::array<Entry, 8> entries{};
    size_t next = 0;
    double get(double e);
};

/// Contact data of a world: state (anchors), derived (pairs, points, contacts), scratch.
struct ContactWorld {
    std::vector<PairAnchor> anchors;      ///< State: sorted by key; hashed and snapshotted.
    std::vector<PairManifold> manifolds;  ///< State: support-map pairs' points, sorted by key; hashed.
    std::vector<BroadphaseProxy> proxies; ///< Scratch.
    BroadphaseScratch broadphase;         ///< Scratch.
    std::vector<BodyPair> pairs;          ///< Derived: candidate pairs of this step, sorted.
    std::vector<uint64_t> excluded_pairs; ///< Input: sorted keys (lo << 32 | hi) of pairs that never collide.
    std::vector<ContactPoint> points;     ///< Derived: this substep's points, grouped by pair.
    std::vector<uint32_t> pair_start;     ///< Derived: pairs.size() + 1 offsets into points.
    std::vector<ContactInfo> contacts;    ///< Derived: touching pairs of the last substep.
    std::vector<Vec3> force, torque;      ///< Scratch: per entity index.
    double max_penetration = 0.0;         ///< Derived: deepest point of the last substep [m].
    ZetaCache zeta_cache;                 ///< Scratch.
};

/// Broadphase over boxes swept by each body's motion over dt; returns the substep count needed so that
/// no body moves more than ContactDef::speculative_speed_factor of a partner's thickness per substep.
[[nodiscard]] int update_pairs(const WorldDef& def, Registry& reg, ContactWorld& io_contact);
/// Narrowphase for this substep's poses.
void collide_pairs(const WorldDef& def, Registry& reg, ContactWorld& io_contact);
/// Penalty normal and friction forces into velocities; updates the friction anchors.
void apply_penalty_forces(const WorldDef& def, const StepContext& ctx, Registry& reg,
                          ContactWorld& io_contact, StepWarnings& io_warnings);

} // namespace supermodal
