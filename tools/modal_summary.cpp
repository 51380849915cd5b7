// SPDX-License-Identifier: MIT
#include "modal_summary.h"

#include "supermodal/body.h"
#include "supermodal/modal.h"

#include <cmath>

namespace supermodal::cli
{
namespace
{

/// JSON has no infinity: an unbounded value is written as null.
nlohmann::json finite_or_null(double v)
{
    return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr);
}

} // namespace

void add_modal_summaries(const World& world, nlohmann::json& io_bodies)
{
    const std::vector<Entity> bodies = world_bodies(world);
    for (size_t i = 0; i < bodies.size() && i < io_bodies.size(); ++i) {
        const ModalBasis* basis = body_modal_basis(world, bodies[i]);
        if (basis == nullptr)
            continue;
        const ModalAccuracy a = body_modal_accuracy(world, bodies[i]);
        const BodyStress s = body_max_stress(world, bodies[i]);
        const BodyPlasticState p = body_plastic_state(world, bodies[i]);
        double set = 0.0; // largest |q_p|: 0 for a body that never yielded
        for (double q : p.offsets)
            set = std::max(set, std::abs(q));
        io_bodies[i]["modal"] = {{"modes", basis->mode_count},
                                 {"energy_j", body_modal_energy(world, bodies[i])},
                                 {"residual", a.residual},
                                 {"load_norm_n", a.load_norm},
                                 {"static_energy_j", a.static_energy},
                                 {"truncated_energy_j", a.truncated_energy},
                                 {"truncated_fraction", a.truncated_fraction},
                                 {"max_von_mises_pa", s.max_von_mises},
                                 {"max_von_mises_at", {s.where.x, s.where.y, s.where.z}},
                                 {"yield_stress_pa", finite_or_null(p.yield_stress)},
                                 {"plastic_strain", p.plastic_strain},
                                 {"max_plastic_offset", set}};
        const BodyModalActivity act = body_modal_activity(world, bodies[i]);
        if (act.adaptive) // "dynamics": "auto": what it chose and the error it left out
            io_bodies[i]["modal"]["auto"] = {{"active_modes", act.active_modes},
                                             {"most_active_modes", act.most_active_modes},
                                             {"chosen", act.most_active_modes > 0 ? "modal" : "rigid"},
                                             {"truncation_estimate_m", act.truncation_estimate},
                                             {"max_truncation_estimate_m", act.max_truncation_estimate},
                                             {"active_count_changes", act.active_count_changes},
                                             {"active_mode_substeps", act.active_mode_substeps},
                                             {"contact_samples", act.contact_samples},
                                             {"sample_spacing_m", act.sample_spacing},
                                             {"sampling_gap_m", act.sampling_gap},
                                             {"sampling_gap_met", act.sampling_gap_met},
                                             {"lattice", act.lattice_cells},
                                             {"lattice_frequency_change", act.lattice_frequency_change},
                                             {"lattice_converged", act.lattice_converged},
                                             {"lattice_error_estimate_m", act.lattice_error_estimate}};
    }
}

} // namespace supermodal::cli
