// Tests for engine/src/modal/eigen_solve.cpp.
// Through the public build: the solver choice, its diagnostics and the frequencies it returns.
#include "modal/modal_scenes.h"
#include "supermodal/modal.h"

#include <algorithm>
#include <cmath>
#include <gtest/gtest.h>

namespace sm = supermodal;
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
    // The fill-reducing ordering (AMD or METIS) and the factorization are deterministic: two builds of
    // one def hand out the same bits, which the world's state hash relies on.
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
