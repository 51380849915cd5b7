// SPDX-License-Identifier: MIT
// The direct solve of small islands' normal contact rows (see solve_small_islands): a dense system
// over the island's points, W·Δλ + C·(λ + Δλ) = −(v_n + bias) for the rows that push, with W the rows'
// coupling through the bodies' masses and C each soft row's compliance, and active sets so that no
// row pulls (a row that would is left at zero, a row left at zero that would close is taken back).
#include "world/contact_solve.h"

#include <Eigen/Dense>
#include <array>
#include <cstdio>
#include <cstdlib>

namespace supermodal
{
namespace
{

// Most points an island may have to be solved directly: a box on a box on the floor has 8, a short
// stack or a few boxes on a chair a few dozen; a pile's islands are left to the passes.
constexpr size_t k_max_direct_rows = 24;
// Each row's diagonal is raised by this fraction: four coplanar points of one face are redundant
// (rank 3), and this picks the even share among the equal solutions.
constexpr double k_regularization = 1e-6;

using Matrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, k_max_direct_rows, k_max_direct_rows>;
using Vector = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, k_max_direct_rows, 1>;

// Normal velocity change of side sj's row (normal nj) per unit impulse along ni at side si, through
// their common body: zero unless both sides are the same dynamic body.
double side_coupling(const Side& si, const Vec3& ni, const Side& sj, const Vec3& nj)
{
    if (si.v == nullptr || si.v != sj.v || si.inv_mass == 0.0)
        return 0.0;
    return si.inv_mass * dot(ni, nj) + dot(cross(si.r, ni), si.inv_inertia * cross(sj.r, nj));
}

// W_ij: row j's relative normal velocity change per unit normal impulse on row i [1/kg].
double coupling(const SoftPoint& i, const SoftPoint& j)
{
    return side_coupling(i.a, i.normal, j.a, j.normal) - side_coupling(i.a, i.normal, j.b, j.normal) -
           side_coupling(i.b, i.normal, j.a, j.normal) + side_coupling(i.b, i.normal, j.b, j.normal);
}

// Δλ for the rows marked active, inactive rows held at a total of zero (Δλ = −λ).
void solve_active(const Matrix& a, const Vector& rhs, const Vector& start,
                  const std::array<bool, k_max_direct_rows>& active, Vector& delta)
{
    const auto n = static_cast<Eigen::Index>(rhs.size());
    std::array<Eigen::Index, k_max_direct_rows> index{};
    Eigen::Index m = 0;
    for (Eigen::Index i = 0; i < n; ++i) {
        delta(i) = active[i] ? 0.0 : -start(i);
        if (active[i])
            index[m++] = i;
    }
    Matrix sub(m, m);
    Vector b(m);
    for (Eigen::Index r = 0; r < m; ++r) {
        b(r) = rhs(index[r]);
        for (Eigen::Index i = 0; i < n; ++i)
            if (!active[i])
                b(r) -= a(index[r], i) * delta(i);
        for (Eigen::Index c = 0; c < m; ++c)
            sub(r, c) = a(index[r], index[c]);
    }
    const Vector x = sub.ldlt().solve(b);
    for (Eigen::Index r = 0; r < m; ++r)
        delta(index[r]) = x(r);
}

// One island's points (indices into rows.points): its system, the active sets, the impulses applied.
void solve_island(SoftContacts& rows, std::span<const uint32_t> points, bool use_bias)
{
    const auto n = static_cast<Eigen::Index>(points.size());
    Matrix a(n, n);
    Vector rhs(n), start(n), delta(n);
    for (Eigen::Index i = 0; i < n; ++i) {
        const SoftPoint& p = rows.points[points[i]];
        const NormalTarget t = normal_target(p, rows.h, rows.push_out_speed, use_bias);
        const double compliance =
            p.normal_mass > 0.0 ? t.impulse_scale / (p.normal_mass * t.mass_scale) : 0.0;
        const double vn = dot(anchor_velocity(p.a) - anchor_velocity(p.b), p.normal);
        start(i) = p.normal_impulse;
        rhs(i) = -(vn + t.bias + compliance * p.normal_impulse);
        for (Eigen::Index j = 0; j < n; ++j)
            a(i, j) = coupling(p, rows.points[points[j]]);
        a(i, i) += compliance + k_regularization * a(i, i);
    }
    if (std::getenv("SM_CHECKW")) {
        auto vn_of = [&](Eigen::Index j) {
            const SoftPoint& q = rows.points[points[j]];
            return dot(anchor_velocity(q.a) - anchor_velocity(q.b), q.normal);
        };
        double worst = 0.0;
        for (Eigen::Index i = 0; i < n; ++i) {
            Vector before(n);
            for (Eigen::Index j = 0; j < n; ++j) before(j) = vn_of(j);
            SoftPoint& p = rows.points[points[i]];
            push(p.a, p.normal, Vec3{});
            push(p.b, -1.0 * p.normal, Vec3{});
            for (Eigen::Index j = 0; j < n; ++j) {
                const double w = vn_of(j) - before(j);
                const double model = coupling(p, rows.points[points[j]]);
                worst = std::max(worst, std::abs(w - model) / (std::abs(a(i, i)) + 1e-30));
            }
            push(p.a, -1.0 * p.normal, Vec3{});
            push(p.b, p.normal, Vec3{});
        }
        std::fprintf(stderr, "W check n=%ld worst rel %g\n", static_cast<long>(n), worst);
    }
    std::array<bool, k_max_direct_rows> active{};
    active.fill(true);
    bool solved = false;
    for (Eigen::Index round = 0; round <= 4 * n && !solved; ++round) {
        solve_active(a, rhs, start, active, delta);
        // One flip a round, the worst: an active row that pulls lets go, a released row whose gap
        // would close comes back. None left: every row meets its target or pushes nothing.
        Eigen::Index worst = -1;
        double worst_violation = 0.0;
        for (Eigen::Index i = 0; i < n; ++i) {
            const double v = active[i] ? (start(i) + delta(i)) * a(i, i) : a.row(i).dot(delta) - rhs(i);
            if (v < worst_violation) {
                worst = i;
                worst_violation = v;
            }
        }
        if (worst < 0)
            solved = delta.allFinite();
        else
            active[worst] = !active[worst];
    }
    if (!solved)
        return; // left to the passes
    for (Eigen::Index i = 0; i < n; ++i) {
        SoftPoint& p = rows.points[points[i]];
        const double total = std::max(start(i) + delta(i), 0.0);
        const Vec3 impulse = (total - p.normal_impulse) * p.normal;
        push(p.a, impulse, Vec3{});
        push(p.b, -1.0 * impulse, Vec3{});
        p.normal_impulse = total;
    }
}

bool all_rigid(const SoftContacts& rows, std::span<const uint32_t> points)
{
    for (const uint32_t i : points)
        if (rows.points[i].a.modal.active() || rows.points[i].b.modal.active())
            return false;
    return true;
}

} // namespace

void solve_small_islands(SoftContacts& rows, bool use_bias)
{
    rows.islands.clear();
    for (const SoftPair& sp : rows.pairs)
        rows.islands.add_row(sp.node_a, sp.node_b);
    rows.islands.build();
    if (std::getenv("SM_CHECKW"))
        for (const SoftPair& sp : rows.pairs)
            std::fprintf(stderr, "pair nodes %u %u count %u islands %zu\n", sp.node_a, sp.node_b, sp.count,
                         rows.islands.island_count());
    for (size_t k = 0; k < rows.islands.island_count(); ++k) {
        rows.island_points.clear();
        for (const uint32_t pair : rows.islands.island(k)) {
            const SoftPair& sp = rows.pairs[pair];
            for (uint32_t i = 0; i < sp.count; ++i)
                rows.island_points.push_back(sp.first + i);
            if (rows.island_points.size() > k_max_direct_rows)
                break;
        }
        if (!rows.island_points.empty() && rows.island_points.size() <= k_max_direct_rows &&
            all_rigid(rows, rows.island_points))
            solve_island(rows, rows.island_points, use_bias);
    }
}

} // namespace supermodal
