// Tests for engine/src/modal/eigen_solve.cpp.
// Through the public build: the solver choice, its diagnostics and the frequencies it returns.
#include "modal/assembly.h"
#include "modal/eigen_solve.h"
#include "modal/modal_scenes.h"
#include "supermodal/modal.h"

#include <Eigen/SVD>
#include <algorithm>
#include <cmath>
#include <gtest/gtest.h>

namespace sm = supermodal;
namespace modal = supermodal::modal;
namespace test = supermodal::test;

namespace
{
sm::ModalBasis build_with(sm::ModalBasisDef def, sm::ModalSolver solver)
{
    def.solver = solver;
    sm::Result<sm::ModalBasis> b = sm::build_modal_basis(def);
    EXPECT_TRUE(b) << b.error().message();
    return b ? std::move(*b) : sm::ModalBasis{};
}

/// Two eigenvalues of one run of repeated frequencies (relative gap below 1e-6).
bool same_frequency(double x, double y)
{
    return std::abs(x - y) <= 1e-6 * std::abs(y);
}

/// Sizes of the runs of equal frequencies (relative gap below 1e-6) in the first `count` modes.
std::vector<int> clusters(const sm::ModalBasis& b, int count)
{
    std::vector<int> sizes;
    for (int k = 0; k < count; ++k) {
        if (k > 0 && b.frequencies_hz[k] - b.frequencies_hz[k - 1] <= 1e-6 * b.frequencies_hz[k])
            ++sizes.back();
        else
            sizes.push_back(1);
    }
    return sizes;
}
} // namespace

TEST(ModalEigenSolve, DenseAndSparseAgreeOnTheBoard)
{
    const sm::ModalBasisDef def = test::board_def({8, 1, 1}, 10);
    const sm::ModalBasis dense = build_with(def, sm::ModalSolver::Dense);
    const sm::ModalBasis sparse = build_with(def, sm::ModalSolver::Sparse);
    ASSERT_EQ(dense.mode_count, 10);
    ASSERT_EQ(sparse.mode_count, 10);
    EXPECT_FALSE(dense.diagnostics.sparse_solver);
    EXPECT_TRUE(sparse.diagnostics.sparse_solver);
    EXPECT_TRUE(sparse.diagnostics.inertia_checked);
    EXPECT_EQ(sparse.diagnostics.solver_rounds, 1);
    for (int k = 0; k < 10; ++k)
        EXPECT_NEAR(sparse.frequencies_hz[k] / dense.frequencies_hz[k], 1.0, 1e-9) << k;
    // The same modes up to sign: compare tip displacements.
    for (int k = 0; k < 10; ++k) {
        std::vector<double> q(10, 0.0);
        q[k] = 1.0;
        const sm::Vec3 a = sm::modal_displacement(dense, sm::Vec3{0.5, 0.019, 0.0445}, q);
        const sm::Vec3 b = sm::modal_displacement(sparse, sm::Vec3{0.5, 0.019, 0.0445}, q);
        const double s = sm::dot(a, b) < 0.0 ? -1.0 : 1.0;
        EXPECT_LT(sm::length(a - s * b), 1e-6 * (sm::length(a) + 1e-3)) << k;
    }
}

TEST(ModalEigenSolve, RepeatedFrequenciesAreAllFound)
{
    // A sphere on a cubic lattice: each five-fold mode of the continuum splits into a pair and a
    // triple. Lanczos can miss copies of a repeated eigenvalue; the Sturm count must catch any miss,
    // and the sparse path must return the same multiplicities as the dense one.
    const sm::ModalBasisDef def = test::sphere_def(4, 1, 12); // 8-node cells, ~350 dofs
    const sm::ModalBasis dense = build_with(def, sm::ModalSolver::Dense);
    const sm::ModalBasis sparse = build_with(def, sm::ModalSolver::Sparse);
    EXPECT_TRUE(sparse.diagnostics.inertia_checked);
    for (int k = 0; k < 12; ++k)
        EXPECT_NEAR(sparse.frequencies_hz[k] / dense.frequencies_hz[k], 1.0, 1e-8) << k;
    const std::vector<int> c = clusters(dense, 10);
    EXPECT_EQ(c, clusters(sparse, 10));
    EXPECT_GE(*std::max_element(c.begin(), c.end()), 3);
    EXPECT_LT(dense.diagnostics.mass_orthonormality_error, 1e-9);
    EXPECT_LT(sparse.diagnostics.mass_orthonormality_error, 1e-9);
}

