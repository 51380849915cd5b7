// SPDX-License-Identifier: MIT
#include "modal/stress.h"

#include "modal/assembly.h"
#include "modal/lattice.h"
#include "supermodal/geometry.h"

#include <algorithm>
#include <cmath>

namespace supermodal::modal
{
namespace
{

/// The nodes whose field covers a point and the shape-function gradients there [1/m] (shape frame).
struct Gradients {
    std::array<int32_t, k_max_cell_nodes> nodes{};
    std::array<std::array<double, 3>, k_max_cell_nodes> grad{};
    int count = 0;
};

/// Like modal_weights: the point's cell, or its proxy's field extended to it.
Gradients gradients_at(const ModalBasis& basis, const Vec3& p)
{
    Gradients g;
    const Lattice lat = lattice_of(basis);
    std::array<double, 3> xi{};
    const int proxy = locate_field(basis, lat, p, xi);
    if (proxy < 0)
        return g;
    const int per_cell = lattice_nodes_per_cell(lat.order);
    double n[k_max_cell_nodes];
    std::array<double, 3> dn[k_max_cell_nodes];
    shape_functions(lat.order, xi, n, dn);
    for (int a = 0; a < per_cell; ++a) {
        g.nodes[a] = basis.cell_nodes[static_cast<size_t>(proxy) * per_cell + a];
        for (int d = 0; d < 3; ++d) // uniform box cell: ∂ξ/∂x = 2 / h
            g.grad[a][d] = dn[a][d] * 2.0 / lat.cell_size[d];
    }
    g.count = per_cell;
    return g;
}

/// Stress of one mode's field (or of a combination, `coefficients` of length r) at a point.
Voigt stress_from(const ModalBasis& basis, const Gradients& g, const Lame& lame, const double* coefficients,
                  int used)
{
    const int r = basis.mode_count;
    double du[3][3] = {}; // ∂u_j/∂x_i
    for (int a = 0; a < g.count; ++a) {
        const double* phi = &basis.mode_shapes[static_cast<size_t>(g.nodes[a]) * 3 * r];
        for (int j = 0; j < 3; ++j) {
            double u = 0.0;
            for (int k = 0; k < used; ++k)
                u += phi[j * r + k] * coefficients[k];
            for (int i = 0; i < 3; ++i)
                du[i][j] += g.grad[a][i] * u;
        }
    }
    const double trace = du[0][0] + du[1][1] + du[2][2];
    const double two_mu = 2.0 * lame.mu;
    return {lame.lambda * trace + two_mu * du[0][0], lame.lambda * trace + two_mu * du[1][1],
            lame.lambda * trace + two_mu * du[2][2], lame.mu * (du[1][2] + du[2][1]),
            lame.mu * (du[0][2] + du[2][0]),         lame.mu * (du[0][1] + du[1][0])};
}

bool inside(const ShapeDef& shape, const Vec3& p)
{
    // Points on the surface count: the lattice box touches a box-like body on its faces, and those are
    // where bending stress peaks. 1e-9 of the radius along the ray (contact_measure's scale).
    constexpr double k_on_surface = 1e-9;
    const bool plain = shape.type == ShapeType::Superquadric && !is_deformed(shape);
    return (plain ? contact_measure(shape, p) : shape_measure(shape, p)) <= k_on_surface;
}

} // namespace

double von_mises(const Voigt& s)
{
    const double a = s[0] - s[1], b = s[1] - s[2], c = s[2] - s[0];
    const double v = 0.5 * (a * a + b * b + c * c) + 3.0 * (s[3] * s[3] + s[4] * s[4] + s[5] * s[5]);
    return std::sqrt(std::max(v, 0.0));
}

Voigt stress_at(const ModalBasis& basis, const Vec3& point_shape, std::span<const double> q)
{
    const Gradients g = gradients_at(basis, point_shape);
    const int used = std::min(basis.mode_count, static_cast<int>(q.size()));
    return stress_from(basis, g, lame_from(basis.young, basis.poisson), q.data(), used);
}

void displacement_and_gradient(const ModalBasis& basis, const Vec3& point_shape, std::span<const double> q,
                               Vec3& out_u, Mat3& out_gradient, std::span<const double> nodal)
{
    out_u = {};
    out_gradient = {};
    const int r = basis.mode_count;
    const int used = std::min(r, static_cast<int>(q.size()));
    const Gradients g = gradients_at(basis, point_shape);
    const LatticeWeights w = modal_weights(basis, point_shape); // same cell and nodes as g
    for (int a = 0; a < g.count; ++a) {
        const double* phi = &basis.mode_shapes[static_cast<size_t>(g.nodes[a]) * 3 * r];
        for (int i = 0; i < 3; ++i) {
            double u = 0.0;
            for (int k = 0; k < used; ++k)
                u += phi[i * r + k] * q[k];
            if (!nodal.empty())
                u += nodal[static_cast<size_t>(g.nodes[a]) * 3 + static_cast<size_t>(i)];
            out_u[i] += w.weights[a] * u;
            for (int j = 0; j < 3; ++j)
                out_gradient.m[i][j] += g.grad[a][j] * u;
        }
    }
}

namespace
{

double point_von_mises(const double* s, size_t r, size_t used, std::span<const double> q)
{
    Voigt v{};
    for (size_t comp = 0; comp < 6; ++comp) {
        double sum = 0.0;
        for (size_t k = 0; k < used; ++k)
            sum += s[comp * r + k] * q[k];
        v[comp] = sum;
    }
    return von_mises(v);
}

// vm² = ½[(a−b)² + (b−c)² + (c−a)²] + 3(d² + e² + f²) ≤ 1.5(a² + b² + c²) + 3(d² + e² + f²) = ‖W v‖²,
// since (a−b)² + (b−c)² + (c−a)² = 3(a² + b² + c²) − (a + b + c)²; and ‖W S q‖ ≤ ‖W S‖_F ‖q‖.
double point_bound(const double* s, size_t r)
{
    double sum = 0.0;
    for (size_t comp = 0; comp < 6; ++comp) {
        const double w2 = comp < 3 ? 1.5 : 3.0;
        for (size_t k = 0; k < r; ++k)
            sum += w2 * s[comp * r + k] * s[comp * r + k];
    }
    return std::sqrt(sum);
}

// Rounding of the bound's own sums (~r ulps): a point is skipped only below threshold / this.
constexpr double k_bound_safety = 1.0 + 1e-9;

} // namespace

StressModel build_stress_model(const ModalBasis& basis, const ShapeDef& shape)
{
    StressModel m;
    const int r = basis.mode_count;
    m.mode_count = r;
    const Lame lame = lame_from(basis.young, basis.poisson);
    const int per_cell = lattice_nodes_per_cell(basis.element_order);
    const int nx = basis.cells[0], ny = basis.cells[1], nz = basis.cells[2];
    std::vector<double> unit(static_cast<size_t>(r), 0.0);
    for (int k = 0, c = 0; k < nz; ++k)
        for (int j = 0; j < ny; ++j)
            for (int i = 0; i < nx; ++i, ++c) {
                if (basis.cell_nodes.empty() || basis.cell_nodes[static_cast<size_t>(c) * per_cell] < 0)
                    continue;
                const Vec3 centre{basis.lattice_min.x + basis.cell_size.x * (i + 0.5),
                                  basis.lattice_min.y + basis.cell_size.y * (j + 0.5),
                                  basis.lattice_min.z + basis.cell_size.z * (k + 0.5)};
                for (int c3 = 0; c3 < 27; ++c3) {
                    const Vec3 xi{static_cast<double>(c3 % 3 - 1), static_cast<double>(c3 / 3 % 3 - 1),
                                  static_cast<double>(c3 / 9 - 1)};
                    // Pulled in by 1e-9 of a cell so that locate() puts the point in this cell.
                    const Vec3 p = centre + Vec3{xi.x * basis.cell_size.x, xi.y * basis.cell_size.y,
                                                 xi.z * basis.cell_size.z} *
                                                (0.5 * (1.0 - 1e-9));
                    if (!inside(shape, p))
                        continue;
                    const Gradients g = gradients_at(basis, p);
                    m.points.push_back(p);
                    const size_t base = m.stress_modes.size();
                    m.stress_modes.resize(base + 6 * static_cast<size_t>(r));
                    for (int mode = 0; mode < r; ++mode) {
                        unit[mode] = 1.0;
                        const Voigt s = stress_from(basis, g, lame, unit.data(), r);
                        unit[mode] = 0.0;
                        for (int comp = 0; comp < 6; ++comp)
                            m.stress_modes[base + static_cast<size_t>(comp) * r + mode] = s[comp];
                    }
                    m.point_bounds.push_back(point_bound(&m.stress_modes[base], static_cast<size_t>(r)));
                    m.max_point_bound = std::max(m.max_point_bound, m.point_bounds.back());
                }
            }
    return m;
}

StressPeak max_von_mises(const StressModel& model, std::span<const double> q)
{
    StressPeak peak;
    const size_t r = static_cast<size_t>(model.mode_count);
    const size_t used = std::min(r, q.size());
    const double* s = model.stress_modes.data();
    for (size_t p = 0; p < model.points.size(); ++p, s += 6 * r) {
        const double vm = point_von_mises(s, r, used, q);
        if (vm > peak.von_mises || peak.point < 0) {
            peak.von_mises = vm;
            peak.point = static_cast<int>(p);
        }
    }
    return peak;
}

StressPeak max_von_mises_above(const StressModel& model, std::span<const double> q, double threshold)
{
    const size_t r = static_cast<size_t>(model.mode_count);
    const size_t used = std::min(r, q.size());
    double q2 = 0.0;
    for (size_t k = 0; k < used; ++k)
        q2 += q[k] * q[k];
    const double q_norm = std::sqrt(q2) * k_bound_safety;
    // Without the bounds (a model built elsewhere) or with a non-finite q: the full search.
    if (model.point_bounds.size() != model.points.size() || !std::isfinite(q_norm))
        return max_von_mises(model, q);
    StressPeak peak;
    if (!(model.max_point_bound * q_norm > threshold))
        return peak;
    const double* s = model.stress_modes.data();
    for (size_t p = 0; p < model.points.size(); ++p, s += 6 * r) {
        if (!(model.point_bounds[p] * q_norm > threshold))
            continue; // cannot exceed the threshold, so cannot be a peak above it
        const double vm = point_von_mises(s, r, used, q);
        if (vm > peak.von_mises || peak.point < 0) {
            peak.von_mises = vm;
            peak.point = static_cast<int>(p);
        }
    }
    return peak;
}

} // namespace supermodal::modal
