// SPDX-License-Identifier: MIT
// The soft contact solver: every contact point is a one-sided soft constraint (dynamics/soft_constraint.h)
// on the bodies' relative normal velocity, with two friction rows bounded by the Coulomb cone and, per
// pair, a rolling-resistance row bounded by ℓ·λ_n. The rows are solved in the same Gauss–Seidel passes
// as the joints, warm started from the pair's loads of the last substep. After the positions move, a
// relax pass solves them again without the push-out, so the push-out moves the bodies apart without
// leaving them the speed it took (Box2D v3's soft step); restitution then sets a bouncing contact's
// separation speed. A modal body takes each impulse through its modes (world/constraint_side.h), whose
// compliance at the point joins the effective mass. A body resting on one at least 4 times lighter
// solves their rows with the lighter one's mass scaled up to its own (scale_heavy_on_light).
#pragma once

#include "dynamics/soft_constraint.h"
#include "supermodal/contact.h"
#include "world/constraint_side.h"
#include "world/constraint_system.h"

#include <vector>

namespace supermodal
{

class Parallel;
struct ContactWorld;
struct StepContext;
struct StepWarnings;

/// One contact point as a soft constraint for one substep. What a pass over two rigid bodies reads
/// comes first and the set-up's data (the sides) last, so such a pass streams ~60% of the point's bytes.
struct SoftPoint {
    Velocity* v_a = nullptr;     ///< a.v, copied by set_point_masses (null for the world).
    Velocity* v_b = nullptr;     ///< b.v, likewise.
    double inv_mass_a = 0.0;     ///< a.inv_mass [1/kg], likewise.
    double inv_mass_b = 0.0;     ///< b.inv_mass [1/kg], likewise.
    Vec3 normal{};               ///< Unit, from b towards a, world.
    double separation = 0.0;     ///< Gap along the normal [m], < 0 when overlapping.
    double normal_mass = 0.0;    ///< 1 / (n·K·n) [kg].
    double normal_impulse = 0.0; ///< Accumulated this substep, ≥ 0 [N·s].
    SoftCoefficients soft{};     ///< The point's spring (stiffened by the load it carries).
    // The normal row's angular terms, for the passes over two rigid bodies: r × n [m] and I⁻¹(r × n)
    // [1/(kg·m)] of each side (set_point_masses).
    Vec3 arm_a{}, arm_b{}, turn_a{}, turn_b{};
    Vec3 tangent[2]{};           ///< Unit, ⟂ normal and each other.
    double tangent_mass[2]{};    ///< [kg].
    double tangent_impulse[2]{}; ///< Accumulated this substep [N·s].
    Vec3 tangent_arm_a[2]{}, tangent_arm_b[2]{}, tangent_turn_a[2]{}, tangent_turn_b[2]{}; ///< Same, r × t.
    double approach = 0.0; ///< Normal velocity before the solve [m/s] (< 0: closing).
    double depth = 0.0;    ///< Penetration found by the narrowphase [m].
    Side a, b;
};

/// One touching pair's rows: its points, and its pair-wide settings and rolling row.
struct SoftPair {
    uint32_t pair = 0;        ///< Index into ContactWorld::pairs.
    uint32_t first = 0;       ///< First point in SoftContacts::points.
    uint32_t count = 0;       ///< Points.
    uint32_t node_a = 0;      ///< Island node of a (its entity index), k_no_node if no impulse moves it.
    uint32_t node_b = 0;      ///< The same for b.
    double friction = 0.0;    ///< μ [-].
    double restitution = 0.0; ///< e [-].
    double rolling = 0.0;     ///< Rolling lever arm ℓ [m] (0: no rolling row).
    Vec3 stick{};             ///< Tangential slip since the pair last slid [m], world (static friction).
    bool sliding = false;   ///< Friction reached the Coulomb disc this substep (a point's, then the pair's).
    Mat3 roll_mass{};       ///< (Ia⁻¹ + Ib⁻¹)⁻¹ [kg·m²].
    Vec3 roll_impulse{};    ///< Accumulated angular impulse on a [N·m·s].
    bool backwards = false; ///< Take the normal rows last to first (flips after each pass).
    bool rigid = false;     ///< It has points and none has a modal side (the rows' direct path).
    bool free_a = false;    ///< a is dynamic and not frozen (the direct path's check, kept here so a
    bool free_b = false;    ///< pass does not read the body models); the same for b.
    bool warm = false;      ///< The warm start applies the points' impulses (the pair has last loads).
    bool roll_warm = false; ///< ... and roll_impulse.
};

/// One part's share of the pairs with rows and of their points (summed in part order).
struct RowTally {
    size_t pairs = 0;
    size_t points = 0;
    RowTally& operator+=(const RowTally& o)
    {
        pairs += o.pairs;
        points += o.points;
        return *this;
    }
};

/// The soft solver's rows of one substep (scratch of ContactWorld).
struct SoftContacts {
    std::vector<SoftPoint> points;
    std::vector<SoftPair> pairs;
    double h = 0.0;                 ///< Substep [s].
    double push_out_speed = 0.0;    ///< [m/s].
    double restitution_speed = 0.0; ///< [m/s].
    double gravity = 0.0;           ///< |g| [m/s²]: a load's mass is its weight over this.
    Vec3 up{};                      ///< −g/|g|, zero without gravity.
    bool take_approach = false;     ///< The warm start notes each point's approach speed.
    std::vector<uint32_t> nodes;    ///< Bodies the rows move, sorted (scratch of the heavy-on-light scaling).
    std::vector<uint32_t> nodes_other; ///< The sort's other buffer.
    std::vector<uint32_t> pair_rows;   ///< Per pair of ContactWorld::pairs, the rows it may take (scratch).
    std::vector<Mat3> inv_inertia;     ///< Per entity index: a body's world I⁻¹ this substep (scratch).
    std::vector<RowTally> tally;       ///< Per part + 1, its pairs with rows and points (scratch).
    std::vector<ContactInfo> infos;    ///< Per pair, what world_contacts() reports (finish_soft_contacts).
    /// Where the per-pair loops split across threads (scratch): a floor's pairs, first in key order,
    /// cost less than a pile's, so even counts are uneven times.
    PartBalance make_balance, load_balance, refresh_balance, advance_balance, finish_balance;
};

/// Rows from this substep's points with their last loads; the loads reach the bodies in the warm start
/// of the rows (soft_contact_rows' warm_start, run by island before the passes).
void prepare_soft_contacts(const ContactDef& def, const StepContext& ctx, const Parallel& par, Registry& reg,
                           ContactWorld& io);
/// Which bodies of the rows are still free to move, asked again after a body froze (freeze_non_finite).
void note_frozen_bodies(SoftContacts& io);
/// A solver substep on the last substep's rows (no narrowphase between): their gaps as the bodies moved
/// them, their impulses to be applied again by the warm start; a modal side is made anew for this substep.
void refresh_soft_contacts(const StepContext& ctx, const Parallel& par, Registry& reg, ContactWorld& io);
/// Pair i's warm start: its accumulated impulses on its bodies (and, after a narrowphase, each point's
/// approach speed first).
void warm_start_soft_pair(void* rows, size_t i);
/// The rows as the constraint solver's extra rows (one per pair), with or without the push-out.
[[nodiscard]] ExtraRows soft_contact_rows(SoftContacts& rows, bool use_bias);
/// Pair i's bounce (see restitute_soft_contacts), for solve_extra_rows.
void restitute_soft_pair(void* rows, size_t i);
/// After the positions moved with the solved velocities: each point's gap as it is now, and each
/// sticking pair's slip.
void advance_soft_separations(const Parallel& par, SoftContacts& io);
/// 1 / (d·K d) for an inverse-mass matrix K: the effective mass along the unit d [kg], 0 where K takes
/// nothing along d.
[[nodiscard]] double inverse_along(const Mat3& k, const Vec3& d);
/// A point's effective masses: along the normal with the modes, in the contact plane without them.
void set_point_masses(SoftPoint& p);
/// The pairs' loads into their anchors (warm starting), contacts, events and the deepest overlap.
void finish_soft_contacts(const StepContext& ctx, const Parallel& par, Registry& reg, ContactWorld& io);

} // namespace supermodal
