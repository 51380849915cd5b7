// SPDX-License-Identifier: MIT
// `supermodal modes`: the vibration modes of one modal body of a scene, without stepping it.
#include "cli_common.h"
#include "supermodal/modal.h"

#include <algorithm>
#include <cstdio>

namespace supermodal::cli
{

namespace
{

nlohmann::json modes_json(const ModesOptions& opt, const ModalBasis& basis, int count)
{
    const ModalDiagnostics& d = basis.diagnostics;
    nlohmann::json frequencies = nlohmann::json::array(), kinds = nlohmann::json::array(),
                   residuals = nlohmann::json::array();
    for (int k = 0; k < count; ++k) {
        frequencies.push_back(basis.frequencies_hz[k]);
        kinds.push_back(mode_kind_name(basis.kinds[k]));
        residuals.push_back(d.mode_residuals.empty() ? 0.0 : d.mode_residuals[k]);
    }
    return {{"scene", opt.scene},
            {"body", opt.body},
            {"frequencies_hz", frequencies},
            {"kinds", kinds},
            {"residuals", residuals},
            {"lattice",
             {{"cells", basis.cells},
              {"element_order", basis.element_order},
              {"nodes", basis.node_positions.size()},
              {"dofs", d.dof_count},
              {"kept_cells", d.kept_cell_count},
              {"cut_cells", d.cut_cell_count}}},
            {"mass", basis.mass},
            {"solver", d.sparse_solver ? "sparse" : "dense"},
            {"rigid_ratio", d.rigid_ratio},
            {"mass_orthonormality_error", d.mass_orthonormality_error},
            {"build_seconds", d.assembly_seconds + d.eigen_seconds},
            {"assembly_seconds", d.assembly_seconds},
            {"eigen_seconds", d.eigen_seconds}};
}

void print_modes(const ModesOptions& opt, const ModalBasis& basis, int count)
{
    const ModalDiagnostics& d = basis.diagnostics;
    std::printf("%s: body %s, lattice %dx%dx%d (%d dofs), built in %.3f s (%s solver)\n", opt.scene.c_str(),
                opt.body.c_str(), basis.cells[0], basis.cells[1], basis.cells[2], d.dof_count,
                d.assembly_seconds + d.eigen_seconds, d.sparse_solver ? "sparse" : "dense");
    for (int k = 0; k < count; ++k)
        std::printf("  mode %2d  %12.4f Hz  %-8s residual %.1e\n", k + 1, basis.frequencies_hz[k],
                    mode_kind_name(basis.kinds[k]), d.mode_residuals.empty() ? 0.0 : d.mode_residuals[k]);
}

} // namespace

int modes_command(const ModesOptions& opt)
{
    Result<Scene> scene = load_scene(opt.scene);
    if (!scene) {
        print_error(scene.error().message());
        return k_exit_bad_input;
    }
    Result<World> built = build_world(*scene); // builds every modal basis (the build time below)
    if (!built) {
        print_error(built.error().message());
        return k_exit_bad_input;
    }
    const World& world = *built;
    const Entity body = find_body(world, opt.body);
    if (body.is_null()) {
        print_error(opt.scene + ": no body named \"" + opt.body + "\"");
        return k_exit_bad_input;
    }
    const ModalBasis* basis = body_modal_basis(world, body);
    if (basis == nullptr) {
        print_error(opt.scene + ": body \"" + opt.body +
                    "\" is rigid; give it \"dynamics\": {\"type\": \"modal\"} to see its modes");
        return k_exit_bad_input;
    }
    const int count = opt.count > 0 ? std::min(opt.count, basis->mode_count) : basis->mode_count;
    if (opt.json)
        std::printf("%s\n", json_text(modes_json(opt, *basis, count)).c_str());
    else
        print_modes(opt, *basis, count);
    return k_exit_ok;
}

} // namespace supermodal::cli
