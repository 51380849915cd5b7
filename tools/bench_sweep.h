// SPDX-License-Identifier: MIT
// `supermodal bench`: the configurations of a speed/accuracy sweep, running one, and its errors against a
// converged reference run of the same scene (docs/speed_accuracy.md explains the method).
#pragma once

#include "supermodal/scene.h"

#include <array>
#include <optional>
#include <string>
#include <vector>

namespace supermodal::cli
{

/// Every knob the sweep knows, in the order it runs them.
[[nodiscard]] const std::vector<std::string>& bench_knobs();

/// One point of a sweep: the scene with one knob moved.
struct BenchConfig {
    std::string knob;  ///< Name from bench_knobs().
    std::string value; ///< What the knob was set to, as a short label ("x0.5", "support_map", "8").
    Scene scene;
};

/// What the sweep derives from the scene before it starts.
struct BenchBase {
    std::vector<std::string> modal_bodies;       ///< Names of the modal bodies.
    std::vector<size_t> modal_indices;           ///< Their indices in Scene::bodies.
    std::vector<std::array<int, 3>> modal_cells; ///< Their lattice cells as built (auto resolved).
    double spacing = 0.0; ///< Effective sample spacing [m]: the scene's, or the finest body default.
};

/// Builds the scene once to resolve automatic lattices and the default spacing; an error message when
/// the scene does not build.
[[nodiscard]] std::string resolve_base(const Scene& scene, BenchBase& base);
/// How the reference treats modal bodies' modes.
enum class ReferenceModes {
    All,     ///< every elastic mode of the lattice ("type": "full"; refused past k_max_full_dofs)
    Doubled, ///< twice the scene's count, capped at k_max_modes
    Scene,   ///< the scene's own counts
};
/// The converged reference: dt/8, sample spacing/2, modal bodies with `modes`, exact integrator.
[[nodiscard]] Scene reference_scene(const Scene& scene, const BenchBase& base, ReferenceModes modes);
/// One-knob-at-a-time configurations for the given knobs (all when empty); knobs without a subject in
/// this scene (modes, lattice, integrator with no modal body) give none.
[[nodiscard]] std::vector<BenchConfig> make_sweep(const Scene& scene, const BenchBase& base,
                                                  const std::vector<std::string>& knobs);

/// What one run records: states at the common sample times and the run's extremes.
struct BenchTrace {
    std::string refused;                 ///< Non-empty: the engine refused the configuration (why).
    std::vector<std::string> body_names; ///< Dynamic bodies, in creation order.
    std::vector<std::vector<Vec3>> com;  ///< [sample][body] centre of mass [m], world.
    double max_penetration = 0.0;        ///< Over every step [m].
    double max_constraint_error = 0.0;   ///< Over every step [m]; 0 without constraints.
    double energy_start = 0.0;           ///< Kinetic + potential + modal energy at t = 0 [J].
    double energy_end = 0.0;             ///< The same at the end [J].
    bool non_finite = false;             ///< A body or a modal state turned NaN/Inf (frozen or reset).
    std::vector<std::vector<double>> modal_frequencies_hz; ///< Per modal body (BenchBase order).
    long long steps = 0;
    double cpu_ms_per_step = 0.0; ///< Process CPU time of step() calls / steps [ms].
    double setup_ms = 0.0;        ///< Process CPU time to build the world (modal bases included) [ms].
};

/// Runs the scene for `seconds`, sampling every `sample_every` seconds of simulated time (linear
/// interpolation between step ends). With record false, only the timing fields are filled.
[[nodiscard]] BenchTrace run_bench(const Scene& scene, const BenchBase& base, double seconds,
                                   double sample_every, bool record = true);

/// Errors of a run against the reference.
struct BenchErrors {
    double trajectory_rms = 0.0;           ///< RMS over samples and dynamic bodies of |com − com_ref| [m].
    double trajectory_max = 0.0;           ///< The largest of those [m].
    std::optional<double> energy_drift;    ///< (E_end − E_start)/|E_start| [-]; none when E_start ≈ 0.
    std::optional<double> frequency_error; ///< max |f − f_ref|/f_ref over modal bodies and shared modes.
};
[[nodiscard]] BenchErrors compare_to_reference(const BenchTrace& run, const BenchTrace& reference);

/// The relative energy change of a trace, or none when its start energy is ~0.
[[nodiscard]] std::optional<double> energy_drift(const BenchTrace& trace);

} // namespace supermodal::cli