TEST(ModalEigenSolve, CholeskyPathMatchesDenseOnACube)
{
    // A rounded cube on a 2³ lattice of 20-node cells (243 dofs): its cubic symmetry gives two- and
    // three-fold frequencies, the case where Lanczos misses copies and the confirmation run must add
    // them. The dense generalized solver is the reference: both solve the same discrete problem, the
    // sparse one to a Lanczos tolerance of 1e-10 on 1/(ω² − σ), and both end with a Rayleigh–Ritz
    // step, so eigenvalue errors are of the order of the squared residual; 1e-9 relative leaves room
    // for round-off in the dense reduction and still fails on any missed or misplaced mode.
    sm::ModalBasisDef def = sm::default_modal_basis_def();
    def.shape.epsilon1 = def.shape.epsilon2 = 0.1;
    def.lattice.cells = {2, 2, 2};
    def.mode_count = 12;
    const sm::ModalBasis dense = build_with(def, sm::ModalSolver::Dense);
    const sm::ModalBasis sparse = build_with(def, sm::ModalSolver::Sparse);
    ASSERT_TRUE(sparse.diagnostics.sparse_solver);
    EXPECT_TRUE(sparse.diagnostics.inertia_checked);
    for (int k = 0; k < 12; ++k)
        EXPECT_NEAR(sparse.frequencies_hz[k] / dense.frequencies_hz[k], 1.0, 1e-9) << k;
    const std::vector<int> c = clusters(dense, 11);
    EXPECT_EQ(c, clusters(sparse, 11));
    EXPECT_GE(*std::max_element(c.begin(), c.end()), 3);
    EXPECT_LT(sparse.diagnostics.mass_orthonormality_error, 1e-9);
}

TEST(ModalEigenSolve, SparseBuildsAreBitIdentical)
{
    // The fill-reducing ordering (the lattice dissection, or AMD) and the factorization are deterministic:
    // two builds of one def hand out the same bits, which the world's state hash relies on.
    const sm::ModalBasisDef def = test::sphere_def(4, 2, 12);
    const sm::ModalBasis a = build_with(def, sm::ModalSolver::Sparse);
    const sm::ModalBasis b = build_with(def, sm::ModalSolver::Sparse);
    ASSERT_TRUE(a.diagnostics.sparse_solver);
    EXPECT_EQ(a.frequencies_hz, b.frequencies_hz);
    EXPECT_EQ(a.mode_shapes, b.mode_shapes);
}

TEST(ModalEigenSolve, AutoPicksDenseForSmallLatticesAndSparseForLarge)
{
    EXPECT_FALSE(build_with(test::board_def({4, 1, 1}, 2), sm::ModalSolver::Auto).diagnostics.sparse_solver);
    const sm::ModalBasis big = build_with(test::board_def({16, 1, 1}, 2), sm::ModalSolver::Auto);
    EXPECT_GT(big.diagnostics.dof_count, sm::k_dense_dof_limit);
    EXPECT_TRUE(big.diagnostics.sparse_solver);
}

TEST(ModalEigenSolve, TinyLatticesFallBackToDense)
{
    // Lanczos needs room beyond the wanted vectors; asking for 25 of 30 elastic modes goes dense.
    sm::ModalBasisDef def = test::board_def({2, 1, 1}, 25);
    def.lattice.element_order = 1;
    const sm::ModalBasis b = build_with(def, sm::ModalSolver::Sparse);
    EXPECT_FALSE(b.diagnostics.sparse_solver);
    EXPECT_EQ(b.mode_count, 25);
}

