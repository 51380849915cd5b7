// Fuzz target for engine/src/scene (libFuzzer): any bytes in, never a crash, hang or sanitizer report.
// A rejected input must carry an error that says where (a JSON pointer, "" for the document root, or
// "line L, column C" for syntax); an accepted one must build a world that steps to finite state.
#include "supermodal/body.h"
#include "supermodal/scene.h"
#include "supermodal/world.h"

#include <cstdint>
#include <cstdlib>
#include <string>
#include <string_view>

namespace sm = supermodal;

namespace {
// Enough steps to exercise every stage; few enough that a 60 s run sees ~10^5 inputs.
constexpr int k_steps = 8;
// Larger worlds would only measure how fast we step, not find loader bugs.
constexpr size_t k_max_bodies = 256;

bool names_a_place(const sm::Error& e)
{
    return e.where.empty() || e.where[0] == '/' || e.where.rfind("line ", 0) == 0;
}
} // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
    const std::string_view text(reinterpret_cast<const char*>(data), size);
    sm::Result<sm::Scene> scene = sm::parse_scene(text, "fuzz.json");
    if (!scene) {
        if (scene.error().what.empty() || !names_a_place(scene.error()))
            std::abort();
        return 0;
    }
    if (scene->bodies.size() > k_max_bodies)
        return 0;
    sm::Result<sm::World> world = sm::build_world(*scene);
    if (!world)
        return 0;
    for (int i = 0; i < k_steps; ++i)
        world->step();
    (void)world->state_hash();
    return 0;
}
