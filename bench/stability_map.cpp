// SPDX-License-Identifier: MIT
// Stability map at the extremes (docs/stability.md): sweeps 2-D slices of the grid ε × aspect ×
// mass ratio × dt/limit × penalty frequency × impact speed (and a modal slice) and prints one CSV row
// per cell (tests/stability/stability_cells.h says what each scene is and what is measured). Not a
// Google Benchmark: bench/stability_report.py turns the CSV into heat maps and docs/stability.md tables.
//
// Usage: stability_map [SLICE...]   (slices: eps_aspect mass_dt freq_speed modal_dt modal_exact_dt;
//                                     default all)
//        stability_map --trace SCENE EPS ASPECT MASS_RATIO DT_RATIO FREQ SPEED SECONDS
//        (one cell, SCENE 0 drop, 1 stack, 2 impact, 3 modal_drop; per-step lines on stderr)
#include "stability/stability_cells.h"

#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

namespace st = supermodal::stability;

namespace
{

const std::vector<double> k_epsilons{0.01, 0.03, 0.1, 0.3, 0.5, 1.0, 1.5, 2.0, 2.5, 3.0, 4.0};
const std::vector<double> k_aspects{1, 2, 5, 10, 30, 100, 300, 1000};
const std::vector<double> k_mass_ratios{1e-6, 1e-4, 1e-2, 1, 1e2, 1e4, 1e6};
const std::vector<double> k_dt_ratios{0.1, 0.2, 0.5, 1, 2, 5, 10};
const std::vector<double> k_frequencies{1, 3, 10, 30, 50, 100, 300, 1000};
const std::vector<double> k_speeds{0.01, 0.1, 1, 3, 10, 30, 100, 300, 1000};
const std::vector<double> k_modal_epsilons{0.1, 0.3, 0.5, 1.0, 2.0, 3.0};
const std::vector<double> k_modal_dt_ratios{0.1, 0.3, 0.5, 0.9, 1.1, 2, 5, 10};

void emit(const std::string& slice, const st::CellDef& d)
{
    const st::CellResult r = st::run_cell(d);
    std::printf("%s\n", st::csv_row(slice, d, r).c_str());
    std::fflush(stdout);
}

bool wanted(const std::vector<std::string>& slices, const std::string& name)
{
    if (slices.empty())
        return true;
    for (const std::string& s : slices)
        if (s == name)
            return true;
    return false;
}

} // namespace

int main(int argc, char** argv)
{
    if (argc == 10 &&
        std::string(argv[1]) == "--trace") { // SM_EXACT=1: exact modal integrator; SM_SOFT=1: soft solver
        const auto num = [&](int i) { return std::strtod(argv[i], nullptr); };
        const st::CellDef d{.scene = static_cast<st::Scene>(std::atoi(argv[2])),
                            .epsilon = num(3),
                            .aspect = num(4),
                            .mass_ratio = num(5),
                            .dt_ratio = num(6),
                            .frequency_hz = num(7),
                            .speed = num(8),
                            .seconds = num(9),
                            .exact_modal = std::getenv("SM_EXACT") != nullptr,
                            .solver = std::getenv("SM_SOFT") != nullptr ? supermodal::ContactSolver::Soft
                                                                        : supermodal::ContactSolver::Penalty,
                            .trace = stderr};
        std::printf("%s\n%s\n", st::csv_header().c_str(), st::csv_row("trace", d, st::run_cell(d)).c_str());
        return 0;
    }
    const std::vector<std::string> slices(argv + 1, argv + argc);
    std::printf("%s\n", st::csv_header().c_str());
    if (wanted(slices, "eps_aspect"))
        for (const double e : k_epsilons)
            for (const double a : k_aspects)
                emit("eps_aspect", {.scene = st::Scene::Drop, .epsilon = e, .aspect = a, .seconds = 1.0});
    if (wanted(slices, "mass_dt"))
        for (const double m : k_mass_ratios)
            for (const double r : k_dt_ratios)
                emit("mass_dt", {.scene = st::Scene::Stack, .mass_ratio = m, .dt_ratio = r, .seconds = 1.0});
    if (wanted(slices, "freq_speed"))
        for (const double f : k_frequencies)
            for (const double v : k_speeds)
                emit("freq_speed",
                     {.scene = st::Scene::Impact, .frequency_hz = f, .speed = v, .seconds = 0.5});
    if (wanted(slices, "modal_dt"))
        for (const double e : k_modal_epsilons)
            for (const double r : k_modal_dt_ratios)
                emit("modal_dt",
                     {.scene = st::Scene::ModalDrop, .epsilon = e, .dt_ratio = r, .seconds = 0.5});
    if (wanted(slices, "modal_exact_dt")) // the same drop with the exact modal integrator
        for (const double e : k_modal_epsilons)
            for (const double r : k_modal_dt_ratios)
                emit("modal_exact_dt", {.scene = st::Scene::ModalDrop,
                                        .epsilon = e,
                                        .dt_ratio = r,
                                        .seconds = 0.5,
                                        .exact_modal = true});
    return 0;
}
