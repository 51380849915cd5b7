// SPDX-License-Identifier: MIT
// Modal bases: the lowest free vibration modes of a body, computed once from a finite-element lattice
// over its shape (Williams & Pentland 1992; docs/modal.md). A basis is model data:
// built once, immutable, shared by every body with the same shape, material and lattice.
//
// Frames and units. Everything lives in the shape frame (Barr: z is the polar axis), origin at the
// shape's centre, in SI units. A body's deformation is u(p) = Σ_k φ_k(p) q_k [m], where the mode shapes
// φ_k are mass-normalised (Φᵀ M Φ = I with M the lattice's consistent mass [kg]), so φ has units
// 1/√kg and the modal amplitudes q have units √kg·m; each mode obeys q̈ + 2ζω q̇ + ω² q = φᵀ f.
#pragma once

#include "supermodal/api.h"
#include "supermodal/body.h"
#include "supermodal/entity.h"
#include "supermodal/math.h"
#include "supermodal/result.h"
#include "supermodal/shape.h"

#include <array>
#include <cstdint>
#include <map>
#include <memory>
#include <mutex>
#include <span>
#include <string>
#include <vector>

namespace supermodal
{

/// Largest mode_count a ModalBasisDef may ask for.
inline constexpr int k_max_modes = 256;
/// mode_count asking for every elastic mode of the lattice (3n − 6 for n nodes): the full lattice,
/// nothing truncated (scene "dynamics": {"type": "full"}).
inline constexpr int k_all_modes = 0;
/// Most degrees of freedom (3 × lattice nodes) a k_all_modes basis may have: it is solved dense, O(n³)
/// (1536 dofs: about 2 s), and every mode is stepped.
inline constexpr int k_max_full_dofs = 1536;
/// Largest cell count per lattice axis.
inline constexpr int k_max_lattice_cells = 128;
/// Most degrees of freedom a lattice may have, counted over its whole box (3 × (corners + edge
/// midpoints) for 20-node cells), so a request is refused before anything is built: the largest
/// lattices within it took 44–107 s and 1.2 GB to build on one core (docs/modal.md).
inline constexpr int k_max_lattice_dofs = 100000;

/// The hexahedral lattice over the shape's bounding box.
struct LatticeDef {
    std::array<int, 3> cells{};    ///< Cells along x, y, z; 0 = the default lattice (docs/modal.md,
                                   ///< "Default lattice": 16 along the longest side, at least 3 through
                                   ///< the others, at most 3000 dofs; 16 / 2 / 512 cells for order 1).
    int element_order = 2;         ///< 1: 8-node trilinear (locks in bending); 2: 20-node serendipity.
    int cut_cell_subdivisions = 4; ///< Sub-cells per axis for the quadrature of cells the surface cuts
                                   ///< (2×2×2 Gauss points each); higher = truer boundary, slower build.
};

/// Which eigensolver a build uses.
enum class ModalSolver : uint8_t {
    Auto,   ///< Dense up to k_dense_dof_limit degrees of freedom, sparse above.
    Dense,  ///< Eigen's dense generalized solver: every eigenpair; O(n³) time, O(n²) memory.
    Sparse, ///< Shift-invert block Krylov iteration on a supernodal sparse Cholesky (Spectra's Lanczos with a
            ///< confirmation run where a run of equal frequencies is as wide as the block): the lowest modes.
};
/// Auto switches to the sparse solver above this many degrees of freedom.
inline constexpr int k_dense_dof_limit = 300;

/// How to build a modal basis. Start from default_modal_basis_def() and change what differs.
struct ModalBasisDef {
    ShapeDef shape{};        ///< Superquadric (tapered/bent allowed) or hyperquadric; not Plane.
    double density = 1000.0; ///< ρ [kg/m³], > 0.
    double young = 1e7;      ///< Young's modulus E [Pa], > 0.
    double poisson = 0.3;    ///< Poisson's ratio ν [-], in (−1, 0.5).
    LatticeDef lattice{};    ///< Lattice resolution and element type.
    int mode_count = 12;     ///< Elastic modes kept, r ∈ [1, k_max_modes], or k_all_modes (every
                             ///< elastic mode; dense; at most k_max_full_dofs); rigid modes never. Where
                             ///< the cut splits a run of equal frequencies the basis keeps the whole run
                             ///< (up to k_max_modes), except with rest_offsets: then exactly this many.
    ModalSolver solver = ModalSolver::Auto;
    /// A moulded rest shape: per node of the lattice the def makes without them (node order of
    /// ModalBasis::node_positions), how far the rest shape has moved [m], shape frame. The same cells,
    /// quadrature points and nodes are integrated over their moved places (the material carried along);
    /// ModalBasis::node_positions then holds the moved nodes, while the lattice box and modal_weights
    /// stay those of the unmoulded shape (points are named by where they were). Empty: the shape itself.
    std::vector<Vec3> rest_offsets;
};

/// The documented starting point: a sphere of 1 m diameter, soft (E = 10 MPa, ν = 0.3, ρ = 1000 kg/m³),
/// 12 modes, 20-node cells on an automatic lattice (4³).
[[nodiscard]] SM_API ModalBasisDef default_modal_basis_def();
/// Checks ranges (see the field comments) and the shape.
[[nodiscard]] SM_API Status validate(const ModalBasisDef& def);

/// A guess at what a mode looks like, from its displacement field about the body's longest axis
/// (bodies without one, longest side under 1.5 × the next, get Other).
enum class ModeKind : uint8_t {
    Bend,    ///< Cross-sections translate sideways (beam bending).
    Torsion, ///< Cross-sections rotate about the long axis.
    Axial,   ///< Motion along the long axis (stretching).
    Other,   ///< None of the above dominates (plate, breathing, mixed modes; compact bodies).
};
/// "bend", "torsion", "axial" or "other".
[[nodiscard]] SM_API const char* mode_kind_name(ModeKind kind);

/// How the basis came out: checks and costs. Filled by build_modal_basis.
struct ModalDiagnostics {
    std::array<double, 6> rigid_eigenvalues{}; ///< ω² of the six rigid-body modes before they were
                                               ///< dropped [rad²/s²]; ~0 for a free body.
    double first_elastic_eigenvalue = 0.0;     ///< ω₁² [rad²/s²].
    double rigid_ratio = 0.0;                  ///< max |rigid eigenvalue| / first elastic eigenvalue [-].
    double mass_orthonormality_error = 0.0;    ///< max |(Φᵀ M Φ − I)_ij| over the kept modes [-].
    bool splits_degenerate_cluster = false;    ///< Mode r and r+1 share a frequency (within 1e-6): which
                                               ///< of the pair is kept is arbitrary (only with
                                               ///< rest_offsets, which keep the count exact).
    bool sparse_solver = false;                ///< The sparse (sparse Cholesky) path ran.
    int solver_rounds = 0;         ///< Sparse path: runs that added modes (more than 1 = a Lanczos
                                   ///< confirmation run found missed copies of repeated frequencies).
    bool inertia_checked = false;  ///< Sparse path: repeated frequencies cannot have been missed:
                                   ///< every run of equal ones is narrower than the block iteration's
                                   ///< block, or (Lanczos) a confirmation run with every found mode
                                   ///< deflated found no further mode below the cut.
    int dof_count = 0;             ///< Degrees of freedom of the lattice (3 per node).
    int kept_cell_count = 0;       ///< Cells with material in them.
    int cut_cell_count = 0;        ///< Of those, cells the surface cuts (sub-cell quadrature).
    int aggregated_cell_count = 0; ///< Slivers (cut cells too thinly sampled to integrate alone)
                                   ///< merged into a neighbour whose field extends over them.
    int dropped_sliver_count = 0;  ///< Slivers with no neighbour to merge into: material lost.
    std::vector<double> mode_residuals; ///< (r) ‖Kφ − ω²Mφ‖ / ‖Kφ‖ of each kept mode on the lattice [-].
    double assembly_seconds = 0.0; ///< Lattice, quadrature and sparse assembly [s].
    double eigen_seconds = 0.0;    ///< Eigensolver, orthonormalisation, classification [s].
};

/// The lowest elastic modes of a body and the lattice they live on. Plain data, shape frame, SI.
struct ModalBasis {
    std::array<int, 3> cells{};       ///< Lattice cells per axis actually used.
    int element_order = 2;            ///< 1: 8-node cells, 2: 20-node cells.
    Vec3 lattice_min{};               ///< Low corner of the lattice box [m].
    Vec3 cell_size{};                 ///< Edge lengths of one cell [m].
    std::vector<Vec3> node_positions; ///< Rest positions of the lattice nodes that carry material [m].
    std::vector<int32_t> cell_nodes;  ///< Per cell (x fastest, then y, z): nodes_per_cell indices
                                      ///< into node_positions (8 or 20, the local order of
                                      ///< engine/src/modal/lattice.h); −1 for a cell without nodes
                                      ///< (empty, or a sliver merged into its proxy).
    std::vector<int32_t> cell_proxy;  ///< Per cell: itself, or for a cell without nodes the nearest cell
                                      ///< with them, whose field modal_displacement extends to it.
    double density = 0.0, young = 0.0, poisson = 0.0; ///< The material it was built for (SI).
    double mass = 0.0;                  ///< Mass of the lattice model, Σ over its consistent mass [kg].
    int mode_count = 0;                 ///< r, the elastic modes kept (more than asked where a run of
                                        ///< equal frequencies was kept whole).
    std::vector<double> frequencies_hz; ///< (r) natural frequencies ω/2π, ascending [Hz].
    std::vector<ModeKind> kinds;        ///< (r) guess per mode.
    /// (node_count × 3 × r) mass-normalised mode shapes [1/√kg]: entry (node·3 + axis)·r + k.
    std::vector<double> mode_shapes;
    ModalDiagnostics diagnostics;
};

/// Nodes per cell of an element order: 8 or 20.
[[nodiscard]] SM_API int lattice_nodes_per_cell(int element_order);

/// Builds the lattice, integrates stiffness and mass over the body, solves K φ = ω² M φ, drops the six
/// rigid modes and keeps the lowest mode_count elastic ones, mass-normalised. Errors: invalid def, a
/// lattice with fewer elastic degrees of freedom than modes, more than six zero-frequency modes (the
/// material falls apart into pieces on this lattice: refine it), or a solver that does not converge.
[[nodiscard]] SM_API Result<ModalBasis> build_modal_basis(const ModalBasisDef& def);

/// Where a point sits in a basis's lattice: the nodes whose shape functions reach it and their values.
struct LatticeWeights {
    std::array<int32_t, 20> nodes{};  ///< Indices into ModalBasis::node_positions.
    std::array<double, 20> weights{}; ///< Shape-function values there [-]; they sum to 1.
    int count = 0;                    ///< 8 or 20.
};
/// Shape-function weights of a rest-shape point [m] (shape frame). In a cell without nodes the field of
/// its proxy cell is extended, at most one cell beyond it; points outside the lattice box are clamped
/// onto it. Compute once per surface sample; then modal_displacement costs 3·count·r multiply-adds.
[[nodiscard]] SM_API LatticeWeights modal_weights(const ModalBasis& basis, const Vec3& point_shape);
/// Displacement [m], shape frame, of a point with precomputed weights, for modal amplitudes q [√kg·m].
/// q may hold fewer than mode_count amplitudes: the missing ones count as zero.
[[nodiscard]] SM_API Vec3 modal_displacement(const ModalBasis& basis, const LatticeWeights& weights,
                                             std::span<const double> q);
/// Displacement [m], shape frame, of a rest-shape point [m] for modal amplitudes q [√kg·m].
[[nodiscard]] SM_API Vec3 modal_displacement(const ModalBasis& basis, const Vec3& point_shape,
                                             std::span<const double> q);
/// Displacement [m] of every lattice node for amplitudes q (fewer than mode_count: the rest are zero),
/// into out (resized to the node count): 3·r multiply-adds per node, once per frame. Then each of many
/// points costs 3·count multiply-adds (interpolate_nodal) instead of 3·count·r: how a render mesh of
/// 10k vertices deforms (docs/modal.md "Deforming a render mesh").
SM_API void modal_nodal_displacements(const ModalBasis& basis, std::span<const double> q,
                                      std::vector<Vec3>& out);
/// Displacement [m] of a point with precomputed weights from modal_nodal_displacements' output.
[[nodiscard]] SM_API Vec3 interpolate_nodal(const LatticeWeights& weights, std::span<const Vec3> nodal);

/// Shares bases between identical bodies: keyed by every field of the def (shape, material, lattice,
/// mode count, solver), compared exactly. Thread-safe; a build runs outside the lock, so two threads
/// asking for the same new basis may both build it (the first result is kept).
class SM_API ModalBasisCache
{
  public:
    /// The cached basis for def, building it on first use. Failed builds are not cached.
    [[nodiscard]] Result<std::shared_ptr<const ModalBasis>> get_or_build(const ModalBasisDef& def);
    [[nodiscard]] int size() const;
    void clear();