TEST(ModalEigenSolve, BlockIterationMatchesLanczosOnAMidSizeCube)
{
    // The default sparse path (block Krylov, 4 vectors a step) against the single-vector Lanczos with
    // confirmation runs, on a rounded cube of 4³ 20-node cells (1275 dofs) whose cubic symmetry gives
    // two- and three-fold frequencies. Both converge every Ritz pair to ‖Tx − νx‖_M ≤ 1e-10·ν for the
    // same T = (K − σM)⁻¹M and end with a Rayleigh–Ritz step on K and M, so their eigenvalues differ
    // by the squared residual over the gap plus round-off (measured: 3e-15 relative at most); 1e-10
    // leaves room and still fails on a missed or misplaced mode, whose neighbours lie at least 1e-2
    // apart here. Mode shapes are compared as subspaces, one per run of equal frequencies (within a
    // run any basis is as good): the largest principal angle in the M inner product is the vector
    // error, about residual / relative gap ≈ 1e-10 / 1e-2 (measured: sin θ ≤ 5e-8, the round-off
    // floor of √(1 − cos²θ)); 1e-6 leaves room and still fails on any wrong vector.
    sm::ModalBasisDef def = sm::default_modal_basis_def();
    def.shape.epsilon1 = def.shape.epsilon2 = 0.1;
    def.lattice.cells = {4, 4, 4};
    def.lattice.element_order = 2;
    const int modes = 12;
    sm::Result<modal::LatticeModel> model = modal::assemble_lattice_model(def);
    ASSERT_TRUE(model) << model.error().message();
    ASSERT_EQ(model->dof_count(), 1275);
    const double scale = def.young / def.density; // E/(ρℓ²) with ℓ = 1 m: it only sets the shift
    sm::Result<modal::ModeSolution> block =
        modal::solve_modes(*model, modes, sm::ModalSolver::Sparse, scale, modal::SparseMethod::Block);
    sm::Result<modal::ModeSolution> lanczos =
        modal::solve_modes(*model, modes, sm::ModalSolver::Sparse, scale, modal::SparseMethod::Lanczos);
    ASSERT_TRUE(block) << block.error().message();
    ASSERT_TRUE(lanczos) << lanczos.error().message();
    EXPECT_TRUE(block->sparse);
    EXPECT_TRUE(block->block);
    EXPECT_FALSE(lanczos->block);
    EXPECT_TRUE(block->inertia_checked);
    EXPECT_TRUE(lanczos->inertia_checked);
    for (int k = 0; k < modes; ++k)
        EXPECT_NEAR(block->eigenvalues[k] / lanczos->eigenvalues[k], 1.0, 1e-10) << k;

    // Both keep every cluster of repeated frequencies whole, so they keep the same count and every run
    // of equal frequencies is a whole eigenspace, the same subspace in either.
    ASSERT_EQ(block->eigenvalues.size(), lanczos->eigenvalues.size());
    const auto kept = static_cast<int>(lanczos->eigenvalues.size());
    ASSERT_GE(kept, modes);
    EXPECT_FALSE(same_frequency(lanczos->next_eigenvalue, lanczos->eigenvalues[kept - 1]));
    EXPECT_FALSE(same_frequency(block->next_eigenvalue, block->eigenvalues[kept - 1]));
    const Eigen::MatrixXd& a = lanczos->vectors;
    const Eigen::MatrixXd& b = block->vectors;
    const Eigen::MatrixXd mb = model->mass * b;
    int runs = 0, largest = 0;
    for (int first = 0; first < kept;) {
        int last = first;
        while (last + 1 < kept && same_frequency(lanczos->eigenvalues[last + 1], lanczos->eigenvalues[first]))
            ++last;
        const int width = last - first + 1;
        const Eigen::MatrixXd cosines = a.middleCols(first, width).transpose() * mb.middleCols(first, width);
        const Eigen::JacobiSVD<Eigen::MatrixXd> svd(cosines);
        const double c = std::min(1.0, svd.singularValues().minCoeff());
        EXPECT_LT(std::sqrt(std::max(0.0, 1.0 - c * c)), 1e-6) << "modes " << first << ".." << last;
        ++runs;
        largest = std::max(largest, width);
        first = last + 1;
    }
    EXPECT_GE(largest, 3); // the test covers a three-fold frequency
    EXPECT_GE(runs, 5);
}

