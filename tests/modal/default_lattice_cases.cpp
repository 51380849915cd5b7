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

// References: `default_lattice_table --reference NAME SUB` (RelWithDebInfo build, 2026-12-02; SUB the
// cut-cell subdivisions stored with each), refining from the default lattice, except board_1_50:
// `--reference board_1_50 4 16 2 4` (from 16 × 2 × 4: from the default, × 1.5 reaches the dof cap at
// 36 × 8 × 8 still moving 0.3%). The last change is at most 0.1%, except where the next refinement
// would pass k_max_lattice_dofs: rounded_box 0.103%, board_2x4 0.104%, slat_1_30 0.155%.
// `default_lattice_table --check` recomputes every reference (about 7 CPU minutes) and compares.
const std::vector<LatticeCase> k_cases = {
    // Boards: length along x, thickness along y, width along z (the 2x4 of docs/modal.md).
    {"board_2x4",
     superquadric({0.5, 0.019, 0.0445}, 0.1, 0.1),
     {3.92455159, 8.98800588, 10.7121428, 20.7191961, 21.2236279, 23.6336331},
     {36, 8, 8},
     8,
     0.00104},
    {"board_1_10",
     superquadric({0.5, 0.05, 0.1}, 0.1, 0.1),
     {10.0413748, 18.4117938, 23.4221414, 26.1746185, 43.1624112, 47.0109983},
     {24, 5, 5},
     8,
     0.000898},
    {"board_1_50",
     superquadric({0.5, 0.01, 0.05}, 0.1, 0.1),
     {2.07353155, 5.70173498, 10.0289533, 11.1425083, 11.5961595, 18.3443476},
     {54, 8, 14},
     4,
     0.000957,
     {16, 2, 4}},
    // Slender with a rounded section: the pine slat of the auto-lattice tests (1:30, ε 0.3) and a
    // 1:50 ellipsoid, whose sections the cut cells must resolve.
    {"slat_1_30",
     superquadric({0.3, 0.02, 0.01}, 0.3, 0.3),
     {6.02814734, 11.9195557, 16.2224329, 31.0509649, 31.4614121, 43.241182},
     {36, 8, 8},
     4,
     0.00155},
    {"needle_1_50",
     superquadric({0.5, 0.02, 0.01}, 1.0, 1.0),
     {2.60896663, 5.20139223, 5.8739391, 10.2096521, 11.6608773, 15.6046939},
     {36, 8, 8},
     4,
     0.00043},
    {"cube",
     superquadric({0.5, 0.5, 0.5}, 0.1, 0.1),
     {28.7491926, 28.7491926, 38.3396008, 38.3396008, 38.3396008, 38.9406726},
     {18, 18, 18},
     4,
     0.000722},
    {"sphere",
     superquadric({0.5, 0.5, 0.5}, 1.0, 1.0),
     {49.3547844, 49.3550997, 49.3555491, 49.3557774, 49.3559099, 52.2347843},
     {12, 12, 12},
     4,
     0.000463},
    {"ellipsoid",
     superquadric({0.5, 0.3, 0.2}, 1.0, 1.0),
     {38.1766004, 45.8376586, 48.2306086, 63.5255692, 67.9925986, 71.4638096},
     {18, 12, 8},
     4,
     0.000707},
    {"rounded_box",
     superquadric({0.5, 0.3, 0.2}, 0.4, 0.4),
     {31.3059937, 31.8997151, 39.118629, 52.2856214, 55.8201411, 59.2886468},
     {27, 18, 12},
     4,
     0.00103},
    {"eps_0.1",
     superquadric({0.5, 0.4, 0.3}, 0.1, 0.1),
     {27.0739284, 35.0089301, 39.0462371, 43.8150776, 47.3471758, 47.7426164},
     {11, 9, 6},
     8,
     0.000506},
    {"eps_2",
     superquadric({0.5, 0.4, 0.3}, 2.0, 2.0),
     {51.2478294, 60.6306467, 72.2892566, 74.2012603, 80.0407626, 81.5966729},
     {17, 14, 9},
     8,
     0.000893},
    {"taper",
     tapered(superquadric({0.2, 0.2, 0.5}, 0.5, 1.0), 0.6, 0.3),
     {31.8571475, 32.7972565, 43.2814414, 58.278477, 61.008127, 62.5685557},
     {14, 14, 27},
     4,
     0.000572},
    {"bend",
     bent(superquadric({0.1, 0.1, 0.5}, 0.5, 1.0), 1.2, 0.3),
     {18.5953668, 21.9202672, 34.7478754, 43.6411182, 47.3891503, 58.6571182},
     {6, 5, 20},
     8,
     0.000965},
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