  private:
    mutable std::mutex m_mutex;
    std::map<std::string, std::shared_ptr<const ModalBasis>> m_entries;
};

// ---- Modal bodies in a world (BodyDef::modal) ----------------------------------------------------------

class World;

/// The basis a modal BodyDef will use in `world`: built now, or found in the world's cache. create_body
/// calls the same; call this first to learn why a build fails (too many modes for the lattice, a
/// lattice too coarse to hold the body together). Errors for rigid or invalid defs too.
[[nodiscard]] SM_API Result<std::shared_ptr<const ModalBasis>> modal_basis_for(World& world,
                                                                               const BodyDef& def);

/// A modal body's basis, or null for a rigid body.
[[nodiscard]] SM_API const ModalBasis* body_modal_basis(const World& world, Entity body);

/// Modal amplitudes and their rates; empty for a rigid body.
struct BodyModalState {
    std::vector<double> amplitudes; ///< (r) q [√kg·m], whole shape (the plastic offsets q_p included).
    std::vector<double> velocities; ///< (r) q̇ [√kg·m/s]; with central difference, half a step behind q.
};
[[nodiscard]] SM_API BodyModalState body_modal_state(const World& world, Entity body);
/// Sets a modal body's amplitudes and rates (both of its mode count, finite); its surface follows.
SM_API Status set_body_modal_state(World& world, Entity body, std::span<const double> amplitudes,
                                   std::span<const double> velocities);
/// How a modal body uses its modes. Adaptive bodies (ModalBodyDef::adaptive_tolerance > 0, scene
/// "dynamics": "auto") step only the lowest ones their loads need; the others step all of them.
struct BodyModalActivity {
    bool adaptive = false;
    int active_modes = 0;      ///< Modes stepped now [-]; 0: the body moves as a rigid one.
    int most_active_modes = 0; ///< The most stepped at once since the body was made [-].
    /// Surface displacement the modes left out may reach, last substep [m] (an upper estimate: each mode's
    /// free amplitude or twice its static response, summed; adaptive bodies only).
    double truncation_estimate = 0.0;
    double max_truncation_estimate = 0.0; ///< Its largest value since the body was made [m].
    uint64_t active_count_changes = 0;    ///< Times the active count changed [-].
    double active_mode_substeps = 0.0;    ///< Σ over substeps of the active count [-] (adaptive bodies):
                                          ///< the modal work done, in mode-substeps.
    /// Contact samples chosen for the budget (adaptive bodies whose world leaves the spacing automatic;
    /// else 0 and the fields below are zero): count, requested spacing [m], and the measured sampling
    /// gap [m] (how much deeper the body may sink between samples), with whether it met its share.
    int contact_samples = 0;
    double sample_spacing = 0.0;
    double sampling_gap = 0.0;
    bool sampling_gap_met = false;
    /// The lattice an adaptive body without a "lattice" was given (docs/modal.md "Lattice for the
    /// budget"): its cells, the largest relative change of its kept modes' frequencies from the lattice
    /// half as fine (−1: not chosen, or nothing coarser to compare), whether that is within 2%, and the
    /// largest displacement error it may have caused so far: Σ over the shown modes of 2 × (2 × the
    /// mode's change, its frequency error estimate) × the displacement it may reach [m].
    std::array<int, 3> lattice_cells{};
    double lattice_frequency_change = -1.0;
    bool lattice_converged = false;
    double lattice_error_estimate = 0.0;
};
/// Zeros for a rigid body.
[[nodiscard]] SM_API BodyModalActivity body_modal_activity(const World& world, Entity body);
/// Elastic energy plus kinetic energy of the modes, ½ Σ (q̇² + ω² (q − q_p)²) [J]; 0 for a rigid body.
[[nodiscard]] SM_API double body_modal_energy(const World& world, Entity body);
/// The plastic part of a modal body's state (BodyModalState's companion; zero for elastic bodies).
struct BodyPlasticState {
    std::vector<double> offsets; ///< (r) q_p [√kg·m]: the rest shape has moved by Σ φ_k q_p,k.
    double plastic_strain = 0.0; ///< Accumulated equivalent plastic strain at the yielding points [-].
    double yield_stress = 0.0;   ///< Current yield σ_y + H ε_p [Pa]; ∞ for an elastic body.
};
[[nodiscard]] SM_API BodyPlasticState body_plastic_state(const World& world, Entity body);

/// How far a modal body's reduced solution is from its full lattice, for the loads of its last substep
/// (docs/modal.md, "Accuracy report"). All in the body frame.
struct ModalAccuracy {
    /// ‖R‖ / max(‖F‖, ‖K u‖) [-], norms ‖x‖ = √(xᵀ M⁻¹ x), where R = M ü + C u̇ + K u − F is the full
    /// lattice's residual on the reduced solution (u = Φ(q − q_p), ü from the modal equation plus the
    /// rigid acceleration, C the modal damping) and F the last substep's nodal loads. 0 when all modes
    /// are kept (to the eigensolver's accuracy); near 1 when the modes cannot represent the load.
    double residual = 0.0;
    double residual_norm = 0.0;    ///< ‖R‖ [N/√kg].
    double load_norm = 0.0;        ///< Euclidean norm of F over the nodes [N].
    double static_energy = 0.0;    ///< ½ u_sᵀ K u_s of the full lattice's static (inertia-relieved)
                                   ///< response u_s to F [J].
    double truncated_energy = 0.0; ///< The part of it the dropped modes carry, ½ dᵀ K d with
                                   ///< d = u_s − Φ Ω⁻² Φᵀ F [J] (= Σ_(k > r) (φ_kᵀF)² / 2ω_k²).
    double truncated_fraction = 0.0; ///< truncated_energy / static_energy [-].
};
/// The accuracy report of a modal body (zeros for a rigid body, or one without loads and deformation).
/// The first call for a basis assembles its lattice and factors K and M (about as long as the basis's
/// assembly plus two sparse factorisations); later calls cost a few sparse products and solves.
[[nodiscard]] SM_API ModalAccuracy body_modal_accuracy(const World& world, Entity body);

/// Stress of a modal body's elastic deformation (q − q_p).
struct BodyStress {
    double max_von_mises = 0.0; ///< Largest von Mises stress over the body's stress points [Pa].
    Vec3 where{};               ///< Its rest position [m], shape frame.
};
/// Largest von Mises stress over the stress points (per lattice cell, the 27 points ξ ∈ {−1, 0, 1}³
/// that lie in the body; docs/modal.md "Stress and plasticity"). Zero for a rigid body.
[[nodiscard]] SM_API BodyStress body_max_stress(const World& world, Entity body);
/// Stress tensor [Pa], shape frame, at a rest point [m] of a modal body's elastic deformation, Voigt order
/// (xx, yy, zz, yz, xz, xy); zeros for a rigid body.
[[nodiscard]] SM_API std::array<double, 6> body_stress_at(const World& world, Entity body,
                                                          const Vec3& point_shape);
/// von Mises equivalent of a Voigt stress [Pa].
[[nodiscard]] SM_API double von_mises_stress(const std::array<double, 6>& voigt);

/// Inside-outside test of a body's current (deformed) shape at a world point.
struct BodyPointTest {
    bool inside = false;
    double depth = 0.0; ///< Approximate distance to the surface [m] (measure / |gradient|), if inside.
    Vec3 normal{};      ///< Unit outward normal of the deformed surface, world frame, if inside.
    Vec3 rest_point{};  ///< The rest point [m] (shape frame) the point came from (modal bodies).
};
/// For a modal body the point is mapped back to the rest shape by Newton's method on the deformation
/// field (X + u(X) = p), tested there, and the rest gradient carried forward by F⁻ᵀ (F = I + ∇u); where
/// Newton fails (a folded field) the point counts as outside. Rigid bodies: the shape's own test.
/// (Contact does not use this yet: docs/modal.md "Deformed surfaces".)
[[nodiscard]] SM_API BodyPointTest body_point_test(const World& world, Entity body, const Vec3& world_point);

/// A plastic body's remoulding (docs/modal.md "Remoulding"); zeros for other bodies.
struct BodyRemould {
    double threshold = 0.0;     ///< ModalBodyDef::remould_threshold [-].
    double rest_change = 0.0;   ///< Largest rest offset of a lattice node since the last build, over the
                                ///< lattice's largest side [-]: a rebuild is asked for past the threshold.
    int rebuilds = 0;           ///< Rebuilt bases swapped in [-].
    uint64_t pending_step = 0;  ///< Step count at whose boundary the rebuild asked for takes over; 0: none.
    bool failed = false;        ///< A rebuild failed (the moulded shape turned a cell inside out): no more.
    double build_seconds = 0.0; ///< Wall time of the last rebuild (build and projection) [s].
    double wait_seconds = 0.0;  ///< How long the step waited for it at the swap [s].
    std::vector<Vec3> rest_offsets; ///< Per lattice node, how far the rest shape of the current modes has
                                    ///< moved [m] (ModalBasisDef::rest_offsets); empty: never rebuilt.
};
[[nodiscard]] SM_API BodyRemould body_remould(const World& world, Entity body);

/// Per lattice node, the displacement the static correction adds to the modes' (ModalBodyDef::
/// static_correction) [m], body frame, node order of ModalBasis::node_positions; empty when it is off.
[[nodiscard]] SM_API std::vector<Vec3> body_static_correction(const World& world, Entity body);

/// Where the material point with rest position `point_shape` [m] (shape frame, as BodyDef::shape)
/// is now [m], world frame: the rigid pose plus the modal displacement and its static correction (for
/// rigid bodies, just the pose).
[[nodiscard]] SM_API Vec3 body_deformed_point(const World& world, Entity body, const Vec3& point_shape);

} // namespace supermodal