namespace
{

// A soft ball of radius 0.3 m on 3³ cells (624 dofs): its low modes come in runs of 1, 2 and 3 equal
// frequencies (a sphere's five-fold ones split by the lattice's cubic symmetry), and the dense solver
// still checks it quickly.
sm::ModalBasisDef small_ball_def()
{
    sm::ModalBasisDef def = sm::default_modal_basis_def();
    def.shape.radii = {0.3, 0.3, 0.3};
    def.young = 2e5;
    def.lattice.cells = {3, 3, 3};
    return def;
}

// The eigenvalue scale of small_ball_def(), E/(ρ·r²) [1/s²].
double small_ball_scale()
{
    const sm::ModalBasisDef def = small_ball_def();
    return def.young / (def.density * 0.36);
}

} // namespace

TEST(ModalEigenSolve, TheCutNeverSplitsAClusterOfRepeatedFrequencies)
{
    // A ball on a cubic lattice has two- and three-fold frequencies (a sphere's five-fold ones split by
    // the lattice's cubic symmetry). Asking for modes up to the middle of such a run must keep the whole
    // run on every path: which members of a split run a solver keeps is arbitrary, and different picks
    // respond differently to the same load (a soft ball dropped on the ground rang at 2 cm/s after 3 s
    // with one solver's pick, 8 mm/s with the whole run). The run is found on the dense spectrum; the
    // sparse paths match it within 1e-9 in ω² and 1e-6 in subspace angle, as in the tests above. 3³ cells
    // (624 dofs) keep the dense reference quick.
    sm::Result<modal::LatticeModel> model = modal::assemble_lattice_model(small_ball_def());
    ASSERT_TRUE(model) << model.error().message();
    ASSERT_GT(model->dof_count(), sm::k_dense_dof_limit); // Auto would take the sparse path: room for it
    const double scale = small_ball_scale();
    const sm::Result<modal::ModeSolution> all = modal::solve_modes(*model, 24, sm::ModalSolver::Dense, scale);
    ASSERT_TRUE(all) << all.error().message();
    // The first run of two or more equal frequencies past the first mode, ending below mode 24.
    int first = 1, last = 1;
    for (; first < 23; first = last + 1) {
        last = first;
        while (last + 1 < 24 && same_frequency(all->eigenvalues[last + 1], all->eigenvalues[first]))
            ++last;
        if (last > first && last < 23)
            break;
    }
    ASSERT_GT(last, first) << "no cluster of repeated frequencies below mode 24";
    const int asked = first + 1; // the cut falls right after the run's first member
    const Eigen::MatrixXd m_reference = model->mass * all->vectors.middleCols(first, last - first + 1);
    struct Path {
        sm::ModalSolver solver;
        modal::SparseMethod method;
        const char* name;
    };
    for (const Path& p : {Path{sm::ModalSolver::Dense, modal::SparseMethod::Block, "dense"},
                          Path{sm::ModalSolver::Sparse, modal::SparseMethod::Block, "block"},
                          Path{sm::ModalSolver::Sparse, modal::SparseMethod::Lanczos, "Lanczos"}}) {
        const sm::Result<modal::ModeSolution> s =
            modal::solve_modes(*model, asked, p.solver, scale, p.method);
        ASSERT_TRUE(s) << p.name << ": " << s.error().message();
        EXPECT_EQ(s->sparse, p.solver == sm::ModalSolver::Sparse) << p.name;
        ASSERT_EQ(s->eigenvalues.size(), last + 1) << p.name;
        EXPECT_GT(s->next_eigenvalue, all->eigenvalues[last] * (1.0 + 1e-6)) << p.name;
        for (int k = 0; k <= last; ++k)
            EXPECT_NEAR(s->eigenvalues[k] / all->eigenvalues[k], 1.0, 1e-9) << p.name << " mode " << k;
        const Eigen::MatrixXd cosines =
            s->vectors.middleCols(first, last - first + 1).transpose() * m_reference;
        const Eigen::JacobiSVD<Eigen::MatrixXd> svd(cosines);
        const double c = std::min(1.0, svd.singularValues().minCoeff());
        EXPECT_LT(std::sqrt(std::max(0.0, 1.0 - c * c)), 1e-6) << p.name;
    }

    // Through the public build: the soft ball of the world tests (5³ cells, 12 modes asked) keeps 13, its
    // three-fold run from mode 11 on whole, and says no cluster was split.
    sm::ModalBasisDef ball = sm::default_modal_basis_def();
    ball.shape.radii = {0.3, 0.3, 0.3};
    ball.young = 2e5;
    const sm::ModalBasis b = build_with(ball, sm::ModalSolver::Auto);
    EXPECT_TRUE(b.diagnostics.sparse_solver);
    EXPECT_TRUE(b.diagnostics.inertia_checked);
    EXPECT_FALSE(b.diagnostics.splits_degenerate_cluster);
    ASSERT_EQ(b.mode_count, 13);
    EXPECT_EQ(clusters(b, 13).back(), 3);

    // Asked for exactly (a moulded basis, here with every node left in place): 12 modes, the run split.
    const sm::Result<modal::ModeSolution> exact = modal::solve_modes(
        *model, asked, sm::ModalSolver::Sparse, scale, modal::SparseMethod::Block, modal::ClusterCut::Exact);
    ASSERT_TRUE(exact) << exact.error().message();
    EXPECT_EQ(exact->eigenvalues.size(), asked);
    ball.rest_offsets.assign(b.node_positions.size(), sm::Vec3{0, 0, 0});
    const sm::ModalBasis moulded = build_with(ball, sm::ModalSolver::Auto);
    EXPECT_EQ(moulded.mode_count, 12);
    EXPECT_TRUE(moulded.diagnostics.splits_degenerate_cluster);
}

