// SPDX-License-Identifier: MIT
// Mode shapes in the editor: a modal body swinging in one of its modes while the world is held still,
// and what the Body window lists about its modes.
#include "session.h"
#include "supermodal/body.h"
#include "supermodal/geometry.h"
#include "ui.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace supermodal::editor
{

Status EditorSession::animate_mode(std::string_view body, const ModeAnimationDef& def)
{
    if (!m_world)
        return Error{"", "", "no scene is loaded"};
    end_mode_animation();
    const std::string name(body);
    const Entity e = find_body(*m_world, name);
    if (e.is_null())
        return Error{"", "", "no body named \"" + name + "\""};
    const ModalBasis* basis = body_modal_basis(*m_world, e);
    if (basis == nullptr)
        return Error{"", "", "\"" + name + "\" is rigid: it has no elastic modes"};
    if (def.mode < 0 || def.mode >= basis->mode_count)
        return Error{"", "",
                     "\"" + name + "\" has modes 1 to " + std::to_string(basis->mode_count) + ", not " +
                         std::to_string(def.mode + 1)};
    if (!(def.period > 0.0 && std::isfinite(def.period)) ||
        !(def.peak_fraction > 0.0 && std::isfinite(def.peak_fraction)))
        return Error{"", "", "a mode animation needs a period and a peak fraction > 0"};
    // The swing that moves the farthest lattice node by peak_fraction of the largest half-extent.
    double extent = 0.0;
    for (int a = 0; a < 3; ++a)
        extent = std::max(extent, 0.5 * basis->cells[a] * basis->cell_size[a]);
    const size_t r = static_cast<size_t>(basis->mode_count), k = static_cast<size_t>(def.mode);
    double largest = 0.0; // max over nodes of |φ_k| [1/√kg]
    for (size_t node = 0; node < basis->node_positions.size(); ++node) {
        double sq = 0.0;
        for (size_t axis = 0; axis < 3; ++axis) {
            const double phi = basis->mode_shapes[(node * 3 + axis) * r + k];
            sq += phi * phi;
        }
        largest = std::max(largest, std::sqrt(sq));
    }
    if (!(largest > 0.0))
        return Error{"", "", "mode " + std::to_string(def.mode + 1) + " of \"" + name + "\" moves no node"};

    ModeAnimation a;
    a.body = e;
    a.name = name;
    a.mode = def.mode;
    a.frequency_hz = basis->frequencies_hz[k];
    a.peak_displacement = def.peak_fraction * extent;
    a.amplitude = a.peak_displacement / largest;
    a.period = def.period;
    a.accuracy = body_modal_accuracy(*m_world, e);
    const BodyModalState state = body_modal_state(*m_world, e);
    m_animation_q = state.amplitudes;
    m_animation_v = state.velocities;
    m_animation_start = m_world->snapshot();
    m_animation_was_playing = m_playing;
    m_playing = false;
    m_animation = a;
    apply_mode_animation();
    return {};
}

void EditorSession::apply_mode_animation()
{
    const ModeAnimation& a = *m_animation;
    std::vector<double> q = m_animation_q;
    q[static_cast<size_t>(a.mode)] += a.amplitude * std::sin(2.0 * M_PI * a.time / a.period);
    (void)set_body_modal_state(*m_world, a.body, q, m_animation_v); // sizes and values checked above
}

void EditorSession::end_mode_animation()
{
    if (!m_animation)
        return;
    // The snapshot holds every body (sleep, contact caches, the adaptive modes set active), so the
    // world is as it was, not merely its amplitudes.
    if (m_world && m_animation_start)
        (void)m_world->restore(*m_animation_start); // same world, no body created since: cannot fail
    m_playing = m_animation_was_playing;
    m_animation.reset();
    m_animation_start.reset();
}

void EditorSession::play()
{
    end_mode_animation();
    m_playing = true;
}

namespace
{

template <class... Args> void add_line(ModesReadout& r, const char* format, Args... args)
{
    char text[256];
    std::snprintf(text, sizeof text, format, args...);
    r.lines.emplace_back(text);
}

} // namespace

ModesReadout modes_readout(const EditorSession& session, const std::string& body)
{
    ModesReadout r;
    r.body = body;
    if (!session.has_world())
        return r;
    const World& w = session.world();
    const Entity e = find_body(w, body);
    const ModalBasis* basis = e.is_null() ? nullptr : body_modal_basis(w, e);
    if (basis == nullptr) {
        r.rigid = !e.is_null();
        return r;
    }
    r.modal = true;
    r.frequencies_hz = basis->frequencies_hz;
    r.amplitudes = body_modal_state(w, e).amplitudes;
    const std::optional<ModeAnimation>& a = session.mode_animation();
    if (a && a->name == body)
        r.animating = a->mode;
    // While a mode swings, the report of the state it swings from: the swing is not a load.
    const ModalAccuracy accuracy = r.animating >= 0 ? a->accuracy : body_modal_accuracy(w, e);
    r.residual = accuracy.residual;
    r.truncated_energy = accuracy.truncated_energy;
    r.truncated_fraction = accuracy.truncated_fraction;
    const BodyPlasticState plastic = body_plastic_state(w, e);
    const BodyRemould remould = body_remould(w, e);
    r.rebuilds = remould.rebuilds;
    r.rebuild_pending_step = remould.pending_step;
    if (!remould.rest_offsets.empty() ||
        std::any_of(plastic.offsets.begin(), plastic.offsets.end(), [](double q) { return q != 0.0; })) {
        // Over surface samples about 1/40 of the body apart: lattice nodes outside the material would
        // overstate the dent.
        double extent = 0.0;
        for (int axis = 0; axis < 3; ++axis)
            extent = std::max(extent, basis->cells[axis] * basis->cell_size[axis]);
        for (const SurfaceSample& p : sample_surface(body_shape(w, e), extent / 40.0, 2000)) {
            const LatticeWeights lw = modal_weights(*basis, p.point);
            Vec3 dent = modal_displacement(*basis, lw, plastic.offsets);
            if (!remould.rest_offsets.empty()) // the part the rebuilt modes' rest shape took over
                dent += interpolate_nodal(lw, remould.rest_offsets);
            r.plastic_dent = std::max(r.plastic_dent, length(dent));
        }
    }

    add_line(r, "%d modes, natural frequency [Hz], amplitude q [sqrt(kg) m]", basis->mode_count);
    for (size_t k = 0; k < r.frequencies_hz.size(); ++k)
        add_line(r, "%7.4g Hz  q %9.2e", r.frequencies_hz[k], r.amplitudes[k]); // after "Animate k"
    add_line(r, "modal residual %.3e (0: the modes hold the last loads)", r.residual);
    add_line(r, "truncated energy %.3e J (%.3e of the static response)", r.truncated_energy,
             r.truncated_fraction);
    if (r.plastic_dent > 0.0 && r.rebuilds == 0)
        add_line(r,
                 "plastic dent: the surface kept up to %.3g mm; the modes are those of the unmoulded shape",
                 1e3 * r.plastic_dent);
    else if (r.plastic_dent > 0.0)
        add_line(r,
                 "plastic dent: the surface kept up to %.3g mm; the modes are those of the moulded shape "
                 "(%d rebuild%s)",
                 1e3 * r.plastic_dent, r.rebuilds, r.rebuilds == 1 ? "" : "s");
    if (r.rebuild_pending_step != 0)
        add_line(r, "modes rebuilding for the moulded shape: in use from step %llu",
                 static_cast<unsigned long long>(r.rebuild_pending_step));
    return r;
}

} // namespace supermodal::editor
