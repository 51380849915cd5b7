// Bodies shared by the modal tests: the free-free 2x4 board and a soft sphere.
#pragma once

#include "modal/beam_reference.h"
#include "supermodal/modal.h"

namespace supermodal::test
{

// The 2x4 board: 1.0 × 0.038 × 0.089 m, length along x, thickness (0.038) along y, width (0.089) along
// z (Barr's frame, radii (0.5, 0.019, 0.0445)); wood-like E 11 GPa, ν 0.3, ρ 450 kg/m³; ε1 = ε2 = 0.05.
// "Flatwise" bending moves the board along y (through its thickness), "edgewise" along z.
inline constexpr double k_board_length = 1.0, k_board_thickness = 0.038, k_board_width = 0.089;

inline ModalBasisDef board_def(std::array<int, 3> cells, int modes = 6)
{
    ModalBasisDef def = default_modal_basis_def();
    def.shape.radii = {k_board_length / 2, k_board_thickness / 2, k_board_width / 2};
    def.shape.epsilon1 = def.shape.epsilon2 = 0.05;
    def.density = 450.0;
    def.young = 11e9;
    def.poisson = 0.3;
    def.lattice.cells = cells;
    def.mode_count = modes;
    return def;
}

/// Beam-theory section of the board for bending through `depth` (thickness: flatwise; width: edgewise).
inline modal::BeamSection board_section(double depth)
{
    const double other = depth == k_board_thickness ? k_board_width : k_board_thickness;
    modal::BeamSection s;
    s.length = k_board_length;
    s.area = depth * other;
    s.second_moment = other * depth * depth * depth / 12.0;
    s.density = 450.0;
    s.young = 11e9;
    s.poisson = 0.3;
    s.shear_coefficient = modal::rectangle_shear_coefficient(0.3);
    return s;
}

// A soft sphere: radius 0.5 m, E 10 MPa, ν 0.3, ρ 1000 kg/m³.
inline ModalBasisDef sphere_def(int cells, int order = 2, int modes = 12)
{
    ModalBasisDef def = default_modal_basis_def();
    def.shape.radii = {0.5, 0.5, 0.5};
    def.density = 1000.0;
    def.young = 1e7;
    def.poisson = 0.3;
    def.lattice.cells = {cells, cells, cells};
    def.lattice.element_order = order;
    def.mode_count = modes;
    return def;
}

} // namespace supermodal::test
