// SPDX-License-Identifier: MIT
// Penalty constraints: soft springs that hold superquadric parts together (ThingWorld's joints).
//
// Each constraint is a spring–damper set by a natural frequency and a damping ratio and scaled by the
// pair's effective mass at the anchors (k = m_eff·(2πf)², c = 2ζ·m_eff·2πf), so one setting is stable
// for any mass ratio at the world's dt. The spring is integrated implicitly, so any frequency is stable
// at any step (docs/constraints.md). On a modal body it acts through the modes at the anchor.
// Anchors are given in a part's shape frame, either as a point or as a place on its surface (a
// direction from the centre, or Barr's angles η, ω) that moves with the surface when the part is
// resized or reshaped.
#pragma once

#include "supermodal/api.h"
#include "supermodal/entity.h"
#include "supermodal/math.h"
#include "supermodal/result.h"

#include <compare>
#include <cstdint>
#include <limits>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace supermodal
{

class World;

/// Opaque handle to a constraint of a World; Constraint{} is null. Stale handles are detected.
struct Constraint {
    uint32_t index = 0;
    uint32_t generation = 0;
    [[nodiscard]] constexpr bool is_null() const { return index == 0; }
    friend constexpr auto operator<=>(const Constraint&, const Constraint&) = default;
};

enum class ConstraintType : uint8_t {
    Point,    ///< Ball joint: the two anchors coincide. Optional swing and twist limits.
    Distance, ///< The anchors stay rest_length apart.
    Weld,     ///< The anchors coincide and the relative orientation stays as it was at creation.
};

/// How an anchor is placed on its body.
enum class AnchorKind : uint8_t {
    Point,     ///< `point` in the body's shape frame [m] (or in the world when the body is the world).
    Direction, ///< Where the ray from the shape origin along `direction` leaves the surface.
    Surface,   ///< Barr's parametric surface point at latitude `eta` and longitude `omega` [rad].
};

struct AnchorDef {
    AnchorKind kind = AnchorKind::Point;
    Vec3 point{};            ///< [m], shape frame (kind Point).
    Vec3 direction{0, 0, 1}; ///< Shape frame, any length > 0 (kind Direction).
    double eta = 0.0;        ///< Latitude [rad], in [−π/2, π/2] (kind Surface).
    double omega = 0.0;      ///< Longitude [rad], in [−π, π] (kind Surface).
};

/// How to make a constraint. Start from default_constraint_def() and change what differs.
struct ConstraintDef {
    std::string name; ///< Optional; used in summaries and find_constraint().
    ConstraintType type = ConstraintType::Point;
    Entity a{}; ///< First body (required).
    Entity b{}; ///< Second body; null = the world (anchor_b is then a world point).
    AnchorDef anchor_a{};
    AnchorDef anchor_b{};
    double frequency_hz = 30.0;   ///< Spring natural frequency [Hz], > 0 (implicit: no cap).
    double damping_ratio = 0.7;   ///< [-], ≥ 0.
    double rest_length = -1.0;    ///< Distance only [m]; < 0 = the anchors' distance at creation.
    double swing_limit = -1.0;    ///< Point only: max swing from the rest pose [rad]; < 0 = none.
    double twist_limit = -1.0;    ///< Point only: max twist about the axis [rad]; < 0 = none.
    Vec3 axis_a{};                ///< Limit axis in a's shape frame; zero = origin → anchor_a.
    double angular_damping = 0.0; ///< Joint friction [1/s], >= 0: a limb swinging on the joint slows at
                                  ///< this rate (torque from the parts' inertia about the joint,
                                  ///< implicit, so any value is stable).
    double break_force = std::numeric_limits<double>::infinity(); ///< [N], > 0; the spring breaks above it.
    bool collide_connected = false; ///< False: a and b do not collide with each other.
};

[[nodiscard]] SM_API ConstraintDef default_constraint_def();
/// Checks the numbers of a def (bodies are checked by create_constraint against the world).
[[nodiscard]] SM_API Status validate(const ConstraintDef& def);

/// Creates a constraint. The rest state (distance, relative orientation, limits' zero) is taken
/// from the bodies' poses now. Returns a null handle (and asserts) for an invalid def or stale body.
[[nodiscard]] SM_API Constraint create_constraint(World& world, const ConstraintDef& def);
SM_API void destroy_constraint(World& world, Constraint constraint);
[[nodiscard]] SM_API bool world_valid(const World& world, Constraint constraint);
/// Live constraints in index order.
[[nodiscard]] SM_API std::vector<Constraint> world_constraints(const World& world);
/// The first constraint with this name, or null.
[[nodiscard]] SM_API Constraint find_constraint(const World& world, std::string_view name);
[[nodiscard]] SM_API const ConstraintDef& constraint_def(const World& world, Constraint constraint);

/// How far a constraint is from holding, measured after the last step.
struct ConstraintError {
    double linear = 0.0;  ///< Anchor separation (point, weld) or length error (distance) [m].
    double angular = 0.0; ///< Weld orientation error, or how far past a joint limit [rad].
};
[[nodiscard]] SM_API ConstraintError constraint_error(const World& world, Constraint constraint);
/// Spring force on body a in the last substep [N], world (b gets the opposite).
[[nodiscard]] SM_API Vec3 constraint_force(const World& world, Constraint constraint);
/// True once the force exceeded break_force; a broken constraint stays inert.
[[nodiscard]] SM_API bool constraint_broken(const World& world, Constraint constraint);
/// Both anchors in the world [m] (a's first); for a null b, anchor_b's world point.
[[nodiscard]] SM_API std::pair<Vec3, Vec3> constraint_anchors(const World& world, Constraint constraint);
/// The largest linear error over unbroken constraints after the last step [m].
[[nodiscard]] SM_API double world_max_constraint_error(const World& world);
/// Constraints broken since the world was made [-].
[[nodiscard]] SM_API uint64_t world_broken_constraints(const World& world);

} // namespace supermodal
