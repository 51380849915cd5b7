// SPDX-License-Identifier: MIT
#include "fuzz/fuzz_case.h"

#include "supermodal/body.h"
#include "supermodal/modal.h"
#include "supermodal/scene.h"
#include "supermodal/world.h"

#include <algorithm>
#include <memory>
#include <string>

namespace supermodal::fuzz
{
namespace
{
// Enough steps to exercise every stage; few enough that a 60 s run sees ~10^5 inputs.
constexpr int k_steps = 8;
// Body-substeps per input: a big pile still takes at least one step (every stage runs), but the
// corpus's 100-body piles no longer take 8, which had cut the long run's rate to ~90 inputs/s.
constexpr long k_body_substep_budget = 8 * 32;
// Larger worlds would only measure how fast we step, not find loader bugs.
constexpr size_t k_max_bodies = 256;
// A modal basis on a 128³ lattice is a legitimate, minutes-long build: valid input, not a loader bug,
// but it would trip the 10 s per-input timeout. Larger models are parsed and checked, not built. The
// cap counts the whole scene's modal cells: one 8×2×4 board with 24 modes took 5.6 s alone (2.1 s at 8
// modes, 32×1×2), and a long run timed out on such an input at 238,570 inputs while builds
// ran beside it; 32 cells (the ball_on_board sample's lattice) take ≤ 2.3 s at 24 modes.
constexpr long k_max_modal_cells = 32;
constexpr int k_max_modes = 24;
// Every mode of the lattice ("type": "full") is a dense O(n³) solve: 64 cells of 20-node elements
// took seconds each under the sanitizers and slowed the long run to ~6 inputs/s while the corpus
// loaded. 8 cells keep it to milliseconds.
constexpr long k_max_full_cells = 8;
constexpr int k_max_cached_bases = 32;

bool cheap_to_build(const Scene& scene)
{
    long scene_cells = 0;
    for (const SceneBody& b : scene.bodies) {
        const ModalBodyDef& m = b.def.modal;
        if (!m.enabled)
            continue;
        // An automatic axis (0) counts as 8 cells, so a fully automatic lattice (counted 512 cells; an
        // auto body's refinement goes up to 3000 dofs) is not built: a ball's 4×4×4 auto lattice took 9 s
        // under the fuzz build's instrumentation (the sparse eigensolve), tripping the 10 s timeout.
        // The choice itself is unit-tested (tests/modal/auto_lattice_test.cpp).
        long cells = 1;
        for (int n : m.lattice)
            cells *= n == 0 ? 8 : n;
        scene_cells += cells;
        if (scene_cells > k_max_modal_cells || m.mode_count > k_max_modes ||
            (m.mode_count == k_all_modes && cells > k_max_full_cells))
            return false;
    }
    return true;
}

bool names_a_place(const Error& e)
{
    return e.where.empty() || e.where[0] == '/' || e.where.rfind("line ", 0) == 0;
}
} // namespace

Verdict run_scene_case(std::string_view text)
{
    Result<Scene> scene = parse_scene(text, "fuzz.json");
    if (!scene)
        return scene.error().what.empty() || !names_a_place(scene.error()) ? Verdict::BadError
                                                                           : Verdict::Rejected;
    if (scene->bodies.size() > k_max_bodies || !cheap_to_build(*scene))
        return Verdict::Skipped;
    // One basis cache for the whole run: most mutations of a modal scene leave its bodies' defs alone,
    // and rebuilding their bases was 83% of a ball_on_board mutation's time (2 s each under the fuzz
    // build; past the 10 s timeout on a loaded machine). Bases are keyed by their whole def, so sharing
    // changes no result. Emptied past 32 bases to bound memory.
    static const std::shared_ptr<ModalBasisCache> bases = std::make_shared<ModalBasisCache>();
    if (bases->size() > k_max_cached_bases)
        bases->clear();
    scene->world.modal_basis_cache = bases;
    Result<World> world = build_world(*scene);
    if (!world)
        return Verdict::Unbuilt;
    const long per_step = std::max<long>(1, long(scene->bodies.size()) * scene->world.substep_count);
    // One step of 5 bodies × 900 substeps (ball_on_board with "substeps" mutated) took 4.3–11 s under
    // the sanitizers on a loaded machine: built and checked, but not stepped.
    if (per_step > k_body_substep_budget)
        return Verdict::Skipped;
    // The tunnelling rule may add up to max_auto_substeps per step (a 2 m ball at dt = 0.4 s on the modal
    // board took 10 s for 8 steps under the fuzz build): the budget counts the substeps taken.
    long used = 0;
    for (int i = 0; i < k_steps && (i == 0 || used + per_step <= k_body_substep_budget); ++i) {
        const uint64_t extra_before = world->warnings().speculative_substeps;
        world->step();
        const auto extra = static_cast<long>(world->warnings().speculative_substeps - extra_before);
        used += long(scene->bodies.size()) * (scene->world.substep_count + extra);
    }
    (void)world->state_hash();
    return Verdict::Stepped;
}

} // namespace supermodal::fuzz
