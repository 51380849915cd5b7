// SPDX-License-Identifier: MIT
#include "world/remould.h"

#include "modal/accuracy.h"
#include "world/modal_system.h"

#include <Eigen/Dense>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <numbers>

namespace supermodal
{
namespace
{

using Clock = std::chrono::steady_clock;
using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

Eigen::Map<const RowMajor> modes_of(const ModalBasis& b)
{
    return {b.mode_shapes.data(), static_cast<Eigen::Index>(b.node_positions.size() * 3), b.mode_count};
}

double lattice_extent(const ModalBasis& b)
{
    double extent = 0.0;
    for (int d = 0; d < 3; ++d)
        extent = std::max(extent, b.cells[d] * b.cell_size[d]);
    return extent;
}

// The moulded rest shape a rebuild asked for with plastic offsets q_p is built for: the model's own
// offsets plus Φ q_p at every node.
std::vector<Vec3> moulded_offsets(const ModalBody& b, std::span<const double> q_plastic)
{
    std::vector<Vec3> out;
    modal_nodal_displacements(*b.model->basis, q_plastic, out);
    const std::vector<Vec3>& before = b.model->surface->rest_offsets;
    for (size_t n = 0; n < before.size() && n < out.size(); ++n)
        out[n] += before[n];
    return out;
}

// The def of the body's unmoulded basis with the given rest offsets.
ModalBasisDef moulded_def(const ModalBody& b, std::vector<Vec3> offsets)
{
    ModalBasisDef def = b.model->surface->accuracy->def;
    def.rest_offsets = std::move(offsets);
    return def;
}

// The build and the least-squares map P = (Φ'ᵀΦ')⁻¹ Φ'ᵀ Φ over the lattice nodes (the same nodes in both
// bases: remoulding carries the lattice's material, it does not re-cut it).
RemouldResult build_remould(const std::shared_ptr<ModalBasisCache>& cache, const ModalBasisDef& def,
                            const std::shared_ptr<const ModalBasis>& old)
{
    const Clock::time_point start = Clock::now();
    RemouldResult out;
    out.rest_offsets = def.rest_offsets;
    Result<std::shared_ptr<const ModalBasis>> built = cache->get_or_build(def);
    if (!built) {
        out.error = built.error().where + ": " + built.error().what;
        return out;
    }
    out.basis = *built;
    const Eigen::Map<const RowMajor> phi_new = modes_of(*out.basis), phi_old = modes_of(*old);
    const Eigen::MatrixXd gram = phi_new.transpose() * phi_new;
    const RowMajor p = gram.ldlt().solve(phi_new.transpose() * phi_old);
    out.projection.assign(p.data(), p.data() + p.size());
    out.seconds = std::chrono::duration<double>(Clock::now() - start).count();
    return out;
}

void launch(World::Impl& w, ModalBody& b)
{
    const ModalBasisDef def = moulded_def(b, moulded_offsets(b, b.state.remould_q_plastic));
    b.remould_job = std::async(std::launch::async, [cache = w.modal_bases, def, old = b.model->basis] {
                        return build_remould(cache, def, old);
                    }).share();
}

// The body's model for a rebuilt basis: the old one's parameters, a surface whose rest samples moved
// with the rest shape, its own substep maps.
void install_model(ModalBody& b, std::shared_ptr<const ModalBasis> basis, std::vector<Vec3> offsets)
{
    const ModalSurface& old_surface = *b.model->surface;
    std::shared_ptr<const Collider> material = old_surface.material;
    std::shared_ptr<const Collider> rest = material;
    if (!offsets.empty()) {
        auto moved = std::make_shared<Collider>(*material);
        auto samples = std::make_shared<SampleSet>(*material->samples);
        double reach = 0.0;
        for (SurfaceSample& s : samples->samples) {
            const Vec3 u = interpolate_nodal(modal_weights(*basis, s.point + material->com_shape), offsets);
            s.point += u;
            reach = std::max(reach, length(u));
        }
        moved->samples = samples;
        moved->local_box = {material->local_box.min - Vec3{reach, reach, reach},
                            material->local_box.max + Vec3{reach, reach, reach}};
        rest = std::move(moved);
    }
    auto model = std::make_shared<ModalModel>(*b.model);
    model->surface = make_modal_surface(rest, basis, material, std::move(offsets));
    model->omega.resize(static_cast<size_t>(basis->mode_count));
    for (size_t k = 0; k < model->omega.size(); ++k)
        model->omega[k] = 2.0 * std::numbers::pi * basis->frequencies_hz[k];
    model->basis = std::move(basis);
    b.model = std::move(model);
    b.maps = std::make_shared<ModalSubstepMaps>();
    b.deformed.stale = true;
}

std::vector<double> flatten(const std::vector<Vec3>& v)
{
    std::vector<double> out;
    out.reserve(v.size() * 3);
    for (const Vec3& u : v)
        out.insert(out.end(), {u.x, u.y, u.z});
    return out;
}

// x ← P (x − minus), r × r row-major P.
void project(const std::vector<double>& p, std::vector<double>& x, const std::vector<double>* minus)
{
    const size_t r = x.size();
    std::vector<double> in(x);
    if (minus != nullptr)
        for (size_t k = 0; k < r; ++k)
            in[k] -= (*minus)[k];
    for (size_t i = 0; i < r; ++i) {
        double s = 0.0;
        for (size_t j = 0; j < r; ++j)
            s += p[i * r + j] * in[j];
        x[i] = s;
    }
}

void swap_in(ModalBody& b)
{
    ModalState& s = b.state;
    const Clock::time_point start = Clock::now();
    const RemouldResult& job = b.remould_job.get(); // waits: the step index fixes the swap, not the build
    b.stats.remould_wait_seconds = std::chrono::duration<double>(Clock::now() - start).count();
    if (job.basis == nullptr || job.basis->mode_count != static_cast<int>(s.q.size())) {
        s.remould_failed = true;
    } else {
        // The old shape is d = U + Φ q; the new rest shape U' = U + Φ q_p,asked, so the new amplitudes
        // fit Φ (q − q_p,asked) and the plastic flow since the request, Φ (q_p − q_p,asked).
        project(job.projection, s.q, &s.remould_q_plastic);
        project(job.projection, s.q_dot, nullptr);
        project(job.projection, s.q_plastic, &s.remould_q_plastic);
        std::fill(s.host_force.begin(), s.host_force.end(), 0.0);
        s.rest_offsets = flatten(job.rest_offsets);
        install_model(b, job.basis, job.rest_offsets);
        ++b.stats.remould_count;
        b.stats.remould_seconds = job.seconds;
    }
    s.remould_step = 0;
    s.remould_q_plastic.clear();
    b.remould_job = {};
}

} // namespace

double rest_shape_change(const ModalBody& b)
{
    const std::vector<double>& qp = b.state.q_plastic;
    if (std::all_of(qp.begin(), qp.end(), [](double x) { return x == 0.0; }))
        return 0.0;
    std::vector<Vec3> nodal;
    modal_nodal_displacements(*b.model->basis, qp, nodal);
    double largest = 0.0;
    for (const Vec3& u : nodal)
        largest = std::max(largest, length(u));
    return largest / lattice_extent(*b.model->basis);
}

void remould_modal_bodies(World::Impl& w)
{
    const auto step = static_cast<uint64_t>(w.step_count);
    for (ModalBody& b : w.reg.store<ModalBody>().values()) {
        const ModalModel& m = *b.model;
        if (!m.plastic.plastic() || !(m.remould_threshold > 0.0))
            continue;
        if (b.state.remould_step != 0) {
            if (step >= b.state.remould_step)
                swap_in(b);
            continue;
        }
        if (b.state.remould_failed || !(rest_shape_change(b) > m.remould_threshold))
            continue;
        b.state.remould_step = step + static_cast<uint64_t>(m.remould_delay_steps);
        b.state.remould_q_plastic = b.state.q_plastic;
        launch(w, b);
    }
}

void restore_remould(World::Impl& w)
{
    for (ModalBody& b : w.reg.store<ModalBody>().values()) {
        b.remould_job = {}; // a rebuild in flight belongs to the state left behind
        if (b.state.rest_offsets != flatten(b.model->surface->rest_offsets)) {
            std::vector<Vec3> offsets(b.state.rest_offsets.size() / 3);
            for (size_t n = 0; n < offsets.size(); ++n)
                offsets[n] = {b.state.rest_offsets[3 * n], b.state.rest_offsets[3 * n + 1],
                              b.state.rest_offsets[3 * n + 2]};
            ModalBasisDef def = moulded_def(b, offsets);
            // Built before (this world or one sharing its cache) or deterministic to build again.
            Result<std::shared_ptr<const ModalBasis>> built = w.modal_bases->get_or_build(def);
            if (built)
                install_model(b, *built, std::move(offsets));
        }
        if (b.state.remould_step != 0)
            launch(w, b);
    }
}

} // namespace supermodal
