// SPDX-License-Identifier: MIT
// One cell of the stability map (docs/stability.md): a small scene built with the public API, stepped
// for a short simulated time, and what it did: NaN/Inf, energy gain, penetration, guards. Shared by
// bench/stability_map.cpp (the full grid, CSV) and tests/stability/stability_test.cpp (a coarse subset).
#pragma once

#include "supermodal/world.h"

#include <cstdint>
#include <cstdio>
#include <string>

namespace supermodal::stability
{

/// Which scene a cell builds; each slice of the map sweeps two of CellDef's axes over one scene.
enum class Scene : uint8_t {
    /// A tilted superquadric (ε1 = ε2 = epsilon, radii R, R, R/aspect with R = 0.2 m) dropped 0.1 m
    /// onto a static plane; dt = 2 ms, contact frequency at the cap. Axes: epsilon × aspect.
    Drop,
    /// A rounded cube (ε = 0.5, half-size 0.1 m) settled on a plane, then a second one of density
    /// mass_ratio × 1000 kg/m³ dropped 0.05 m onto it; contact frequency 50 Hz, dt = dt_ratio × 1/(10·50 Hz)
    /// (past 1 the cap clamps the frequency). Axes: mass_ratio × dt_ratio.
    Stack,
    /// A sphere (r = 0.1 m) shot down at `speed` onto a plane from 0.05 m; dt = 2 ms, contact frequency
    /// frequency_hz (the cap is 50 Hz). Axes: frequency_hz × speed.
    Impact,
    /// A modal superquadric (ε1 = ε2 = epsilon, r = 0.1 m, E = 2 MPa, 8 modes, central difference or
    /// exact_modal) dropped 0.05 m onto a plane; dt = dt_ratio × 2/ω_max. Axes: epsilon × dt_ratio.
    ModalDrop,
};

[[nodiscard]] const char* scene_name(Scene scene);

struct CellDef {
    Scene scene = Scene::Drop;
    double epsilon = 1.0;           ///< Both superquadric exponents [-].
    double aspect = 1.0;            ///< Largest over smallest radius [-].
    double mass_ratio = 1.0;        ///< Top body over bottom body mass [-] (Stack).
    double dt_ratio = 1.0;          ///< Step over its stability limit [-] (Stack, ModalDrop).
    double frequency_hz = 0.0;      ///< Penalty frequency [Hz], 0 = the cap 1/(10 h) (Impact).
    double speed = 0.0;             ///< Initial downward speed [m/s] (Impact).
    double seconds = 1.0;           ///< Simulated time after the scene is set up [s].
    double restitution = 0.5;       ///< Of every body [-].
    bool exact_modal = false;       ///< ModalDrop: the exact integrator instead of central difference.
    bool static_correction = false; ///< ModalDrop: ModalBodyDef::static_correction (mode acceleration).
    ContactSolver solver = ContactSolver::Penalty; ///< Soft: frequency_hz sets the soft spring instead.
    std::FILE* trace = nullptr; ///< If set, one CSV line per step: time, gain, modal energy / E_ref,
                                ///< contacts, penetration (for looking into one cell).
};

struct CellResult {
    bool accepted = false;   ///< validate() accepted every def and create_body made every body.
    std::string refusal;     ///< validate()'s message when not accepted.
    bool non_finite = false; ///< A NaN/Inf in a pose, velocity or energy, or a non-finite counter > 0.
    /// max over steps of (E(t) − E0) / E_ref with E = Σ kinetic + potential + modal energy (for central
    /// difference the energy it conserves, stability_cells.cpp modal_energy) and E_ref the
    /// energy the scene can dissipate (drop height and initial speed above the lowest resting pose).
    /// gain_all: every step; it leaves out the penalty springs' stored energy (≥ 0), so it is a lower
    /// bound on the true gain while a contact is active. gain_free: only at steps with no contact in
    /// that step or the next (no spring holds energy): exact, but −inf where no such step exists.
    double gain_all = 0.0;
    double gain_free = 0.0;
    int free_steps = 0;
    double max_penetration = 0.0;     ///< Deepest penetration of any substep (contact events) [m].
    double max_penetration_rel = 0.0; ///< … over the smallest radius of the bodies [-].
    double dt = 0.0;                  ///< The step used [s].
    double limit_dt = 0.0;            ///< The stability limit dt_ratio refers to [s] (0 where unused).
    StepWarnings warnings{};          ///< Counters at the end of the run (the Stack's settling included).
    double wall_seconds = 0.0;
    /// A guard acted: a frequency clamp, an extra substep, a modal integrator switch, a gyroscopic
    /// fallback, or a refused def.
    [[nodiscard]] bool guard() const
    {
        return !accepted || warnings.contact_frequency_clamps > 0 || warnings.speculative_substeps > 0 ||
               warnings.modal_integrator_switches > 0 || warnings.gyroscopic_fallbacks > 0;
    }
};

/// Builds and runs one cell.
[[nodiscard]] CellResult run_cell(const CellDef& def);

/// CSV header and one row (no newline) of a cell: slice name, its axes, its results.
[[nodiscard]] std::string csv_header();
[[nodiscard]] std::string csv_row(const std::string& slice, const CellDef& def, const CellResult& r);

} // namespace supermodal::stability
