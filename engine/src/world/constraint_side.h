// SPDX-License-Identifier: MIT
// One end of a constraint for one substep: the body's mass at the anchor, rigid and modal, and how an
// impulse there changes its velocities.
#pragma once

#include "modal/constraint_coupling.h"
#include "world/components.h"

#include <memory>

namespace supermodal
{

/// The modes at a side's anchor, held out of line: most sides are rigid, and the solver's passes read
/// the sides back to back (held inline, the anchor's buffers were 40% of a contact point's bytes).
/// Copies are deep; a side that stops being modal keeps its buffers for the next fill.
class ModalSide
{
  public:
    ModalSide() = default;
    ModalSide(const ModalSide& other) { *this = other; }
    ModalSide(ModalSide&&) noexcept = default;
    ModalSide& operator=(ModalSide&&) noexcept = default;
    ~ModalSide() = default;
    ModalSide& operator=(const ModalSide& other)
    {
        if (other.active())
            fill() = *other.m_anchor;
        else
            clear();
        return *this;
    }
    [[nodiscard]] bool active() const { return m_anchor != nullptr && m_anchor->active(); }
    /// The anchor to fill, with its buffers from the last fill (allocated the first time).
    ModalAnchor& fill()
    {
        if (m_anchor == nullptr)
            m_anchor = std::make_unique<ModalAnchor>();
        return *m_anchor;
    }
    /// Not modal any more (the buffers stay).
    void clear()
    {
        if (m_anchor != nullptr)
            m_anchor->body = nullptr;
    }
    /// The anchor; only while active().
    [[nodiscard]] const ModalAnchor& operator*() const { return *m_anchor; }
    [[nodiscard]] ModalAnchor& operator*() { return *m_anchor; }
    [[nodiscard]] const ModalAnchor* operator->() const { return m_anchor.get(); }
    [[nodiscard]] ModalAnchor* operator->() { return m_anchor.get(); }

  private:
    std::unique_ptr<ModalAnchor> m_anchor;
};

/// make_side() sets every field in place (a new field needs setting there too).
struct Side {
    const BodyModel* m = nullptr;
    const Pose* p = nullptr;
    Velocity* v = nullptr; ///< Null for the world.
    Vec3 point{};          ///< Anchor [m], world, with the modal displacement.
    Vec3 r{};              ///< Anchor − centre of mass [m], world.
    Mat3 inv_inertia{};    ///< World frame [1/(kg·m²)]; zero unless dynamic.
    double inv_mass = 0.0;
    ModalSide modal; ///< The modes at the anchor (modal bodies only).
};

/// Makes `out` the side of body e (null: the world, `local` a world point) at shape-frame anchor `local`,
/// reusing out's modal buffers. `with_rotation`: the modes' rotation at the anchor is needed too (welds).
void make_side(Registry& bodies, Entity e, const Vec3& local, double h, bool with_rotation, Side& out);
/// The side of body e at a contact point x [m], world, already on the (deformed) surface: as make_side,
/// with the modes evaluated at x's rest position and no rotation. `inv_inertia`: the body's world
/// inverse inertia when the caller has it (world_inv_inertia), else made here.
[[nodiscard]] Side contact_side(Registry& bodies, Entity e, const Vec3& x, double h,
                                const Mat3* inv_inertia = nullptr);
/// A body's inverse inertia in world axes at its pose [1/(kg·m²)].
[[nodiscard]] Mat3 world_inv_inertia(const BodyModel& m, const Pose& p);
/// Orientation of the material at the anchor: the body's, turned by the modal rotation there.
[[nodiscard]] Quat anchor_orientation(const Side& s);
/// Velocity of the anchor point [m/s], modes included.
[[nodiscard]] Vec3 anchor_velocity(const Side& s);
/// Velocity of the anchor point from the body's rigid motion alone [m/s].
[[nodiscard]] Vec3 rigid_anchor_velocity(const Side& s);
/// The body's spin [rad/s] (rigid only: joint limits and friction act on the parts).
[[nodiscard]] Vec3 angular_velocity(const Side& s);
/// Spin of the material at the anchor [rad/s], modes included (welds).
[[nodiscard]] Vec3 anchor_spin(const Side& s);
/// Adds an impulse J at the anchor and an angular impulse L [N·m·s] to the body and its modes.
void push(Side& s, const Vec3& impulse, const Vec3& angular_impulse);
/// An impulse J [N·s] at the anchor on the rigid body only, not its modes (contact friction).
void push_rigid(Side& s, const Vec3& impulse);
/// An angular impulse on the rigid body only (joint limits, joint friction).
void push_rigid_spin(Side& s, const Vec3& angular_impulse);
/// Whether push() and push_rigid_spin() change anything on this side: a dynamic body's velocity or a
/// modal body's loads. The world and static or kinematic bodies only feed their motion in.
[[nodiscard]] inline bool takes_impulse(const Side& s)
{
    return (s.v != nullptr && s.inv_mass != 0.0) || s.modal.active();
}
/// K = anchor velocity change of a relative to b per unit impulse [1/kg] (rigid and modal).
[[nodiscard]] Mat3 point_mass_inverse(const Side& a, const Side& b);
/// Spin change of b relative to a per unit angular impulse [1/(kg·m²)] (rigid and modal).
[[nodiscard]] Mat3 anchor_inertia_inverse(const Side& a, const Side& b);
/// Inverse of a symmetric 3×3 by cofactors; false when (nearly) singular.
bool invert(const Mat3& a, Mat3& out);

} // namespace supermodal