TEST(ModalEigenSolve, BlockPathKeepsTheDenseSetForEveryModeCountOnABall)
{
    // The default sparse path has no confirmation run: it relies on the block (4 vectors) catching every
    // copy of a frequency repeated up to 3 times, and on the cut never splitting a run. Checked against
    // the dense solver (every eigenpair) for each count from 1 to 30 on the ball of 3³ cells (624 dofs),
    // whose 30 lowest modes come in runs of 1, 2 and 3: the same number of modes, the same frequencies
    // within 1e-9 (the dense/sparse agreement above), and the block set accepted, not the fallback.
    sm::Result<modal::LatticeModel> model = modal::assemble_lattice_model(small_ball_def());
    ASSERT_TRUE(model) << model.error().message();
    const double scale = small_ball_scale();
    const sm::Result<modal::ModeSolution> all = modal::solve_modes(*model, 40, sm::ModalSolver::Dense, scale);
    ASSERT_TRUE(all) << all.error().message();
    const Eigen::VectorXd& reference = all->eigenvalues;
    for (int asked = 1; asked <= 30; ++asked) {
        int expected = asked; // the asked count, extended over a run the cut would split
        while (same_frequency(reference[expected], reference[expected - 1]))
            ++expected;
        const sm::Result<modal::ModeSolution> block =
            modal::solve_modes(*model, asked, sm::ModalSolver::Sparse, scale, modal::SparseMethod::Block);
        ASSERT_TRUE(block) << asked;
        EXPECT_TRUE(block->block) << asked;
        EXPECT_TRUE(block->inertia_checked) << asked;
        ASSERT_EQ(block->eigenvalues.size(), expected) << asked;
        for (int k = 0; k < expected; ++k)
            EXPECT_NEAR(block->eigenvalues[k] / reference[k], 1.0, 1e-9) << asked << " mode " << k;
        EXPECT_NEAR(block->next_eigenvalue / reference[expected], 1.0, 1e-9) << asked;
    }
}
