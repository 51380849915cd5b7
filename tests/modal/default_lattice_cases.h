// SPDX-License-Identifier: MIT
// The bodies the default lattice is held to (docs/modal.md, "Default lattice"): one per family, with the
// six lowest elastic frequencies of a converged lattice of the same solid. Shared by
// bench/default_lattice_table.cpp (the table, and the slow check that recomputes the references) and
// tests/modal/default_lattice_test.cpp (the default within 2% of each reference).
#pragma once

#include "supermodal/modal.h"

#include <array>
#include <span>
#include <string>
#include <vector>

namespace supermodal::test
{

/// Elastic frequencies compared per body: the lowest six.
inline constexpr int k_compared_modes = 6;
/// The default lattice's promise: each of the six within this of the converged solid [-].
inline constexpr double k_default_lattice_tolerance = 0.02;
/// A lattice counts as converged when one more refinement moves no compared frequency more than this [-].
inline constexpr double k_converged_change = 0.001;

/// One family's body and its stored reference.
struct LatticeCase {
    std::string name;
    ShapeDef shape;
    /// Converged frequencies [Hz] (ascending; E = 10 MPa, ν = 0.3, ρ = 1000 kg/m³) and the lattice and
    /// cut-cell subdivisions that gave them (`default_lattice_table --reference NAME SUB [START]` prints
    /// them; `--check` recomputes them).
    std::array<double, k_compared_modes> reference_hz{};
    std::array<int, 3> reference_cells{};
    int reference_subdivisions = 0;
    /// How far the reference's frequencies still moved from the lattice before it [-]: at most
    /// k_converged_change, unless the next refinement would pass k_max_lattice_dofs.
    double reference_change = 1.0;
    /// Where the refinement started: the default lattice, or these cells when given.
    std::array<int, 3> reference_start{};
};

/// Every family, in table order.
[[nodiscard]] std::span<const LatticeCase> lattice_cases();
/// The case called name, or null.
[[nodiscard]] const LatticeCase* find_lattice_case(const std::string& name);

/// The basis def of a case: default material (E 10 MPa, ν 0.3, ρ 1000), six modes, the default
/// (automatic) lattice unless cells are given.
[[nodiscard]] ModalBasisDef lattice_case_def(const LatticeCase& c, const std::array<int, 3>& cells = {},
                                             int subdivisions = 4);

/// Largest |f − reference| / reference over the compared modes [-].
[[nodiscard]] double max_relative_error(std::span<const double> hz, std::span<const double> reference_hz);

} // namespace supermodal::test
