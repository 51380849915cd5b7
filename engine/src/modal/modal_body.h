// SPDX-License-Identifier: MIT
// A modal body's components: the shared surface model and the per-body deformation (model, state,
// diagnostics and scratch).
#pragma once

#include "contact/collider.h"
#include "modal/integrator.h"
#include "modal/plasticity.h"
#include "supermodal/modal.h"

#include <memory>
#include <vector>

namespace supermodal
{

namespace modal
{
struct AccuracyCache;
}

/// Model: how a modal basis moves a collider's rest samples, shared by identical modal bodies.
struct ModalSurface {
    std::shared_ptr<const Collider> rest;    ///< Rest shape; its samples are in the body frame.
    std::shared_ptr<const ModalBasis> basis; ///< The basis the displacements come from.
    std::vector<double> sample_modes;        ///< Per rest sample, (3 × r) body-frame displacement per
                                             ///< unit amplitude, entry (sample·3 + axis)·r + k [1/√kg].
    std::shared_ptr<const modal::StressModel> stress; ///< Stress points and stress per unit amplitude.
    std::shared_ptr<modal::AccuracyCache> accuracy;   ///< Full lattice for the accuracy report, built on
                                                      ///< first use.
    std::vector<double> mode_reach; ///< (r) per mode, the largest sample displacement per unit amplitude
                                    ///< [1/√kg]: what an amplitude moves the surface by, at most.
};

/// A modal body's deformation (only bodies made with ModalBodyDef::enabled have one).
struct ModalBody {
    // Model.
    std::shared_ptr<const ModalBasis> basis;
    std::shared_ptr<const ModalSurface> surface;
    std::vector<double> omega;  ///< (r) natural angular frequencies [rad/s].
    double damping_ratio = 0.0; ///< ζ [-].
    ModalIntegrator integrator = ModalIntegrator::Exact;
    // State: hashed (q, q_dot) and snapshotted (all three).
    std::vector<double> q;          ///< (r) amplitudes [√kg·m].
    std::vector<double> q_dot;      ///< (r) their rates [√kg·m/s]; half a step behind q with
                                    ///< central difference (leapfrog).
    std::vector<double> host_force; ///< (r) generalized host forces for the next step [N/√kg]; cleared
                                    ///< after each step, like ForceAccumulator.
    std::vector<double> q_plastic;  ///< (r) plastic offsets q_p [√kg·m]: the rest shape has moved by
                                    ///< Φ q_p; the elastic part is q − q_p. Zero for elastic bodies.
    double plastic_strain = 0.0;    ///< Accumulated equivalent plastic strain [-] (hardening, limit).
    size_t active = 0; ///< Modes shown on the surface and felt by contact and constraints, the lowest
                       ///< ones (all unless adaptive); the others still step. State: hashed
                       ///< (adaptive bodies) and snapshotted.
    modal::PlasticParams plastic;    ///< Model: yield, hardening, limit.
    double adaptive_tolerance = 0.0; ///< Model: ModalBodyDef::adaptive_tolerance [m]; 0 = not adaptive.
    // Diagnostics of adaptive bodies (body_modal_activity); restore keeps them.
    size_t most_active = 0;
    double truncation = 0.0;        ///< Displacement the inactive modes may miss, last substep [m].
    double max_truncation = 0.0;    ///< Its largest value [m].
    double max_lattice_error = 0.0; ///< Largest lattice error estimate of the shown modes [m].
    /// Model: each kept mode's relative frequency change from the lattice half as fine, when the lattice
    /// was chosen for the budget (modal/auto_lattice.h) [-] (r); empty otherwise.
    std::vector<double> lattice_changes;
    uint64_t active_changes = 0;
    double active_mode_substeps = 0.0; ///< Σ over substeps of the active count [-].
    // Derived and scratch.
    std::vector<double> load; ///< (r) constraint generalized forces of this substep, held over it [N/√kg].
    std::vector<double> contact_load; ///< (r) Φᵀ of this substep's contact (nodal) loads, a kick [N/√kg].
    std::vector<double> nodal_load;   ///< (3 × lattice nodes) contact forces of this substep lumped on the
                                      ///< nodes [N], body frame; projected on the modes once per substep.
    bool has_nodal_load = false;
    std::vector<double> host_nodal_load; ///< (3 × nodes) host point loads of this step lumped likewise [N].
    bool has_host_nodal_load = false;
    // Diagnostics of the last substep (accuracy report); cleared by restore.
    std::vector<double> last_nodal_load; ///< (3 × nodes) the nodal loads F it applied [N], body frame.
    std::vector<double> last_load;       ///< (r) the generalized forces Q it applied [N/√kg].
    bool last_has_load = false;
    std::shared_ptr<Collider> collider;       ///< This body's collider (BodyModel::collider points to it),
                                              ///< its samples deformed by UpdateSurfaces.
    std::shared_ptr<SampleSet> samples;       ///< The deformed samples it holds.
    bool surface_stale = false;               ///< q moved since the samples were last deformed.
    double step_h = 0.0;                      ///< Substep the exact step maps below were made for [s].
    std::vector<modal::ModeStep> exact_steps; ///< (r) per-mode exact maps for step_h.
    double contact_h = 0.0;                   ///< Substep contact_sinc was made for [s].
    std::vector<double> contact_sinc;         ///< (r) sinc(ω_k h / 2) of modal_inverse_mass.
};

} // namespace supermodal
