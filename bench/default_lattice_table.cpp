// SPDX-License-Identifier: MIT
// The default lattice against converged ones (docs/modal.md, "Default lattice"): for each family of
// tests/modal/default_lattice_cases.h, the lattice a body gets when it names none, its cost and the
// largest error of its six lowest elastic frequencies against the stored converged reference. Not a
// Google Benchmark: a table, and the slow check that recomputes the references.
//
// Usage: default_lattice_table [NAME...]        table rows (markdown), one process per family
//        default_lattice_table --reference NAME [SUB [NX NY NZ]]  refine from the default lattice (or
//                                                 the one given) until converged; prints each lattice
//                                                 and the reference to store
//        default_lattice_table --check [NAME...]  recompute the references and compare with the stored
//        default_lattice_table --lattice NAME NX NY NZ [SUB]  one lattice's frequencies
// Exit status: 0, 1 when a check or a row fails its tolerance, 2 on bad arguments.
#include "modal/default_lattice_cases.h"
#include "modal/lattice.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>
#include <vector>

namespace sm = supermodal;
namespace test = supermodal::test;

namespace
{

double cpu_seconds()
{
    rusage u{};
    getrusage(RUSAGE_SELF, &u);
    return static_cast<double>(u.ru_utime.tv_sec + u.ru_stime.tv_sec) +
           1e-6 * static_cast<double>(u.ru_utime.tv_usec + u.ru_stime.tv_usec);
}

struct Built {
    sm::ModalBasis basis;
    double cpu_s = 0.0, wall_s = 0.0;
};

bool build(const sm::ModalBasisDef& def, Built& out)
{
    const double cpu0 = cpu_seconds();
    const auto wall0 = std::chrono::steady_clock::now();
    sm::Result<sm::ModalBasis> b = sm::build_modal_basis(def);
    out.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
    out.cpu_s = cpu_seconds() - cpu0;
    if (!b) {
        std::fprintf(stderr, "build failed: %s\n", b.error().message().c_str());
        return false;
    }
    out.basis = std::move(*b);
    return true;
}

std::string cells_text(const std::array<int, 3>& c)
{
    return std::to_string(c[0]) + "x" + std::to_string(c[1]) + "x" + std::to_string(c[2]);
}

/// The next lattice of a refinement: every axis × 1.5, rounded up.
std::array<int, 3> refined(const std::array<int, 3>& c)
{
    std::array<int, 3> out{};
    for (int d = 0; d < 3; ++d)
        out[d] = std::min(sm::k_max_lattice_cells, (3 * c[d] + 1) / 2);
    return out;
}

double max_change(const std::vector<double>& a, const std::vector<double>& b)
{
    return test::max_relative_error(a, b);
}

void print_hz(const std::vector<double>& hz)
{
    for (const double f : hz)
        std::printf(" %.6g", f);
}

struct Reference {
    std::array<int, 3> cells{};
    std::vector<double> hz;
    double change = 1.0; ///< Largest move of a compared frequency from the lattice before [-].
};

/// Refines from the default lattice (× 1.5 per axis) until no compared frequency moves more than
/// k_converged_change, or the next lattice would pass k_max_lattice_dofs (the finest one, and how much
/// it still moved, is the reference then), printing each step.
bool compute_reference(const test::LatticeCase& c, int subdivisions, Reference& out,
                       const std::array<int, 3>& start = {})
{
    Built b;
    if (!build(test::lattice_case_def(c, start, subdivisions), b))
        return false;
    std::array<int, 3> cells = b.basis.cells;
    std::vector<double> previous = b.basis.frequencies_hz;
    std::printf("%s %s dofs %d cpu %.2f s:", c.name.c_str(), cells_text(cells).c_str(),
                b.basis.diagnostics.dof_count, b.cpu_s);
    print_hz(previous);
    std::printf("\n");
    for (;;) {
        const std::array<int, 3> next = refined(cells);
        if (next == cells || sm::modal::lattice_dof_bound(next, 2) > sm::k_max_lattice_dofs)
            return !out.hz.empty();
        if (!build(test::lattice_case_def(c, next, subdivisions), b))
            return false;
        const double change = max_change(previous, b.basis.frequencies_hz);
        std::printf("%s %s dofs %d cpu %.2f s change %.4f%%:", c.name.c_str(), cells_text(next).c_str(),
                    b.basis.diagnostics.dof_count, b.cpu_s, 100.0 * change);
        print_hz(b.basis.frequencies_hz);
        std::printf("\n");
        std::fflush(stdout);
        cells = next;
        previous = b.basis.frequencies_hz;
        out = {cells, previous, change};
        if (change <= test::k_converged_change)
            return true;
    }
}

int reference_command(const test::LatticeCase& c, int subdivisions, const std::array<int, 3>& start)
{
    Reference r;
    if (!compute_reference(c, subdivisions, r, start))
        return 1;
    std::printf("reference %s: {", c.name.c_str());
    for (size_t k = 0; k < r.hz.size(); ++k)
        std::printf("%s%.9g", k == 0 ? "" : ", ", r.hz[k]);
    std::printf("}, {%d, %d, %d}, %d, %.3g\n", r.cells[0], r.cells[1], r.cells[2], subdivisions, r.change);
    return 0;
}

/// Recomputes a stored reference: the same refinement must end on the same lattice with the same
/// frequencies (to 1e-6: the solver's convergence, not the build's determinism, is what varies).
bool check_case(const test::LatticeCase& c)
{
    Reference r;
    if (!compute_reference(c, c.reference_subdivisions, r, c.reference_start))
        return false;
    const double diff = test::max_relative_error(r.hz, c.reference_hz);
    const bool ok =
        r.cells == c.reference_cells && diff <= 1e-6 &&
        std::abs(r.change - c.reference_change) <= 0.01 * c.reference_change; // stored to 3 digits
    std::printf("check %s: lattice %s (stored %s), max difference %.2e: %s\n", c.name.c_str(),
                cells_text(r.cells).c_str(), cells_text(c.reference_cells).c_str(), diff,
                ok ? "ok" : "FAILED");
    return ok;
}

/// One table row, built in this process (its peak resident set is the build's).
bool row(const test::LatticeCase& c)
{
    Built b;
    if (!build(test::lattice_case_def(c), b))
        return false;
    const double err = test::max_relative_error(b.basis.frequencies_hz, c.reference_hz);
    std::printf("| %s | %s | %d | %.3f | %.3f | %.2f%% | %s (%d sub-cells) |", c.name.c_str(),
                cells_text(b.basis.cells).c_str(), b.basis.diagnostics.dof_count, b.cpu_s, b.wall_s,
                100.0 * err, cells_text(c.reference_cells).c_str(), c.reference_subdivisions);
    std::fflush(stdout);
    return err <= test::k_default_lattice_tolerance;
}

/// Runs row() in a child process and appends its peak resident set [MB].
bool row_in_child(const test::LatticeCase& c)
{
    const pid_t pid = fork();
    if (pid == 0)
        _exit(row(c) ? 0 : 1);
    int status = 0;
    rusage u{};
    if (pid < 0 || wait4(pid, &status, 0, &u) != pid)
        return false;
    std::printf(" %.0f |\n", static_cast<double>(u.ru_maxrss) / 1024.0);
    std::fflush(stdout);
    return WIFEXITED(status) && WEXITSTATUS(status) == 0;
}

const test::LatticeCase* case_or_complain(const char* name)
{
    const test::LatticeCase* c = test::find_lattice_case(name);
    if (c == nullptr)
        std::fprintf(stderr, "default_lattice_table: no family named '%s'\n", name);
    return c;
}

} // namespace

