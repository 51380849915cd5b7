// SPDX-License-Identifier: MIT
#include "contact/penalty.h"

#include <algorithm>
#include <cmath>

namespace supermodal
{
namespace
{

// Tangential spring frequency relative to the normal one, on the tangential effective mass (which
// includes rotation about the centres of mass): below 1 so that a body held by several sticking
// contacts (a box in a stack has two) stays inside the explicit stability region.
constexpr double k_tangential_frequency_ratio = 0.7;
// Damping ratio of the tangential spring: enough that a sticking contact does not ring, small enough
// that the explicit dashpot of two contacts on one body does not overshoot (c·h/m < 1 each).
constexpr double k_tangential_damping_ratio = 0.5;
// Cap on a normal dashpot's c·h/m_eff [-]: two contacts on a box against each other stay below 1
// (2 × 2 × 0.4 × m_eff/m = 0.8 with m_eff = m/2). At the default frequency (ωh = 0.63) restitutions
// e ≥ 0.45 are not affected (c·h/m_eff = 2ζ·ωh ≤ 0.4 for ζ ≤ 0.32); lower ones bounce a little more.
constexpr double k_max_dashpot_step = 0.4;

// Restitution of the no-pull spring–dashpot x'' + 2ζx' + x = 0 (unit frequency): contact starts at
// x = 0, x' = 1 and ends when the force x + 2ζx' first reaches zero, at ω_d·t = atan2(2ζω_d, 2ζ² − 1)
// (ω_d = √(1 − ζ²)); e = −x'(t). The textbook exp(−ζπ/ω_d) ignores the clamp and asks for too little
// damping (a 0.5 target bounced to 0.56, measured).
double clamped_restitution(double zeta)
{
    if (zeta >= 1.0)
        return 0.0;
    const double wd = std::sqrt(1.0 - zeta * zeta);
    const double phase = std::atan2(2.0 * zeta * wd, 2.0 * zeta * zeta - 1.0);
    return -std::exp(-zeta * phase / wd) * (std::cos(phase) - zeta * std::sin(phase) / wd);
}

// ζ for restitution e, by bisection (e falls monotonically with ζ).
double damping_ratio_for_restitution(double e)
{
    double lo = 0.0, hi = 1.0;
    for (int it = 0; it < 50; ++it) {
        const double mid = 0.5 * (lo + hi);
        (clamped_restitution(mid) > e ? lo : hi) = mid;
    }
    return 0.5 * (lo + hi);
}

// Inverse effective mass of a body at offset r for a push along unit d: 1/m + (r×d)·I⁻¹(r×d); for
// d = 0 (any tangent direction) the bound 1/m + |r|²·max(I⁻¹) [1/kg].
double inverse_mass_at(const BodyModel& m, const Pose& p, const Vec3& r, const Vec3& d)
{
    if (m.motion != MotionType::Dynamic)
        return 0.0;
    const Vec3& ii = m.inv_inertia_body;
    if (d == Vec3{})
        return m.inv_mass + dot(r, r) * std::max({ii.x, ii.y, ii.z});
    const Vec3 rd = inv_rotate(principal_orientation(m, p.orientation), cross(r, d));
    return m.inv_mass + dot(rd, hadamard(ii, rd));
}

// n·I⁻¹n in the world frame [1/(kg·m²)]: how easily the body turns about the contact normal.
double inverse_twist_inertia(const BodyModel& m, const Pose& p, const Vec3& n)
{
    if (m.motion != MotionType::Dynamic)
        return 0.0;
    const Vec3 nb = inv_rotate(principal_orientation(m, p.orientation), n);
    return dot(nb, hadamard(m.inv_inertia_body, nb));
}

// Largest principal inverse inertia [1/(kg·m²)]: a bound over every axis of the contact plane.
double max_inverse_inertia(const BodyModel& m)
{
    if (m.motion != MotionType::Dynamic)
        return 0.0;
    const Vec3& ii = m.inv_inertia_body;
    return std::max({ii.x, ii.y, ii.z});
}

// The two bodies of a pair, dereferenced once.
struct PairSides {
    const BodyModel& ma;
    const BodyModel& mb;
    const Pose& pa;
    const Pose& pb;
    const Velocity& va;
    const Velocity& vb;
};

// The pair's contact frame: the points' weighted mean normal and centroid.
struct PairFrame {
    Vec3 n{};                // unit contact normal, b towards a
    Vec3 centroid{};         // where friction, torsion and the summary act [m], world
    Vec3 ra{}, rb{};         // centroid from each centre of mass [m], world
    double weight_sum = 0.0; // Σ of the points' weights [-]
};

PairFrame pair_frame(std::span<const ContactPoint> points, const Pose& pa, const Pose& pb)
{
    PairFrame f;
    Vec3 normal_sum{};
    for (const ContactPoint& cp : points) {
        normal_sum += cp.weight * cp.normal;
        f.centroid += cp.weight * cp.point;
        f.weight_sum += cp.weight;
    }
    f.centroid = f.centroid / f.weight_sum;
    f.n = normalized(normal_sum);
    f.ra = f.centroid - pa.position;
    f.rb = f.centroid - pb.position;
    return f;
}

// Modes are lighter than the rigid body: they join the effective mass. Each point loads the modes
// through its own φ(point), so the weighted mean over the points (along each point's normal; d = 0:
// any direction) is taken, a trace bound on the fastest mode the pair's springs excite. The
// centroid's alone is not: on a star-shaped (ε = 3) modal body it fell between two tips, where φ is
// small, and the spring was stiff enough to throw the tips' modes to 33× the drop energy in one step
// (docs/stability.md). 0 without modes [1/kg].
double modal_inverse_mass(const PairModes* modes, const BodyPair& pair, std::span<const ContactPoint> points,
                          double weight_sum, bool along_normal)
{
    if (modes == nullptr)
        return 0.0;
    double sum = 0.0;
    for (const ContactPoint& cp : points) {
        const Vec3 d = along_normal ? cp.normal : Vec3{};
        sum += cp.weight * (modes->inverse_mass(modes->ctx, pair.a, cp.point, d) +
                            modes->inverse_mass(modes->ctx, pair.b, cp.point, d));
    }
    return sum / weight_sum;
}

// Rolling resistance: a spring on the relative rolling angle (the tangential part of the relative
// spin), clamped to ℓ·F_n with ℓ the pair's lever arm, the torque a contact patch offset by ℓ ahead of
// the centre exerts. Sets out.torque_a/b (zero when the pair has none) and the anchor's roll.
void add_rolling_resistance(const PairSides& s, const Vec3& n, double normal_force, double omega,
                            PairAnchor& anchor, PairForce& out)
{
    out.torque_a = out.torque_b = {};
    const double ell = std::max(s.ma.rolling_resistance, s.mb.rolling_resistance);
    // The smallest inertia about any tangent axis: the spring's frequency stays at or under ω for
    // every axis, and rolling (which also moves the centre of mass) is slower still.
    const double inv_j = max_inverse_inertia(s.ma) + max_inverse_inertia(s.mb);
    out.has_roll = ell > 0.0 && normal_force > 0.0 && inv_j > 0.0;
    if (!out.has_roll) {
        anchor.roll = {};
        return;
    }
    const double j = 1.0 / inv_j;
    const double k = j * omega * omega, c = 2.0 * k_tangential_damping_ratio * j * omega;
    const Vec3 w_rel = s.va.angular - s.vb.angular;
    const Vec3 w_t = w_rel - dot(w_rel, n) * n;
    Vec3 tau = -k * anchor.roll - c * w_t;
    const double limit = ell * normal_force;
    if (length(tau) > limit) {
        tau = tau * (limit / length(tau));
        anchor.roll = -(tau + c * w_t) / k; // rolls on: the anchor follows
    }
    out.torque_a = tau;
    out.torque_b = -1.0 * tau;
}

struct NormalSpring {
    double k = 0.0;       // secant stiffness: F = k·δ [N/m]
    double omega = 0.0;   // rate of the tangent stiffness on m_eff [rad/s], for dampers and friction
    bool clamped = false; // material stiffness cut to the cap
};

// The pair's normal spring. Frequency mode: k = m_eff·ω². Material mode (Hertz, sphere on sphere):
// F = (4/3)·E*·√R*·δ^(3/2) with 1/E* = Σ(1 − ν²)/E and 1/R* = Σ 1/R, taken at the pair's mean depth
// as a secant k = (4/3)·E*·√(R*·δ); its tangent, 1.5·k, sets the rate, which the explicit step
// caps at params.omega.
NormalSpring normal_spring(const PenaltyParams& params, const BodyModel& ma, const BodyModel& mb,
                           double m_eff, std::span<const ContactPoint> points, double weight_sum)
{
    NormalSpring s;
    if (!params.material) {
        s.omega = params.omega;
        s.k = m_eff * s.omega * s.omega;
        return s;
    }
    double mean_depth = 0.0;
    for (const ContactPoint& cp : points)
        mean_depth += cp.weight * cp.depth;
    mean_depth /= weight_sum;
    const double e_star = 1.0 / (ma.contact_compliance + mb.contact_compliance);
    const double curvature = ma.curvature + mb.curvature; // > 0: two planes never pair
    s.k = (4.0 / 3.0) * e_star * std::sqrt(std::max(mean_depth, 0.0) / curvature);
    const double k_cap = m_eff * params.omega * params.omega / 1.5;
    // A floor keeps the friction spring (whose anchor divides by its stiffness) well-defined at a
    // grazing touch, where Hertz gives no stiffness at all.
    const double k_floor = 1e-6 * k_cap;
    if (s.k > k_cap) {
        s.k = k_cap;
        s.clamped = true;
    }
    s.k = std::max(s.k, k_floor);
    s.omega = std::sqrt(1.5 * s.k / m_eff);
    return s;
}

struct HeldSpring {
    double per_area = 0.0; // stiffness per unit of point area used this substep [N/m per m²]
    double credit = 0.0;   // energy the contact has dissipated and not yet spent on a rise [J]
};

// Frequency mode gives a pair the spring k = m_eff·ω² on the points' area-weighted mean depth. Both
// the pose (m_eff) and the set of touching points (the weights are shares of the touching area) change
// while the pair is compressed, so that force is not conservative: as a tip lands, each point that
// joins at zero depth lowers the mean, and as it lifts off, each shallow point that leaves raises it;
// pointed bodies landing on a tip gained 32–226% of the drop energy (docs/stability.md). So a touching
// pair holds its spring per unit of point area, k/A: each point is then a spring of its own, and the
// sum is conservative. The held value may fall at once (that removes stored energy, and keeps k ≤
// m_eff·ω², so the step stays stable as m_eff drops or the area grows); a rise of Δ stores
// ½·Δ·Σaδ² and is allowed only as far as the energy the contact has already dissipated pays for it.
HeldSpring hold_stiffness(double k_target, double area, const PairAnchor* old,
                          std::span<const ContactPoint> points)
{
    const double target = k_target / area;
    if (old == nullptr || !(old->stiffness > 0.0) || target <= old->stiffness)
        return {target, old != nullptr ? old->credit : 0.0};
    double stored = 0.0; // Σ a·δ² [m⁴]
    for (const ContactPoint& cp : points)
        stored += cp.area * cp.depth * cp.depth;
    const double rise = stored > 0.0 ? std::min(target - old->stiffness, 2.0 * old->credit / stored)
                                     : target - old->stiffness;
    return {old->stiffness + rise, std::max(0.0, old->credit - 0.5 * rise * stored)};
}

// The pair's normal spring–dashpot as its points feel it.
struct NormalLaw {
    bool hold = false;    // the spring is held per unit of point area (hold_stiffness)
    bool clamped = false; // material stiffness cut to the cap
    double k = 0.0;       // spring per unit of point weight when not held [N/m]
    HeldSpring held{};    // the held spring, when held
    double omega = 0.0;   // rate of the spring actually used [rad/s]
    double c = 0.0;       // dashpot per unit of point weight [N·s/m]
    /// The spring's stiffness at point cp [N/m].
    [[nodiscard]] double stiffness_at(const ContactPoint& cp) const
    {
        return hold ? held.per_area * cp.area : k * cp.weight;
    }
};

// Effective masses at the contact, rotation included, so a push off the centre of mass (an edge, a
// corner) gets a spring its own inertia can carry at this substep; modal_n: the modes' share
// (modal_inverse_mass) [1/kg].
NormalLaw normal_law(const PenaltyParams& params, const PairSides& s, const PairFrame& f, double modal_n,
                     std::span<const ContactPoint> points, const PairAnchor* old_anchor, ZetaCache& io_zeta)
{
    const double m_eff =
        1.0 / (inverse_mass_at(s.ma, s.pa, f.ra, f.n) + inverse_mass_at(s.mb, s.pb, f.rb, f.n) + modal_n);
    const double zeta = params.damping_ratio >= 0.0
                            ? params.damping_ratio
                            : io_zeta.get(std::max(s.ma.restitution, s.mb.restitution));
    const NormalSpring spring = normal_spring(params, s.ma, s.mb, m_eff, points, f.weight_sum);
    NormalLaw law;
    law.clamped = spring.clamped;
    law.k = spring.k;
    // Frequency mode holds a rigid pair's spring per unit of point area (hold_stiffness). Not held:
    // Hertz springs (their secant stiffness rises with depth by design), and pairs with a modal body,
    // whose m_eff includes the modes: adaptive bodies change their mode count mid-contact, and holding
    // the spring there moved ball_on_board's strike (0.24 → 0.39 mm off the 16-mode reference at a
    // 0.3 mm budget); the stability map's modal slices never gained energy without it.
    double area = 0.0;
    for (const ContactPoint& cp : points)
        area += cp.area;
    law.hold = !params.material && area > 0.0 && modal_n == 0.0;
    law.held = law.hold ? hold_stiffness(spring.k, area, old_anchor, points) : HeldSpring{};
    const double k_pair = law.hold ? law.held.per_area * area : spring.k;
    // The dashpot works on the spring actually used, so a held (softer) spring keeps its restitution.
    law.omega = k_pair == spring.k ? spring.omega : std::sqrt(k_pair / m_eff);
    // The dashpot is explicit: a body feels the sum of its contacts' c·h/m_eff, and in a stack every
    // middle box has two, whose Nyquist mode (neighbours moving against each other) flips the velocity
    // every step once the sum passes 1 (measured: ten boxes, e = 0.2, c·h/m_eff = 0.92 per contact, in
    // a period-2 limit cycle at 0.19 m/s). Capped at k_max_dashpot_step for rigid pairs. Not for pairs
    // with a modal body: the modes absorb the dashpot's kick, and the cap starves them of damping
    // (measured: a soft sphere kept bouncing at 0.2–0.3 m/s for 12 s with it, rests within 3 s without).
    const double c_free = 2.0 * zeta * m_eff * law.omega;
    law.c = modal_n > 0.0 ? c_free : std::min(c_free, k_max_dashpot_step * m_eff / params.h);
    return law;
}

// Sums of the points' normal forces.
struct NormalForces {
    Vec3 total{};              // Σ force on a [N], world
    Vec3 torque_a{};           // about a's centre of mass [N·m], world
    Vec3 torque_b{};           // about b's centre of mass [N·m], world
    double normal_force = 0.0; // Σ magnitude [N]
    double deepest = 0.0;      // [m]
    double dissipated = 0.0;   // by the dashpot or a let-go spring over the substep [J]
};

// Each point's spring–dashpot, written to out_point_force (one per point, when given).
NormalForces normal_forces(const NormalLaw& law, const PairSides& s, std::span<const ContactPoint> points,
                           double h, std::span<double> out_point_force)
{
    NormalForces out;
    for (size_t i = 0; i < points.size(); ++i) {
        const ContactPoint& cp = points[i];
        const double vn =
            dot(velocity_at(s.va, s.pa.position, cp.point) - velocity_at(s.vb, s.pb.position, cp.point),
                cp.normal);
        // No pull: a separating contact whose dashpot would exceed its spring just lets go.
        const double spring_force = law.stiffness_at(cp) * cp.depth;
        const double f = std::max(0.0, spring_force - law.c * vn * cp.weight);
        out.dissipated += (spring_force - f) * vn * h; // ≥ 0: the dashpot, or a let-go spring
        const Vec3 fv = f * cp.normal;
        out.total += fv;
        out.torque_a += cross(cp.point - s.pa.position, fv);
        out.torque_b -= cross(cp.point - s.pb.position, fv);
        if (i < out_point_force.size())
            out_point_force[i] = f;
        out.normal_force += f;
        out.deepest = std::max(out.deepest, cp.depth);
    }
    return out;
}

// The pair's anchor going into this substep's tangential springs: the old one turned into today's
// contact plane, with the held normal spring and the energy credit it may spend.
PairAnchor carried_anchor(uint64_t key, const PairAnchor* old_anchor, const Vec3& n, const NormalLaw& law,
                          double dissipated)
{
    PairAnchor anchor{key, {}};
    anchor.stiffness = law.held.per_area;
    anchor.credit = law.hold ? law.held.credit + dissipated : 0.0;
    if (old_anchor != nullptr) {
        anchor.spring = old_anchor->spring - dot(old_anchor->spring, n) * n; // keep it in today's plane
        anchor.twist = old_anchor->twist;
        anchor.roll = old_anchor->roll - dot(old_anchor->roll, n) * n;
    }
    return anchor;
}

// Friction: a tangential spring anchored where the contact stuck, clamped to the Coulomb cone
// (`limit` [N]); modal_t: the modes' inverse mass over any direction [1/kg]. The force on a at the
// centroid [N], world; a sliding contact's anchor follows.
Vec3 friction_force(const PairSides& s, const PairFrame& f, double modal_t, double omega_t, double limit,
                    PairAnchor& anchor)
{
    const Vec3 v_rel =
        velocity_at(s.va, s.pa.position, f.centroid) - velocity_at(s.vb, s.pb.position, f.centroid);
    const Vec3 v_t = v_rel - dot(v_rel, f.n) * f.n;
    const double m_t =
        1.0 / (inverse_mass_at(s.ma, s.pa, f.ra, {}) + inverse_mass_at(s.mb, s.pb, f.rb, {}) + modal_t);
    const double kt = m_t * omega_t * omega_t;
    const double ct = 2.0 * k_tangential_damping_ratio * m_t * omega_t;
    Vec3 ft = -kt * anchor.spring - ct * v_t;
    if (length(ft) > limit) {
        ft = limit > 0.0 ? ft * (limit / length(ft)) : Vec3{};
        anchor.spring = limit > 0.0 ? -(ft + ct * v_t) / kt : Vec3{}; // slide: the anchor follows
    }
    return ft;
}

struct TwistTorque {
    bool active = false; // the pair has a patch and a body that can turn about the normal
    double tau = 0.0;    // torque on a about the normal [N·m]
};

// Torsional friction about the normal: a spring on the relative twist, clamped to what Coulomb
// friction over the patch can resist ((2/3)·μ·F·R for a disc of radius R = √(2ρ²), ρ² the patch's
// second moment; `limit` = μ·F [N]). Without it a single friction anchor lets a resting face spin up.
TwistTorque twist_torque(const PairSides& s, const PairFrame& f, std::span<const ContactPoint> points,
                         double omega_t, double limit, PairAnchor& anchor)
{
    double patch_rho2 = 0.0;
    for (const ContactPoint& cp : points) {
        const Vec3 d = cp.point - f.centroid;
        patch_rho2 += cp.weight * (dot(d, d) - dot(d, f.n) * dot(d, f.n)) / f.weight_sum;
    }
    const double inv_j = inverse_twist_inertia(s.ma, s.pa, f.n) + inverse_twist_inertia(s.mb, s.pb, f.n);
    TwistTorque out;
    out.active = patch_rho2 > 0.0 && inv_j > 0.0;
    if (!out.active) {
        anchor.twist = 0.0;
        return out;
    }
    const double j = 1.0 / inv_j;
    const double k_tw = j * omega_t * omega_t, c_tw = 2.0 * k_tangential_damping_ratio * j * omega_t;
    const double spin = dot(s.va.angular - s.vb.angular, f.n);
    out.tau = -k_tw * anchor.twist - c_tw * spin;
    const double tau_limit = (2.0 / 3.0) * limit * std::sqrt(2.0 * patch_rho2);
    if (std::abs(out.tau) > tau_limit) {
        out.tau = std::copysign(tau_limit, out.tau);
        anchor.twist = -(out.tau + c_tw * spin) / k_tw;
    }
    return out;
}

} // namespace

double ZetaCache::get(double e)
{
    for (const Entry& entry : entries)
        if (entry.e == e)
            return entry.zeta;
    entries[next] = {e, damping_ratio_for_restitution(e)};
    const double zeta = entries[next].zeta;
    next = (next + 1) % entries.size();
    return zeta;
}

PairForce penalty_pair(const PenaltyParams& params, const BodyPair& pair, const PenaltyBody& a,
                       const PenaltyBody& b, std::span<const ContactPoint> points,
                       const PairAnchor* old_anchor, ZetaCache& io_zeta, const PairModes* modes,
                       std::span<double> out_point_force)
{
    PairForce out;
    if (points.empty() || !(a.model->inv_mass + b.model->inv_mass > 0.0))
        return out;
    const PairSides s{*a.model, *b.model, *a.pose, *b.pose, *a.velocity, *b.velocity};
    const PairFrame f = pair_frame(points, s.pa, s.pb);
    const double modal_n = modal_inverse_mass(modes, pair, points, f.weight_sum, true);
    const NormalLaw law = normal_law(params, s, f, modal_n, points, old_anchor, io_zeta);
    out.stiffness_clamped = law.clamped;
    const NormalForces normal = normal_forces(law, s, points, params.h, out_point_force);

    PairAnchor anchor = carried_anchor(pair.key(), old_anchor, f.n, law, normal.dissipated);
    const double omega_t = k_tangential_frequency_ratio * law.omega;
    const double limit = std::sqrt(s.ma.friction * s.mb.friction) * normal.normal_force;
    const double modal_t = modal_inverse_mass(modes, pair, points, f.weight_sum, false);
    const Vec3 ft = friction_force(s, f, modal_t, omega_t, limit, anchor);
    Vec3 torque_a = normal.torque_a, torque_b = normal.torque_b;
    torque_a += cross(f.centroid - s.pa.position, ft);
    torque_b -= cross(f.centroid - s.pb.position, ft);
    const TwistTorque twist = twist_torque(s, f, points, omega_t, limit, anchor);
    out.has_twist = twist.active;
    if (twist.active) {
        torque_a += twist.tau * f.n;
        torque_b -= twist.tau * f.n;
    }
    add_rolling_resistance(s, f.n, normal.normal_force, omega_t, anchor, out);
    torque_a += out.torque_a;
    torque_b += out.torque_b;

    out.touching = true;
    out.force_a = normal.total + ft;
    out.friction_force = ft;
    out.torque_a = torque_a;
    out.torque_b = torque_b;
    out.normal_force = normal.normal_force;
    out.anchor = anchor;
    out.info = {.a = pair.a,
                .b = pair.b,
                .point = f.centroid,
                .normal = f.n,
                .depth = normal.deepest,
                .force_on_a = normal.total + ft,
                .point_count = static_cast<int>(points.size())};
    return out;
}

} // namespace supermodal
