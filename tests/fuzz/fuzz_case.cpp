// SPDX-License-Identifier: MIT
#include "fuzz/fuzz_case.h"

#include "supermodal/body.h"
#include "supermodal/scene.h"
#include "supermodal/world.h"

#include <string>

namespace supermodal::fuzz
{
namespace
{
// Enough steps to exercise every stage; few enough that a 60 s run sees ~10^5 inputs.
constexpr int k_steps = 8;
// Larger worlds would only measure how fast we step, not find loader bugs.
constexpr size_t k_max_bodies = 256;
// A modal basis on a 128³ lattice is a legitimate, minutes-long build: valid input, not a loader bug,
// but it would trip the 10 s per-input timeout. Larger models are parsed and checked, not built.
constexpr long k_max_modal_cells = 64;
constexpr int k_max_modes = 24;

bool cheap_to_build(const Scene& scene)
{
    for (const SceneBody& b : scene.bodies) {
        const ModalBodyDef& m = b.def.modal;
        if (!m.enabled)
            continue;
        long cells = 1; // an automatic axis (0) gets up to 8 cells
        for (int n : m.lattice)
            cells *= n == 0 ? 8 : n;
        if (cells > k_max_modal_cells || m.mode_count > k_max_modes)
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
    Result<World> world = build_world(*scene);
    if (!world)
        return Verdict::Unbuilt;
    for (int i = 0; i < k_steps; ++i)
        world->step();
    (void)world->state_hash();
    return Verdict::Stepped;
}

} // namespace supermodal::fuzz
