// SPDX-License-Identifier: MIT
// One constraint prepared for a substep's velocity passes (world/constraint_solve.cpp): its two sides,
// effective masses and the impulses accumulated so far. Positions stay fixed meanwhile.
#pragma once

#include "constraints/constraint_world.h"
#include "dynamics/soft_constraint.h"
#include "world/constraint_side.h"

namespace supermodal
{

/// Soft-constraint coefficients of a backward-Euler spring–damper over one substep.
using Soft = SoftCoefficients;

/// Everything of a row but its sides: plain data, reset wholesale every substep.
struct ConstraintRowTerms {
    Entity id{};
    const ConstraintModel* model = nullptr; ///< In the constraint registry, fixed while the world steps.
    ConstraintState* state = nullptr;
    bool active = false; ///< Prepared (its bodies exist); an inactive row is skipped.
    Soft soft{};
    double h = 0.0; ///< Substep [s].
    Vec3 gap{};     ///< Anchor a − anchor b [m] (point, weld) or n·(len − rest) (distance).
    Vec3 normal{};  ///< Distance: unit a − b.
    Mat3 mass{};    ///< Point/weld: K⁻¹ [kg]; distance: m_eff on the diagonal.
    bool has_mass = false;
    Vec3 impulse{}; ///< Accumulated linear impulse on a this substep [N·s].
    // Angular parts: weld (3-D) or up to two one-sided limit rows (axis, excess).
    Vec3 theta{};    ///< Weld error rotation vector [rad], world.
    Mat3 ang_mass{}; ///< Weld: (Ia⁻¹ + Ib⁻¹)⁻¹ [kg·m²].
    bool has_ang_mass = false;
    Vec3 ang_impulse{}; ///< Accumulated angular impulse on b [N·m·s].
    // Limit slots: 0 swing, 1 twist.
    bool limit_active[2]{};
    Vec3 limit_axis[2]{};      ///< Unit world axes of violated limits.
    double limit_excess[2]{};  ///< [rad], > 0 when violated.
    double limit_mass[2]{};    ///< [kg·m²].
    double limit_impulse[2]{}; ///< Accumulated, ≥ 0 (pushes back only) [N·m·s].
    // Joint friction: relative spin + compliance·impulse = 0, solved with the other rows.
    bool has_friction = false;
    Mat3 friction_compliance{}; ///< (h·C)⁻¹ [1/(kg·m²)], C the friction coefficient [N·m·s].
    Mat3 friction_mass{};       ///< (Ia⁻¹ + Ib⁻¹ + (h·C)⁻¹)⁻¹ [kg·m²].
    Vec3 friction_impulse{};    ///< Accumulated angular impulse on b [N·m·s].
};

/// The sides hold modal buffers that make_side() refills in place, so they are kept, not reset.
struct ConstraintRow : ConstraintRowTerms {
    Side a, b;
};

} // namespace supermodal
