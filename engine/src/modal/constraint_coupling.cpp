// SPDX-License-Identifier: MIT
#include "modal/constraint_coupling.h"

#include "modal/integrator.h"

#include <algorithm>
#include <cmath>
#include <span>

namespace supermodal
{
namespace
{

// φ_k at a rest point [1/√kg], shape frame: one slot of `out` per mode.
void mode_field(const ModalBasis& basis, const Vec3& point, std::span<Vec3> out)
{
    const size_t r = out.size();
    std::fill(out.begin(), out.end(), Vec3{});
    const LatticeWeights lw = modal_weights(basis, point);
    for (int j = 0; j < lw.count; ++j) {
        const double* node = &basis.mode_shapes[static_cast<size_t>(lw.nodes[j]) * 3 * r];
        const double w = lw.weights[j];
        for (size_t k = 0; k < r; ++k)
            out[k] += w * Vec3{node[k], node[r + k], node[2 * r + k]};
    }
}

// ψ_k = ½∇×φ_k at a rest point [rad/(√kg·m)], shape frame. Central differences a ten-thousandth of a
// cell apart (the field is a low-order polynomial inside a cell), one-sided at the lattice box.
// `work` holds the three gradients and the two fields of a difference (kept by the anchor).
void mode_rotation(const ModalBasis& basis, const Vec3& point, std::vector<Vec3>& work,
                   std::vector<Vec3>& out)
{
    const size_t r = static_cast<size_t>(basis.mode_count);
    work.assign(5 * r, Vec3{});
    const std::span<Vec3> all(work);
    const std::span<Vec3> grad[3] = {all.subspan(0, r), all.subspan(r, r),
                                     all.subspan(2 * r, r)}; // ∂φ_k/∂x_j
    const std::span<Vec3> lo_f = all.subspan(3 * r, r), hi_f = all.subspan(4 * r, r);
    for (int j = 0; j < 3; ++j) {
        const double box_lo = basis.lattice_min[j];
        const double box_hi = box_lo + basis.cells[j] * basis.cell_size[j];
        const double delta = 1e-4 * basis.cell_size[j];
        Vec3 lo = point, hi = point;
        const double c = std::clamp(point[j], box_lo, box_hi);
        lo[j] = std::max(box_lo, c - delta);
        hi[j] = std::min(box_hi, c + delta);
        mode_field(basis, lo, lo_f);
        mode_field(basis, hi, hi_f);
        const double span = hi[j] - lo[j];
        if (span > 0.0)
            for (size_t k = 0; k < r; ++k)
                grad[j][k] = (hi_f[k] - lo_f[k]) / span;
    }
    out.assign(r, Vec3{});
    for (size_t k = 0; k < r; ++k)
        out[k] =
            0.5 * Vec3{grad[1][k].z - grad[2][k].y, grad[2][k].x - grad[0][k].z, grad[0][k].y - grad[1][k].x};
}

// Σ (gain_k/h) v_k v_kᵀ.
Mat3 sum_outer(const std::vector<Vec3>& v, const std::vector<double>& gain, double h)
{
    Mat3 m;
    for (size_t k = 0; k < v.size(); ++k) {
        const double weight = gain[k] / h;
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j)
                m.m[i][j] += weight * v[k][i] * v[k][j];
    }
    return m;
}

// Empties an anchor but keeps its buffers, so anchors made every substep allocate nothing once warm.
void clear_anchor(ModalAnchor& a)
{
    a.body = nullptr;
    a.phi.clear();
    a.psi.clear();
    a.drift.clear();
    a.gain.clear();
    a.h = 0.0;
    a.displacement = Vec3{};
    a.rotation = Vec3{};
}

// The map ModalUpdate will use for mode k over h (update_modal_bodies): central difference below its
// stability limit when asked for, the exact step otherwise.
modal::ModeStep mode_map(const ModalBody& b, size_t k, double h)
{
    const ModalModel& m = *b.model;
    const double w = m.omega[k];
    if (m.integrator == ModalIntegrator::CentralDifference && w * h < modal::k_central_difference_limit) {
        // v₁ = (v(1 − c) + h(F − ω²q))/(1 + c), q₁ = q + h v₁ with c = ζωh.
        const double c = m.damping_ratio * w * h, d = 1.0 / (1.0 + c);
        modal::ModeStep s;
        s.a21 = -h * w * w * d;
        s.a22 = (1.0 - c) * d;
        s.b2 = h * d;
        s.a11 = 1.0 + h * s.a21;
        s.a12 = h * s.a22;
        s.b1 = h * s.b2;
        return s;
    }
    if (b.maps->h == h && k < b.maps->exact.size())
        return b.maps->exact[k];
    return modal::exact_mode_step(w, m.damping_ratio, h);
}

} // namespace

