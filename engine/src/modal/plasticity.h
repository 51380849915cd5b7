// SPDX-License-Identifier: MIT
// Plastic relief in modal space (the paper's clay moulding): where the elastic part of the deformation
// stresses the body past its yield stress, part of it becomes the body's new rest shape.
#pragma once

#include "modal/stress.h"

#include <limits>
#include <span>

namespace supermodal::modal
{

/// A material's plastic behaviour (equivalent uniaxial, von Mises).
struct PlasticParams {
    double yield_stress = std::numeric_limits<double>::infinity(); ///< σ_y [Pa], > 0; ∞ = elastic.
    double hardening = 0.0; ///< Linear hardening modulus H [Pa], ≥ 0: the yield stress grows by
                            ///< H per unit of accumulated plastic strain.
    double max_plastic_strain =
        std::numeric_limits<double>::infinity(); ///< Accumulated plastic strain
                                                 ///< [-] past which the body flows no more (fully worked).
    [[nodiscard]] bool plastic() const { return yield_stress < std::numeric_limits<double>::infinity(); }
};

struct PlasticStep {
    double trial_von_mises = 0.0; ///< Peak von Mises stress of the elastic part before relief [Pa]
                                  ///< where it exceeds the current yield; else some value at most that
                                  ///< (points that cannot yield are not evaluated), 0 when nothing can
                                  ///< flow (elastic, or fully worked).
    double von_mises = 0.0;       ///< After relief [Pa].
    bool yielded = false;         ///< The rest shape moved.
};

/// One return step, radial in modal space. With q_e = q − q_p the elastic amplitudes and σ_t their peak
/// von Mises stress (stress is linear in q_e), if σ_t exceeds the current yield σ_c = σ_y + H ε_p:
/// Δε_p = (σ_t − σ_c)/(E + H) (the uniaxial return with linear hardening; clipped so ε_p stays within
/// max_plastic_strain), the elastic part is scaled to carry σ_t − E Δε_p (= σ_c + H Δε_p) and the rest
/// moves by the remainder: q_p += (1 − s) q_e, s = (σ_t − E Δε_p)/σ_t. q itself (the shape) does not
/// change, nor do the rates: the step only dissipates elastic energy, ½ω²q_e² falls by 1 − s².
PlasticStep relieve_plastic(const StressModel& model, const PlasticParams& params, double young,
                            std::span<const double> q, std::span<double> io_q_plastic,
                            double& io_plastic_strain);

} // namespace supermodal::modal
