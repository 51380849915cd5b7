// SPDX-License-Identifier: MIT
#include "modal/inverse_map.h"

#include "modal/stress.h"

#include <algorithm>
#include <cmath>

namespace supermodal::modal
{
namespace
{

/// Inverse of a 3×3 matrix by its adjugate; false when (nearly) singular (|det F| ≤ 1e-12: the
/// deformation has folded or squashed the material flat).
bool invert(const Mat3& a, Mat3& out)
{
    const auto& m = a.m;
    const double c00 = m[1][1] * m[2][2] - m[1][2] * m[2][1], c01 = m[1][2] * m[2][0] - m[1][0] * m[2][2],
                 c02 = m[1][0] * m[2][1] - m[1][1] * m[2][0];
    const double det = m[0][0] * c00 + m[0][1] * c01 + m[0][2] * c02;
    if (!(std::abs(det) > 1e-12) || !std::isfinite(det))
        return false;
    const double inv = 1.0 / det;
    out.m[0][0] = c00 * inv;
    out.m[1][0] = c01 * inv;
    out.m[2][0] = c02 * inv;
    out.m[0][1] = (m[0][2] * m[2][1] - m[0][1] * m[2][2]) * inv;
    out.m[1][1] = (m[0][0] * m[2][2] - m[0][2] * m[2][0]) * inv;
    out.m[2][1] = (m[0][1] * m[2][0] - m[0][0] * m[2][1]) * inv;
    out.m[0][2] = (m[0][1] * m[1][2] - m[0][2] * m[1][1]) * inv;
    out.m[1][2] = (m[0][2] * m[1][0] - m[0][0] * m[1][2]) * inv;
    out.m[2][2] = (m[0][0] * m[1][1] - m[0][1] * m[1][0]) * inv;
    return true;
}

} // namespace

InverseMap invert_deformation(const ModalBasis& basis, std::span<const double> q, const Vec3& p,
                              std::span<const double> nodal)
{
    InverseMap out;
    if (!is_finite(p))
        return out;
    const double size = std::max({basis.cell_size.x * basis.cells[0], basis.cell_size.y * basis.cells[1],
                                  basis.cell_size.z * basis.cells[2]});
    const double tolerance = 1e-10 * size;
    constexpr int k_max_iterations = 12; // small strains converge in 2–3 steps
    Vec3 u{};
    Mat3 grad{};
    displacement_and_gradient(basis, p, q, u, grad, nodal);
    Vec3 x = p - u;
    for (int it = 0; it < k_max_iterations; ++it) {
        displacement_and_gradient(basis, x, q, u, grad, nodal);
        for (int i = 0; i < 3; ++i)
            grad.m[i][i] += 1.0; // F = I + ∇u
        if (!invert(grad, out.inverse_deformation))
            return out;
        const Vec3 residual = x + u - p;
        out.iterations = it;
        if (length(residual) <= tolerance) {
            out.converged = true;
            out.rest_point = x;
            return out;
        }
        x = x - out.inverse_deformation * residual;
        if (!is_finite(x))
            return out;
    }
    return out;
}

} // namespace supermodal::modal
