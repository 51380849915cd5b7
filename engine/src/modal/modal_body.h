// SPDX-License-Identifier: MIT
// A modal body's components, grouped by who writes them while a world steps (MuJoCo's split: a const
// model, mutable data). ModalModel is shared by identical bodies and read-only; ModalSubstepMaps, derived
// from the model and the substep, is shared with it and written only between the parallel stages; the
// rest is the body's own: ModalState (what the step changes, hashed and snapshotted), ModalLoads (what
// contact, constraints and the host add during a substep, consumed by the step), DeformedSurface (written
// by UpdateSurfaces) and ModalStats (diagnostics).
#pragma once

#include "contact/collider.h"
#include "modal/integrator.h"
#include "modal/plasticity.h"
#include "supermodal/modal.h"

#include <future>
#include <memory>
#include <string>
#include <vector>

namespace supermodal
{

namespace modal
{
struct AccuracyCache;
}

/// How long the static correction of contact loads takes to follow them [s]: the part of its answer it
/// takes per substep h is 1 − e^(−h/τ) (bounded further by the loop's gain, correct_statically). Taken
/// at once (τ = 0), a resting soft ellipsoid (E = 1 MPa) never slept on either solver: its dent, far more
/// compliant than the contact spring, and the force chased each other; with 0.02 s it sleeps 3.4 mm lower
/// than with the modes alone (4 substeps of 1/60 s on the soft solver, 30 on penalty).
inline constexpr double k_contact_correction_time = 0.02;

/// Model: how a modal basis moves a collider's rest samples, shared by identical modal bodies.
struct ModalSurface {
    std::shared_ptr<const Collider> rest;    ///< Rest shape; its samples are in the body frame.
    std::shared_ptr<const ModalBasis> basis; ///< The basis the displacements come from.
    std::vector<double> sample_modes;        ///< Per rest sample, (3 × r) body-frame displacement per
                                             ///< unit amplitude, entry (sample·3 + axis)·r + k [1/√kg].
    std::vector<LatticeWeights> sample_weights;       ///< Per rest sample, where it sits in the lattice (a
                                                      ///< nodal field at the sample: the static correction).
    std::shared_ptr<const modal::StressModel> stress; ///< Stress points and stress per unit amplitude.
    std::shared_ptr<modal::AccuracyCache> accuracy;   ///< Full lattice for the accuracy report, built on
                                                      ///< first use.
    std::vector<double> mode_reach; ///< (r) per mode, the largest sample displacement per unit amplitude
                                    ///< [1/√kg]: what an amplitude moves the surface by, at most.
    /// The unmoulded rest shape: material points are named by where they were on it (modal_weights).
    /// Equal to `rest` until the body is remoulded; then `rest` holds its samples moved by rest_offsets.
    std::shared_ptr<const Collider> material;
    std::vector<Vec3> rest_offsets; ///< (nodes) how far the moulded rest shape moved [m]; empty: none.
};

/// A rebuild of a body's modes for its moulded rest shape, running on a thread of its own.
struct RemouldResult {
    std::shared_ptr<const ModalBasis> basis; ///< Null when the build failed (why: error).
    std::string error;
    std::vector<Vec3> rest_offsets; ///< (nodes) the moulded rest shape it was built for [m].
    std::vector<double> projection; ///< (r × r, row-major) least-squares map of old amplitudes to new.
    double seconds = 0.0;           ///< Wall time of the build and projection [s].
};

/// Model of a modal body: everything its step reads and never writes. Shared (read-only, any thread) by
/// the bodies made from the same basis, rest collider and ModalBodyDef.
struct ModalModel {
    std::shared_ptr<const ModalBasis> basis;
    std::shared_ptr<const ModalSurface> surface;
    std::vector<double> omega;  ///< (r) natural angular frequencies [rad/s].
    double damping_ratio = 0.0; ///< ζ [-].
    ModalIntegrator integrator = ModalIntegrator::Exact;
    modal::PlasticParams plastic;    ///< Yield, hardening, limit.
    double adaptive_tolerance = 0.0; ///< ModalBodyDef::adaptive_tolerance [m]; 0 = not adaptive.
    double remould_threshold = 0.0;  ///< ModalBodyDef::remould_threshold [-]; 0 = never.
    int remould_delay_steps = 1;     ///< ModalBodyDef::remould_delay_steps [-].
    bool static_correction = false;  ///< ModalBodyDef::static_correction.
    /// Each kept mode's relative frequency change from the lattice half as fine, when the lattice was
    /// chosen for the budget (modal/auto_lattice.h) [-] (r); empty otherwise.
    std::vector<double> lattice_changes;

