// SPDX-License-Identifier: MIT
// Mode-kind guess (see mode_kind.h).
#include "modal/mode_kind.h"

#include <algorithm>

namespace supermodal::modal
{
namespace
{

constexpr double k_dominant_fraction = 0.5;
constexpr double k_min_aspect = 1.5; // longest side over the next one

struct Energies {
    double bend = 0.0, torsion = 0.0, axial = 0.0, total = 0.0;
};

/// Adds one cross-section's shares of Σ m|u|² for mode `col`.
void add_section(const LatticeModel& model, const Eigen::VectorXd& weight, const std::vector<int>& nodes,
                 const Eigen::MatrixXd& modes, Eigen::Index col, int axis, Energies& e)
{
    const Vec3 along{axis == 0 ? 1.0 : 0.0, axis == 1 ? 1.0 : 0.0, axis == 2 ? 1.0 : 0.0};
    double w_sum = 0.0;
    Vec3 center{}, t{};
    for (const int a : nodes) {
        const Vec3 u{modes(3 * a, col), modes(3 * a + 1, col), modes(3 * a + 2, col)};
        w_sum += weight[a];
        center += weight[a] * model.node_positions[a];
        t += weight[a] * (u - dot(u, along) * along);
    }
    if (!(w_sum > 0.0))
        return;
    center = center / w_sum;
    t = t / w_sum; // best sideways translation: the weighted mean (the rotation field averages to zero)
    double num = 0.0, den = 0.0;
    for (const int a : nodes) {
        const Vec3 u{modes(3 * a, col), modes(3 * a + 1, col), modes(3 * a + 2, col)};
        Vec3 r = model.node_positions[a] - center;
        r -= dot(r, along) * along;
        const Vec3 swirl = cross(along, r); // rotation about the axis, per radian
        num += weight[a] * dot(swirl, u - dot(u, along) * along - t);
        den += weight[a] * dot(swirl, swirl);
    }
    const double theta = den > 0.0 ? num / den : 0.0;
    for (const int a : nodes) {
        const Vec3 u{modes(3 * a, col), modes(3 * a + 1, col), modes(3 * a + 2, col)};
        e.axial += weight[a] * dot(u, along) * dot(u, along);
        e.total += weight[a] * dot(u, u);
    }
    e.bend += w_sum * dot(t, t);
    e.torsion += theta * theta * den;
}

} // namespace

std::vector<ModeKind> classify_modes(const LatticeModel& model, const Eigen::MatrixXd& modes)
{
    const Lattice& lat = model.lattice;
    int axis = 0;
    for (int d = 1; d < 3; ++d)
        if (lat.cells[d] * lat.cell_size[d] > lat.cells[axis] * lat.cell_size[axis])
            axis = d;
    double second = 0.0;
    for (int d = 0; d < 3; ++d)
        if (d != axis)
            second = std::max(second, lat.cells[d] * lat.cell_size[d]);
    if (lat.cells[axis] * lat.cell_size[axis] < k_min_aspect * second)
        return std::vector<ModeKind>(modes.cols(), ModeKind::Other); // no long axis to name modes by
    std::vector<std::vector<int>> sections(lat.grid_points(axis));
    for (int a = 0; a < model.node_count(); ++a)
        sections[model.node_grid[a][axis]].push_back(a);
    Eigen::VectorXd weight(model.node_count());
    for (int a = 0; a < model.node_count(); ++a)
        weight[a] = model.mass.coeff(3 * a, 3 * a); // diagonal of M: positive, unlike row sums
    std::vector<ModeKind> kinds;
    for (Eigen::Index col = 0; col < modes.cols(); ++col) {
        Energies e;
        for (const std::vector<int>& s : sections)
            add_section(model, weight, s, modes, col, axis, e);
        const double best = std::max({e.bend, e.torsion, e.axial});
        ModeKind kind = ModeKind::Other;
        if (e.total > 0.0 && best > k_dominant_fraction * e.total)
            kind =
                best == e.bend ? ModeKind::Bend : (best == e.torsion ? ModeKind::Torsion : ModeKind::Axial);
        kinds.push_back(kind);
    }
    return kinds;
}

} // namespace supermodal::modal