int main(int argc, char** argv)
{
    const std::vector<std::string> args(argv + 1, argv + argc);
    if (!args.empty() && args[0] == "--reference" &&
        (args.size() == 2 || args.size() == 3 || args.size() == 6)) {
        const test::LatticeCase* c = case_or_complain(argv[2]);
        std::array<int, 3> start{};
        if (args.size() == 6)
            start = {std::atoi(argv[4]), std::atoi(argv[5]), std::atoi(argv[6])};
        return c == nullptr ? 2 : reference_command(*c, args.size() >= 3 ? std::atoi(argv[3]) : 4, start);
    }
    if (!args.empty() && args[0] == "--lattice" && (args.size() == 5 || args.size() == 6)) {
        const test::LatticeCase* c = case_or_complain(argv[2]);
        if (c == nullptr)
            return 2;
        Built b;
        const std::array<int, 3> cells{std::atoi(argv[3]), std::atoi(argv[4]), std::atoi(argv[5])};
        if (!build(test::lattice_case_def(*c, cells, args.size() == 6 ? std::atoi(argv[6]) : 4), b))
            return 1;
        std::printf("%s %s dofs %d cpu %.2f s wall %.2f s:", c->name.c_str(),
                    cells_text(b.basis.cells).c_str(), b.basis.diagnostics.dof_count, b.cpu_s, b.wall_s);
        print_hz(b.basis.frequencies_hz);
        std::printf("\n");
        return 0;
    }
    const bool check = !args.empty() && args[0] == "--check";
    std::vector<const test::LatticeCase*> chosen;
    for (size_t i = check ? 1 : 0; i < args.size(); ++i) {
        const test::LatticeCase* c = case_or_complain(args[i].c_str());
        if (c == nullptr)
            return 2;
        chosen.push_back(c);
    }
    if (chosen.empty())
        for (const test::LatticeCase& c : test::lattice_cases())
            chosen.push_back(&c);
    bool ok = true;
    if (!check)
        std::printf(
            "| family | default lattice | dofs | build CPU [s] | build wall [s] | max error, 6 modes | "
            "reference lattice | peak memory [MB] |\n|---|---|---|---|---|---|---|---|\n");
    std::fflush(stdout); // before fork(): the children would print it again
    for (const test::LatticeCase* c : chosen)
        ok = (check ? check_case(*c) : row_in_child(*c)) && ok;
    return ok ? 0 : 1;
}
