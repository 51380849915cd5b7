// SPDX-License-Identifier: MIT
// The contact stages of the step: pairs once per step from swept boxes (which also decides how many
// substeps a fast body needs so it cannot tunnel), contact points per substep, penalty forces.
//
// Threads: the narrowphase and the per-pair penalty math run over a static partition of the sorted
// pair list; each part writes its own point buffer and per-pair slots, and everything that touches
// two bodies is added up serially in pair order, so results are bit-identical for any thread count.
#pragma once

#include "contact/broadphase.h"
#include "contact/events.h"
#include "contact/manifold.h"
#include "contact/narrowphase.h"
#include "contact/penalty.h"
#include "supermodal/contact.h"
#include "supermodal/world.h"
#include "world/components.h"
#include "world/contact_solve.h"

#include <span>
#include <vector>

namespace supermodal
{

struct StepContext;
class Parallel;

/// Where one pair's points of this substep sit: part_points[part][begin, end).
struct PairPoints {
    uint32_t part = 0, begin = 0, end = 0;
};

/// Contact data of sleeping pairs (no end awake), set aside while their bodies sleep so that the
/// pairs wake with the friction anchors and manifold points they slept with (world/sleep.h).
struct ParkedContacts {
    std::vector<PairAnchor> anchors;     ///< State: by key; hashed and snapshotted.
    std::vector<PairManifold> manifolds; ///< State: by key; hashed and snapshotted.
    std::vector<TouchRecord> touching;   ///< Derived: touching as they fell asleep (no events meanwhile).
    std::vector<uint8_t> body_class;     ///< Scratch: per entity index, a SleepClass.
    std::vector<uint32_t> wake;          ///< Scratch: islands to wake.
};

/// One part's share of the kept manifolds and support-map counts of a substep (summed in part order).
struct ManifoldTally {
    size_t kept = 0;
    uint64_t support_calls = 0;
    uint64_t touching_pairs = 0;
    uint64_t touching_support_calls = 0;
    ManifoldTally& operator+=(const ManifoldTally& o)
    {
        kept += o.kept;
        support_calls += o.support_calls;
        touching_pairs += o.touching_pairs;
        touching_support_calls += o.touching_support_calls;
        return *this;
    }
};

/// Contact data of a world: state (anchors), derived (pairs, points, contacts), scratch.
struct ContactWorld {
    std::vector<PairAnchor> anchors;           ///< State: sorted by key; hashed and snapshotted.
    std::vector<PairManifold> manifolds;       ///< State: support-map pairs' points, sorted by key.
    std::vector<PairManifold> pair_manifold;   ///< Scratch: per pair, its manifold this substep.
    std::vector<PairManifold> old_manifolds;   ///< Scratch: last substep's, read while making new ones.
    std::vector<PairAnchor> next_anchors;      ///< Scratch: this substep's anchors while they are made.
    std::vector<QueryCost> pair_cost;          ///< Scratch: per pair, its support-map work this substep.
    std::vector<ManifoldTally> manifold_tally; ///< Scratch: per part + 1, its kept manifolds and counts.
    uint64_t support_calls = 0;                ///< Derived: support-map evaluations over this step [-].
    uint64_t touching_pairs = 0;               ///< Derived: pairs with points, summed over substeps [-].
    uint64_t touching_support_calls = 0;       ///< Derived: the part of support_calls those pairs made [-].
    std::vector<uint64_t> excluded_pairs;      ///< Input: sorted keys (lo << 32 | hi) never colliding.
    std::vector<BroadphaseProxy> proxies;      ///< Scratch.
    std::vector<uint8_t> pair_apart;           ///< Scratch: per broadphase pair, 1 if it cannot touch.
    std::vector<BroadphaseProxy> body_proxies; ///< Scratch: per body of the store, its proxy or none.
    std::vector<Aabb> boxes;                   ///< Scratch: world box per entity index [m].
    /// Scratch: per entity index, the pose its box was made at and the broadphase that made it, so the
    /// narrowphase right after takes the broadphase's boxes instead of three more support calls each.
    std::vector<std::pair<Vec3, Quat>> box_poses;
    std::vector<uint64_t> box_made_by;
    uint64_t broadphase_count = 0; ///< Broadphases run [-] (to match box_made_by).
    /// Scratch: per entity index, a sleeping body's swept box, computed once while it sleeps (its pose
    /// and velocity do not change then, so reusing it gives the same box) [m]; and whether it is set.
    std::vector<Aabb> sleep_boxes;
    std::vector<uint8_t> sleep_box_set;
    std::vector<Aabb> swept;                         ///< Scratch: swept box per entity index [m], world.
    BroadphaseScratch broadphase;                    ///< Scratch.
    std::vector<BodyPair> pairs;                     ///< Derived: candidate pairs of this step, sorted.
    std::vector<PartList<ContactPoint>> part_points; ///< Derived: this substep's points, per part.
    std::vector<double> part_needed;     ///< Scratch: per part, the most substeps a pair of it needs [-].
    PartBalance collide_balance;         ///< Scratch: where the narrowphase's pairs split across threads.
    std::vector<PairPoints> pair_points; ///< Derived: per pair, where its points are.
    std::vector<PairForce> pair_force;   ///< Scratch: per pair, this substep's forces.
    std::vector<ContactInfo> contacts;   ///< Derived: touching pairs of the last substep.
    std::vector<uint8_t> has_twist;      ///< Scratch: per contact, the torsional spring is active.
    std::vector<uint8_t> has_roll;       ///< Scratch: per contact, the rolling spring is active.
    std::vector<Vec3> force, torque;     ///< Scratch: per entity index.
    double max_penetration = 0.0;        ///< Derived: deepest point of the last substep [m].
    std::vector<ZetaCache> zeta_caches;  ///< Scratch: one per part.
    std::vector<std::vector<double>> modal_phi; ///< Scratch: one per part, φ at a point of a modal body.
    /// Scratch: per part, parallel to part_points, each point's normal force [N] (pairs with modes only).
    std::vector<PartList<double>> part_point_force;
    ContactEvents events;  ///< Step events and the host's callback.
    SoftContacts soft;     ///< Scratch: the soft solver's rows of this substep.
    ParkedContacts parked; ///< Contacts of sleeping pairs.

