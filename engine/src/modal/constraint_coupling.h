// SPDX-License-Identifier: MIT
// A constraint anchor on a modal body: how the modes move it and how an impulse there loads them.
// The anchor's material point carries the modal displacement u = R·Φ(x)q and (for welds) the small
// rotation θ = R·½∇×(Φ(x)q). A constraint impulse J (angular impulse L) over a substep h is a generalized
// force held over it, Q_k += (φ_kᵀRᵀJ + ψ_kᵀRᵀL)/h, which the ModalUpdate stage then steps exactly.
// The constraint sees the anchor's mean velocity over the substep, (u(t+h) − u(t))/h, which that force
// changes by b1_k/h² per unit impulse (b1 of the mode's step map: ½·sinc²(ωh/2)·h² undamped, h²/2 for a
// free mass). So the modes join the effective mass exactly as the integrator will move them, and the
// implicit spring stays stable for every mode: an impulse put into q̇ instead resonates with the exact
// step near ωh = π (spectral radius 1.06 per substep, computed for one mode against a fixed anchor).
#pragma once

#include "modal/modal_body.h"

#include <vector>

namespace supermodal
{

/// The modes at one anchor for one substep, world frame. Empty (body null) for a rigid body.
struct ModalAnchor {
    ModalBody* body = nullptr;
    std::vector<Vec3> phi;     ///< (r) displacement per unit q_k [1/√kg].
    std::vector<Vec3> psi;     ///< (r) rotation per unit q_k [rad/(√kg·m)]; empty unless asked for.
    std::vector<double> drift; ///< (r) mean rate of q_k over the substep without new load [√kg·m/s].
    std::vector<double> gain;  ///< (r) b1_k/h: mean rate per unit generalized force [s].
    double h = 0.0;            ///< Substep [s].
    Vec3 displacement{};       ///< R·Φ(x)q over all modes [m].
    Vec3 rotation{};           ///< R·Ψ(x)q over all modes [rad] (with psi).
    std::vector<Vec3> work;    ///< Scratch of the ψ differences, kept so a reused anchor allocates nothing.

    [[nodiscard]] bool active() const { return body != nullptr; }
};

/// Fills `out` for the anchor at rest point `local` [m] (shape frame) of modal body `b` (null: rigid) whose
/// world_from_body rotation is `rot`, for substep h [s]; `with_rotation` also evaluates ψ = ½∇×φ (by
/// central differences inside the lattice box). Returns false (out.body null) for a rigid body or a
/// non-finite anchor.
bool modal_anchor(ModalBody* b, const Quat& rot, const Vec3& local, double h, bool with_rotation,
                  ModalAnchor& out);
/// The anchor's mean modal velocity over the substep [m/s]: Σ φ_k (drift_k + gain_k Q_k), with Q the
/// generalized forces constraints have put on the body so far in this substep.
[[nodiscard]] Vec3 modal_anchor_velocity(const ModalAnchor& a);
/// The same for the rotation at the anchor [rad/s] (zero without psi).
[[nodiscard]] Vec3 modal_anchor_spin(const ModalAnchor& a);
/// Σ (gain_k/h) φ_k φ_kᵀ [1/kg]: mean anchor velocity change per unit impulse through the modes.
[[nodiscard]] Mat3 modal_anchor_inverse_mass(const ModalAnchor& a);
/// Σ (gain_k/h) ψ_k ψ_kᵀ [1/(kg·m²)]: the same for spin per unit angular impulse.
[[nodiscard]] Mat3 modal_anchor_inverse_inertia(const ModalAnchor& a);
/// Q_k += (φ_k·J + ψ_k·L)/h for impulse J [N·s] and angular impulse L [N·m·s], world: a generalized
/// force held over this substep (ModalLoads::load, consumed by the ModalUpdate stage).
void modal_anchor_push(ModalAnchor& a, const Vec3& impulse, const Vec3& angular_impulse);

} // namespace supermodal
