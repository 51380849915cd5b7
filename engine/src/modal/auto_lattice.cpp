// SPDX-License-Identifier: MIT
#include "modal/auto_lattice.h"

#include "modal/lattice.h"

#include <algorithm>
#include <cmath>

namespace supermodal::modal
{
namespace
{

ModalBasisDef with_cells(ModalBasisDef def, const std::array<int, 3>& cells)
{
    def.lattice.cells = cells;
    return def;
}

void set_changes(LatticeChoice& choice, std::vector<double> changes)
{
    choice.frequency_changes = std::move(changes);
    choice.frequency_change = 0.0;
    for (const double c : choice.frequency_changes)
        choice.frequency_change = std::max(choice.frequency_change, std::isnan(c) ? 1.0 : c);
}

} // namespace

std::vector<double> frequency_changes(const ModalBasis& fine, const ModalBasis& coarse)
{
    // Both keep at least the modes asked for; either may keep more where its cut met a cluster of
    // repeated frequencies (eigen_solve.h), so only the modes both hold are compared.
    std::vector<double> out(std::min(fine.frequencies_hz.size(), coarse.frequencies_hz.size()), 1.0);
    for (size_t k = 0; k < out.size(); ++k) {
        const double f = fine.frequencies_hz[k];
        if (f > 0.0) // elastic modes are; a zero would leave the change at 1
            out[k] = std::abs(coarse.frequencies_hz[k] - f) / f;
    }
    return out;
}

Result<LatticeChoice> choose_lattice(ModalBasisCache& cache, const ModalBasisDef& def, double target,
                                     int max_dofs)
{
    Result<std::shared_ptr<const ModalBasis>> first = cache.get_or_build(def);
    if (!first)
        return first.error();
    LatticeChoice choice;
    choice.basis = *first;
    const std::array<int, 3> base = choice.basis->cells;
    const int order = def.lattice.element_order;
    // The default halved: a coarser lattice that may fail to hold the modes (too few dofs) or the body.
    std::array<int, 3> half{};
    for (int d = 0; d < 3; ++d)
        half[d] = std::max(order == 1 ? 2 : 1, (base[d] + 1) / 2); // rounded up: 3 cells halve to 2
    if (half != base)
        if (Result<std::shared_ptr<const ModalBasis>> coarse = cache.get_or_build(with_cells(def, half));
            coarse)
            set_changes(choice, frequency_changes(*choice.basis, **coarse));
    choice.met = choice.frequency_change >= 0.0 && choice.frequency_change <= target;
    std::array<int, 3> cells = base;
    while (!choice.met) {
        std::array<int, 3> finer{};
        for (int d = 0; d < 3; ++d)
            finer[d] = std::min(2 * cells[d], k_max_lattice_cells);
        if (finer == cells || lattice_dof_bound(finer, order) > max_dofs)
            break;
        Result<std::shared_ptr<const ModalBasis>> built = cache.get_or_build(with_cells(def, finer));
        if (!built)
            break;
        set_changes(choice, frequency_changes(**built, *choice.basis));
        choice.basis = *built;
        choice.met = choice.frequency_change <= target;
        cells = finer;
    }
    return choice;
}

} // namespace supermodal::modal