    /// The points of pair pi in this substep.
    [[nodiscard]] std::span<const ContactPoint> points_of(size_t pi) const
    {
        const PairPoints& r = pair_points[pi];
        return {part_points[r.part].data() + r.begin, r.end - r.begin};
    }
};

/// The anchor of the pair with `key` in `anchors` (sorted by key), or null.
[[nodiscard]] const PairAnchor* find_pair_anchor(const std::vector<PairAnchor>& anchors, uint64_t key);

/// Broadphase over boxes swept by each body's motion over dt; returns the substep count needed so that
/// no body moves more than ContactDef::speculative_speed_factor of a partner's thickness per substep.
/// Also starts the step's event accumulators.
[[nodiscard]] int update_pairs(const WorldDef& def, const Parallel& par, Registry& reg,
                               ContactWorld& io_contact);
/// Narrowphase for this substep's poses.
void collide_pairs(const WorldDef& def, const Registry& reg, const Parallel& par, ContactWorld& io_contact);
/// Makes the next narrowphase query every awake pair of `body` afresh (its surface changed): none reuses
/// its stored points.
void requery_pairs_of(ContactWorld& io_contact, Entity body);
/// Penalty normal and friction forces into velocities; updates the step's event accumulators.
void apply_penalty_forces(const WorldDef& def, const StepContext& ctx, Registry& reg, const Parallel& par,
                          ContactWorld& io_contact, StepWarnings& io_warnings);
/// Moves the friction anchors of this substep's contacts by the relative motion the bodies will make,
/// h·v'. Call after every velocity change of the substep (contact forces and constraint impulses).
void update_contact_anchors(const StepContext& ctx, const Registry& reg, const Parallel& par,
                            ContactWorld& io_contact);

} // namespace supermodal
