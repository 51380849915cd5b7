// SPDX-License-Identifier: MIT
#include "modal/default_lattice_cases.h"

#include <algorithm>
#include <cmath>

namespace supermodal::test
{
namespace
{

ShapeDef superquadric(Vec3 radii, double eps1, double eps2)
{
    ShapeDef s = default_shape_def();
    s.radii = radii;
    s.epsilon1 = eps1;
    s.epsilon2 = eps2;
    return s;
}

ShapeDef tapered(ShapeDef s, double kx, double ky)
{
    s.taper = {kx, ky};
    return s;
}

ShapeDef bent(ShapeDef s, double curvature, double angle)
{
    s.bend = {curvature, angle};
    return s;
}

// References: `default_lattice_table --reference NAME` (RelWithDebInfo), its last lattice.
const std::vector<LatticeCase> k_cases = {
    // Boards: length along x, thickness along y, width along z (the 2x4 of docs/modal.md).
    {"board_2x4", superquadric({0.5, 0.019, 0.0445}, 0.1, 0.1), {}, {}, 0},
    {"board_1_10", superquadric({0.5, 0.05, 0.1}, 0.1, 0.1), {}, {}, 0},
    {"board_1_50", superquadric({0.5, 0.01, 0.05}, 0.1, 0.1), {}, {}, 0},
    {"cube", superquadric({0.5, 0.5, 0.5}, 0.1, 0.1), {}, {}, 0},
    {"sphere", superquadric({0.5, 0.5, 0.5}, 1.0, 1.0), {}, {}, 0},
    {"ellipsoid", superquadric({0.5, 0.3, 0.2}, 1.0, 1.0), {}, {}, 0},
    {"rounded_box", superquadric({0.5, 0.3, 0.2}, 0.4, 0.4), {}, {}, 0},
    {"eps_0.1", superquadric({0.5, 0.4, 0.3}, 0.1, 0.1), {}, {}, 0},
    {"eps_2", superquadric({0.5, 0.4, 0.3}, 2.0, 2.0), {}, {}, 0},
    {"taper", tapered(superquadric({0.2, 0.2, 0.5}, 0.5, 1.0), 0.6, 0.3), {}, {}, 0},
    {"bend", bent(superquadric({0.1, 0.1, 0.5}, 0.5, 1.0), 1.2, 0.3), {}, {}, 0},
};

} // namespace

std::span<const LatticeCase> lattice_cases()
{
    return k_cases;
}

const LatticeCase* find_lattice_case(const std::string& name)
{
    for (const LatticeCase& c : k_cases)
        if (c.name == name)
            return &c;
    return nullptr;
}

ModalBasisDef lattice_case_def(const LatticeCase& c, const std::array<int, 3>& cells, int subdivisions)
{
    ModalBasisDef def = default_modal_basis_def();
    def.shape = c.shape;
    def.mode_count = k_compared_modes;
    def.lattice.cells = cells;
    def.lattice.cut_cell_subdivisions = subdivisions;
    return def;
}

double max_relative_error(std::span<const double> hz, std::span<const double> reference_hz)
{
    double worst = 0.0;
    const size_t n = std::min(hz.size(), reference_hz.size());
    for (size_t k = 0; k < n; ++k)
        worst = std::max(worst, std::abs(hz[k] - reference_hz[k]) / reference_hz[k]);
    return n == 0 ? 1.0 : worst;
}

} // namespace supermodal::test