bool modal_anchor(ModalBody* b, const Quat& rot, const Vec3& local, double h, bool with_rotation,
                  ModalAnchor& out)
{
    clear_anchor(out);
    if (b == nullptr || !is_finite(local) || !(h > 0.0))
        return false;
    out.h = h;
    const ModalBasis& basis = *b->model->basis;
    const ModalState& st = b->state;
    out.phi.assign(static_cast<size_t>(basis.mode_count), Vec3{});
    mode_field(basis, local, out.phi);
    if (with_rotation)
        mode_rotation(basis, local, out.work, out.psi);
    const size_t r = out.phi.size();
    out.drift.resize(r);
    out.gain.resize(r);
    for (size_t k = 0; k < r; ++k) {
        out.phi[k] = rotate(rot, out.phi[k]);
        if (with_rotation)
            out.psi[k] = rotate(rot, out.psi[k]);
        if (k >= st.active)
            continue; // an adaptive body's hidden mode: not felt, but its load still counts (push)
        out.displacement += st.q[k] * out.phi[k];
        if (with_rotation)
            out.rotation += st.q[k] * out.psi[k];
        const modal::ModeStep s = mode_map(*b, k, h);
        // The host loads (apply_force) are known now; contact loads join in the ModalUpdate stage. The
        // modes spring back to the plastically moved rest shape, q_p (as update_modal_bodies steps them):
        // measured from q = 0 instead, a moulded body's anchors seemed to move at the spring-back speed,
        // and contact rows pushed against that phantom motion (a dented clay block slid and spun).
        const double elastic = st.q[k] - (k < st.q_plastic.size() ? st.q_plastic[k] : 0.0);
        out.drift[k] = ((s.a11 - 1.0) * elastic + s.a12 * st.q_dot[k] + s.b1 * st.host_force[k]) / h;
        out.gain[k] = s.b1 / h;
    }
    if (!is_finite(out.displacement) || !is_finite(out.rotation)) {
        clear_anchor(out);
        return false;
    }
    out.body = b;
    return true;
}

Vec3 modal_anchor_velocity(const ModalAnchor& a)
{
    Vec3 v{};
    for (size_t k = 0; k < a.phi.size(); ++k)
        v += (a.drift[k] + a.gain[k] * a.body->loads.load[k]) * a.phi[k];
    return v;
}

Vec3 modal_anchor_spin(const ModalAnchor& a)
{
    Vec3 w{};
    for (size_t k = 0; k < a.psi.size(); ++k)
        w += (a.drift[k] + a.gain[k] * a.body->loads.load[k]) * a.psi[k];
    return w;
}

Mat3 modal_anchor_inverse_mass(const ModalAnchor& a)
{
    return sum_outer(a.phi, a.gain, a.h);
}

Mat3 modal_anchor_inverse_inertia(const ModalAnchor& a)
{
    return sum_outer(a.psi, a.gain, a.h);
}

void modal_anchor_push(ModalAnchor& a, const Vec3& impulse, const Vec3& angular_impulse)
{
    if (a.body == nullptr)
        return;
    for (size_t k = 0; k < a.phi.size(); ++k)
        a.body->loads.load[k] += dot(a.phi[k], impulse) / a.h;
    for (size_t k = 0; k < a.psi.size(); ++k)
        a.body->loads.load[k] += dot(a.psi[k], angular_impulse) / a.h;
}

} // namespace supermodal
