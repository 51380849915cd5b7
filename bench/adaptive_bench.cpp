// SPDX-License-Identifier: MIT
// Adaptive modes (scene "dynamics": "auto", docs/modal.md "Adaptive modes"): CPU time per step of
// samples/ball_on_board.json over its first 0.3 s (the strike and the ringing) with the board rigid,
// modal with a fixed mode count, or auto at a 1 mm and a 0.3 mm budget. One iteration = 600 steps (CPU
// time, so the shared machine's other jobs count less).
#include "supermodal/scene.h"
#include "supermodal/world.h"

#include <benchmark/benchmark.h>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>

namespace sm = supermodal;

namespace
{

std::string with(std::string text, const std::string& from, const std::string& to)
{
    const size_t at = text.find(from);
    if (at == std::string::npos)
        throw std::runtime_error("samples/ball_on_board.json changed: " + from);
    return text.replace(at, from.size(), to);
}

sm::Scene board_scene(const std::string& dynamics, const std::string& budget)
{
    std::ifstream in(std::string(SM_SOURCE_DIR) + "/samples/ball_on_board.json");
    std::stringstream text;
    text << in.rdbuf();
    std::string json =
        with(text.str(), R"("dynamics": { "type": "modal", "modes": 8, "lattice": [16, 1, 2] })",
             "\"dynamics\": " + dynamics);
    json = with(json, R"("duration": 1.0 })",
                R"("duration": 1.0, "accuracy": {"displacement": )" + budget + "} }");
    sm::Result<sm::Scene> scene = sm::parse_scene(json);
    if (!scene)
        throw std::runtime_error(scene.error().message());
    return *scene;
}

void run(benchmark::State& state, const std::string& dynamics, const std::string& budget)
{
    const sm::Scene scene = board_scene(dynamics, budget);
    constexpr int k_steps = 600; // 0.3 s at 0.5 ms
    for (auto _ : state) {
        state.PauseTiming();
        sm::Result<sm::World> world = sm::build_world(scene); // the basis build is not timed
        state.ResumeTiming();
        for (int s = 0; s < k_steps; ++s)
            world->step();
        benchmark::DoNotOptimize(world->state_hash());
    }
    state.SetItemsProcessed(state.iterations() * k_steps); // items/s = steps per CPU second
}

const std::string k_lattice = R"(, "lattice": [16, 1, 2] })";

} // namespace

BENCHMARK_CAPTURE(run, rigid, R"({ "type": "rigid" })", "1e-3")->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(run, modal_1, R"({ "type": "modal", "modes": 1)" + k_lattice, "1e-3")
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(run, modal_3, R"({ "type": "modal", "modes": 3)" + k_lattice, "1e-3")
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(run, modal_16, R"({ "type": "modal", "modes": 16)" + k_lattice, "1e-3")
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(run, auto_1mm, R"({ "type": "auto", "modes": 16)" + k_lattice, "1e-3")
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(run, auto_0_3mm, R"({ "type": "auto", "modes": 16)" + k_lattice, "3e-4")
    ->Unit(benchmark::kMillisecond);
