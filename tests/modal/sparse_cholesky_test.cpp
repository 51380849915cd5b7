// Tests for engine/src/modal/sparse_cholesky.cpp and supernodal.cpp: the supernodal factorization of
// K − σM for the shift-invert eigen solve.
#include "modal/assembly.h"
#include "modal/dissection.h"
#include "modal/modal_scenes.h"
#include "modal/sparse_cholesky.h"

#include <Eigen/Core>
#include <cstdint>
#include <cstring>
#include <gtest/gtest.h>

namespace modal = supermodal::modal;
namespace test = supermodal::test;

namespace
{

modal::LatticeModel sphere_model(int cells)
{
    supermodal::Result<modal::LatticeModel> m = modal::assemble_lattice_model(test::sphere_def(cells));
    EXPECT_TRUE(m);
    return m ? std::move(*m) : modal::LatticeModel{};
}

/// A fixed pseudo-random block (64-bit LCG), the same on every platform.
Eigen::MatrixXd random_block(Eigen::Index rows, Eigen::Index cols)
{
    Eigen::MatrixXd b(rows, cols);
    uint64_t x = 12345;
    for (Eigen::Index i = 0; i < b.size(); ++i) {
        x = x * 6364136223846793005ull + 1442695040888963407ull;
        b.data()[i] = static_cast<double>(x >> 11) * 0x1.0p-53 - 0.5;
    }
    return b;
}

/// Norm-wise backward error ‖AX − B‖ / (‖A‖ ‖X‖ + ‖B‖) (Frobenius norms).
double backward_error(const modal::SparseMatrix& a, const Eigen::MatrixXd& x, const Eigen::MatrixXd& b)
{
    return (a * x - b).norm() / (a.norm() * x.norm() + b.norm());
}

// The soft sphere's σ = −10⁻³ E/(ρℓ²) with ℓ = 1 m, as the eigen solve shifts it.
constexpr double k_sigma = -10.0;

} // namespace

TEST(SparseCholesky, SolvesTheShiftedLatticeToRoundOff)
{
    // Cholesky is backward stable: the computed X solves a nearby system, ‖ΔA‖ ≲ c·n·u·‖A‖ with
    // c of order one for a positive definite A. The dissection's largest supernode has a few hundred
    // columns, so n·u ≈ 10⁻¹³; 10⁻¹³ on the norm-wise backward error fails on any wrong entry of L.
    const modal::LatticeModel model = sphere_model(4);
    const modal::SparseMatrix a = model.stiffness - k_sigma * model.mass;
    modal::SparseCholesky c;
    ASSERT_TRUE(c.compute_shifted(model.stiffness, &model.mass, k_sigma, modal::lattice_dissection(model)));
    for (int cols : {1, 3, 4}) { // 4 goes through the four-column sweeps, others column by column
        const Eigen::MatrixXd b = random_block(a.rows(), cols);
        Eigen::MatrixXd x;
        ASSERT_TRUE(c.solve(b, x));
        EXPECT_LT(backward_error(a, x, b), 1e-13) << cols << " columns";
    }
    Eigen::VectorXd b = random_block(a.rows(), 1), x(a.rows());
    c.solve(b.data(), x.data());
    EXPECT_LT(backward_error(a, x, b), 1e-13);
}

TEST(SparseCholesky, OrderingsAgreeAndTheDissectionFillsNoMoreThanMetis)
{
    // The same matrix factored through the lattice dissection and through CHOLMOD's own choice (AMD,
    // then METIS where AMD fills much): the same solution to round-off (‖A⁻¹‖‖A‖ ≈ 10⁸ here bounds
    // the forward error by 10⁸·10⁻¹³), and a fill no larger than 2% above the graph partitioner's.
    const modal::LatticeModel model = sphere_model(6);
    const modal::SparseMatrix a = model.stiffness - k_sigma * model.mass;
    modal::SparseCholesky by_geometry, by_graph;
    ASSERT_TRUE(
        by_geometry.compute_shifted(model.stiffness, &model.mass, k_sigma, modal::lattice_dissection(model)));
    ASSERT_TRUE(by_graph.compute(a));
    const Eigen::MatrixXd b = random_block(a.rows(), 4);
    Eigen::MatrixXd x1, x2;
    ASSERT_TRUE(by_geometry.solve(b, x1));
    ASSERT_TRUE(by_graph.solve(b, x2));
    EXPECT_LT((x1 - x2).norm() / x2.norm(), 1e-5);
    EXPECT_LE(by_geometry.factor_nonzeros(), 1.02 * by_graph.factor_nonzeros());
}