    [[nodiscard]] size_t mode_count() const { return omega.size(); }
    [[nodiscard]] bool adaptive() const { return adaptive_tolerance > 0.0; }
};

/// Derived from a model and a substep h: what every mode's step needs, made once per (model, h). Shared by
/// the model's bodies; written only by prepare_modal_substep() on the stepping thread, before the
/// parallel stages read it, so it needs no lock.
struct ModalSubstepMaps {
    double h = 0.0;                     ///< Substep the maps are for [s]; 0 = not made yet.
    std::vector<modal::ModeStep> exact; ///< (r) per-mode exact maps for h.
    std::vector<double> sinc;           ///< (r) sinc(ω_k h / 2) of modal_inverse_mass.
};

/// What identical modal bodies share.
struct ModalShared {
    std::shared_ptr<const ModalModel> model;
    std::shared_ptr<ModalSubstepMaps> maps;
};

/// State: what the step changes, hashed (q, q_dot; q_plastic and plastic_strain of plastic bodies; active
/// of adaptive ones) and snapshotted (all).
struct ModalState {
    std::vector<double> q;          ///< (r) amplitudes [√kg·m].
    std::vector<double> q_dot;      ///< (r) their rates [√kg·m/s]; half a step behind q with
                                    ///< central difference (leapfrog).
    std::vector<double> host_force; ///< (r) generalized host forces for the next step [N/√kg]; cleared
                                    ///< after each step, like ForceAccumulator.
    std::vector<double> q_plastic;  ///< (r) plastic offsets q_p [√kg·m]: the rest shape has moved by
                                    ///< Φ q_p; the elastic part is q − q_p. Zero for elastic bodies.
    double plastic_strain = 0.0;    ///< Accumulated equivalent plastic strain [-] (hardening, limit).
    size_t active = 0; ///< Modes shown on the surface and felt by contact and constraints, the lowest
                       ///< ones (all unless adaptive); the others still step.
    // Remoulding (docs/modal.md "Remoulding").
    std::vector<double> rest_offsets;      ///< (3 × nodes) the moulded rest shape the model is built for
                                           ///< [m] (ModalSurface::rest_offsets); empty: none.
    uint64_t remould_step = 0;             ///< Step count at whose boundary a rebuild takes over; 0: none.
    std::vector<double> remould_q_plastic; ///< (r) q_p when it was asked for [√kg·m]: what it absorbs.
    bool remould_failed = false;           ///< A rebuild failed (a cell turned inside out): no more.
    /// (3 × nodes) the static correction of the last substep's contact and host loads [m], body frame:
    /// what the modes left out would add at each node (ModalBodyDef::static_correction); empty: off.
    std::vector<double> correction;
    /// (3 × nodes) the part of `correction` that contact loads make [m], relaxed towards their static
    /// answer over k_contact_correction_time (the surface it moves feeds back into the contact force).
    std::vector<double> contact_correction;
};

/// Loads of one substep: added by contact (nodal), constraints (load) and the host (host nodal loads,
/// per step), consumed and cleared by the ModalUpdate stage.
struct ModalLoads {
    std::vector<double> load; ///< (r) constraint generalized forces of this substep, held over it [N/√kg].
    std::vector<double> nodal_load; ///< (3 × lattice nodes) contact forces of this substep lumped on the
                                    ///< nodes [N], body frame; projected on the modes once per substep.
    bool has_nodal_load = false;
    std::vector<double> host_nodal_load; ///< (3 × nodes) host point loads of this step lumped likewise [N].
    bool has_host_nodal_load = false;
    /// (3 × nodes) the soft solver's contact forces of this substep lumped likewise [N]. They reached the
    /// modes through `load` already; only the static correction and the accuracy report read them.
    std::vector<double> solved_nodal_load;
    bool has_solved_nodal_load = false;
    std::vector<double> correction_load, correction_answer; ///< (3 × nodes) scratch of the static correction.
    double spring_work = 0.0;    ///< Σ over this substep's contact points of normal force × depth [J]: with
                                 ///< Fᵀ u_c, how much more compliant the dent is than the contact spring.
    std::vector<double> contact; ///< (r) Φᵀ nodal_load, made by the step: a kick [N/√kg] (scratch).
};

/// The body's own deformed copy of its rest collider, written by the UpdateSurfaces stage.
struct DeformedSurface {
    std::shared_ptr<Collider> collider; ///< This body's collider (BodyModel::collider points to it).
    std::shared_ptr<SampleSet> samples; ///< The deformed samples it holds.
    bool stale = false;                 ///< q moved since the samples were last deformed.
};

/// Diagnostics, written by the step; read by body_modal_activity() and body_modal_accuracy().
struct ModalStats {
    // Adaptive bodies; restore keeps them.
    size_t most_active = 0;
    double truncation = 0.0;        ///< Displacement the inactive modes may miss, last substep [m].
    double max_truncation = 0.0;    ///< Its largest value [m].
    double max_lattice_error = 0.0; ///< Largest lattice error estimate of the shown modes [m].
    uint64_t active_changes = 0;
    double active_mode_substeps = 0.0; ///< Σ over substeps of the active count [-].
    // The last substep (accuracy report); cleared by restore.
    std::vector<double> last_nodal_load; ///< (3 × nodes) the nodal loads F it applied [N], body frame.
    std::vector<double> last_load;       ///< (r) the generalized forces Q it applied [N/√kg].
    bool last_has_load = false;
    // Remoulding; restore keeps them.
    int remould_count = 0;             ///< Rebuilds swapped in.
    double remould_seconds = 0.0;      ///< Wall time of the last rebuild [s].
    double remould_wait_seconds = 0.0; ///< How long the last swap waited for it [s].
};

/// A modal body's deformation (only bodies made with ModalBodyDef::enabled have one).
struct ModalBody {
    std::shared_ptr<const ModalModel> model; ///< Shared, read-only.
    std::shared_ptr<ModalSubstepMaps> maps;  ///< Shared with the model's other bodies.
    ModalState state;
    ModalLoads loads;
    DeformedSurface deformed;
    ModalStats stats;
    std::shared_future<RemouldResult> remould_job; ///< The rebuild in flight, if any (not state).
};

} // namespace supermodal
