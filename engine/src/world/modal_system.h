// SPDX-License-Identifier: MIT
// Modal bodies inside a world: creation, generalized forces, the ModalUpdate and UpdateSurfaces stages.
// Co-rotational: the rigid motion stays in the body (Pose, Velocity), the modes deform the body frame,
// and loads are rotated into it before they are projected on the modes.
#pragma once

#include "contact/broadphase.h"
#include "contact/narrowphase.h"
#include "modal/auto_lattice.h"
#include "supermodal/world.h"
#include "world/components.h"

#include <memory>
#include <span>
#include <vector>

namespace supermodal
{

struct StepContext;
class Parallel;

/// The model of a modal surface: `rest` the rest collider (its samples where the rest shape is),
/// `material` the unmoulded one whose sample positions name the material points (the same collider
/// unless remoulded), rest_offsets the moulded shape's node offsets [m] (empty: none).
[[nodiscard]] std::shared_ptr<const ModalSurface> make_modal_surface(std::shared_ptr<const Collider> rest,
                                                                     std::shared_ptr<const ModalBasis> basis,
                                                                     std::shared_ptr<const Collider> material,
                                                                     std::vector<Vec3> rest_offsets);
/// The basis definition a modal BodyDef asks for.
[[nodiscard]] ModalBasisDef modal_basis_def(const BodyDef& def);
/// The world's basis for a modal BodyDef, built on first use and cached. An auto body (adaptive
/// tolerance > 0) with an automatic lattice gets the lattice modal::choose_lattice() settles on; for
/// the others frequency_change stays −1.
[[nodiscard]] Result<modal::LatticeChoice> find_or_build_modal_basis(World::Impl& w, const BodyDef& def);
/// Gives body e (already holding its BodyModel, collider and mass) a ModalBody at rest, sharing the world's
/// ModalModel for identical bodies (same basis, rest collider and ModalBodyDef).
void attach_modal_body(World::Impl& w, Entity e, const modal::LatticeChoice& choice, const BodyDef& def);

/// The deformed inside-outside test of modal body e for the narrowphase (ContactDef::deformed_inside_test):
/// empty (the rest shape) for a rigid body, a remoulded one, or one whose surface shows no mode.
[[nodiscard]] DeformedTest modal_deformed_test(const Registry& reg, Entity e);

/// Sets how many of an adaptive body's lowest modes its surface shows (the others keep stepping, hidden).
void set_active_modes(ModalBody& b, size_t active);

/// Adds a point load f [N] at world point x [m] to e's contact generalized forces of this substep:
/// Q += φ(x_local)ᵀ Rᵀ f. Does nothing for rigid bodies.
void modal_add_point_load(Registry& reg, Entity e, const Vec3& world_point, const Vec3& world_force);
/// A force the soft solver's rows already put on e's modes (through ModalLoads::load), lumped on the
/// lattice nodes for the static correction and the accuracy report only.
void modal_add_solved_load(Registry& reg, Entity e, const Vec3& world_point, const Vec3& world_force);
/// Notes a contact point's normal force × its depth [J] on e (static correction: the spring's compliance).
void modal_add_spring_work(Registry& reg, Entity e, double work);
/// The same as modal_add_point_load into the host forces held for the next step (apply_force).
void modal_add_host_load(Registry& reg, Entity e, const Vec3& world_point, const Vec3& world_force);
/// Makes the substep maps (exact step maps, sinc(ω_k h / 2)) of every modal body's model for substep h [s],
/// unless made for h already. On the stepping thread, before contact or the modal update read them in
/// parallel (the maps are shared by the bodies of a model).
void prepare_modal_substep(Registry& reg, double h);
/// What the modes add to a body's inverse mass at a world point for a push along unit world direction d
/// held over the substep h [s] of the last prepare_modal_substep(): Σ_k (φ_k(x_local) · Rᵀd)² · sinc²(ω_k h /
/// 2) [1/kg] (for d = 0 the bound over directions, |φ_k|² in place of (φ_k · Rᵀd)²). The sinc² factor is how
/// far mode k moves under a force held for h, relative to a free mass (1 for ω_k h → 0, 4/(ω_k h)² for a
/// stiff mode, which only deflects statically). Contact springs are tuned on the inverse mass: without this a
/// soft body's light surface makes the explicit contact coupling unstable (measured: a soft sphere bounced
/// above its drop height). 0 for rigid bodies. Reads only (any thread may call it, each with its own
/// scratch_phi); the sinc² factors come from prepare_modal_substep().
[[nodiscard]] double modal_inverse_mass(const Registry& reg, Entity e, const Vec3& world_point, const Vec3& d,
                                        std::vector<double>& scratch_phi);
/// An impulse J [N·s] at a world point changes the rates at once: q̇ += φ(x_local)ᵀ Rᵀ J.
void modal_add_point_impulse(Registry& reg, Entity e, const Vec3& world_point, const Vec3& impulse);

/// Buffers of the stages below, kept between substeps.
struct ModalScratch {
    std::vector<uint8_t> flags;    ///< update_modal_bodies: per modal body, what its step reported.
    std::vector<ModalBody*> stale; ///< update_modal_surfaces: bodies whose samples are to move.
};

/// ModalUpdate stage: steps every modal body's amplitudes over ctx.h under this substep's loads and the
/// host loads, then clears the substep's loads.
void update_modal_bodies(const StepContext& ctx, const Parallel& par, Registry& reg, ModalScratch& scratch,
                         StepWarnings& io_warnings);
/// UpdateSurfaces stage: moves the contact samples of the modal bodies in `pairs` (the only ones the
/// narrowphase will read) by their current amplitudes, if these moved since. Others stay stale until they
/// join a pair: call it again after the broadphase.
void update_modal_surfaces(const Parallel& par, Registry& reg, std::span<const BodyPair> pairs,
                           ModalScratch& scratch);
/// Moves one modal body's samples (after creation, set_body_modal_state, restore).
void update_modal_surface(ModalBody& body);
/// Clears host generalized forces once a step has used them.
void clear_modal_forces(Registry& reg);

} // namespace supermodal