TEST(SparseCholesky, RefusesAnIndefiniteMatrix)
{
    // σ far above the lowest elastic ω² (about 10⁵ s⁻² for the soft sphere): K − σM has negative
    // eigenvalues, so a pivot goes negative and the factorization must say so.
    const modal::LatticeModel model = sphere_model(3);
    modal::SparseCholesky c;
    EXPECT_FALSE(c.compute_shifted(model.stiffness, &model.mass, 1e9, modal::lattice_dissection(model)));
    Eigen::MatrixXd x;
    EXPECT_FALSE(c.solve(random_block(model.dof_count(), 4), x));
}

TEST(SparseCholesky, AMassPatternOutsideTheStiffnessIsSummedFirst)
{
    // A tridiagonal K and an M coupling the two ends (outside K's pattern): the factor must be of
    // the formed K − σM, not of K with M's stray entries dropped.
    const int n = 60;
    std::vector<Eigen::Triplet<double>> kt, mt;
    for (int i = 0; i < n; ++i) {
        kt.emplace_back(i, i, 2.0);
        if (i + 1 < n) {
            kt.emplace_back(i, i + 1, -1.0);
            kt.emplace_back(i + 1, i, -1.0);
        }
        mt.emplace_back(i, i, 1.0);
    }
    mt.emplace_back(0, n - 1, 0.5);
    mt.emplace_back(n - 1, 0, 0.5);
    modal::SparseMatrix k(n, n), m(n, n);
    k.setFromTriplets(kt.begin(), kt.end());
    m.setFromTriplets(mt.begin(), mt.end());
    const double sigma = -0.7;
    modal::SparseCholesky c;
    ASSERT_TRUE(c.compute_shifted(k, &m, sigma, {}));
    const Eigen::MatrixXd b = random_block(n, 4);
    Eigen::MatrixXd x;
    ASSERT_TRUE(c.solve(b, x));
    const modal::SparseMatrix a = k - sigma * m;
    EXPECT_LT(backward_error(a, x, b), 1e-14);
}

TEST(SparseCholesky, BitsDoNotDependOnTheCpuCacheSizes)
{
    // Eigen cuts a product's depth by the L1 size it reads from the CPU; the factorization keeps
    // every depth below the smallest cut, so the same build gives the same bits on any CPU. Here the
    // CPU is simulated by the cache sizes Eigen plans with (16 kB to 48 kB of L1, as x86-64 CPUs have).
    const modal::LatticeModel model = sphere_model(6);
    const Eigen::MatrixXd b = random_block(model.dof_count(), 4);
    const std::ptrdiff_t l1 = Eigen::l1CacheSize(), l2 = Eigen::l2CacheSize(), l3 = Eigen::l3CacheSize();
    Eigen::MatrixXd reference;
    for (const std::array<std::ptrdiff_t, 3>& sizes :
         {std::array<std::ptrdiff_t, 3>{32 << 10, 512 << 10, 16 << 20},
          std::array<std::ptrdiff_t, 3>{16 << 10, 256 << 10, 2 << 20},
          std::array<std::ptrdiff_t, 3>{48 << 10, 2 << 20, 32 << 20}}) {
        Eigen::setCpuCacheSizes(sizes[0], sizes[1], sizes[2]);
        modal::SparseCholesky c;
        Eigen::MatrixXd x;
        const bool ok =
            c.compute_shifted(model.stiffness, &model.mass, k_sigma, modal::lattice_dissection(model)) &&
            c.solve(b, x);
        Eigen::setCpuCacheSizes(l1, l2, l3);
        ASSERT_TRUE(ok);
        if (reference.size() == 0)
            reference = x;
        else
            EXPECT_EQ(std::memcmp(x.data(), reference.data(), sizeof(double) * x.size()), 0) << sizes[0];
    }
}
