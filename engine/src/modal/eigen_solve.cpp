// SPDX-License-Identifier: MIT
// Lowest elastic modes of a free lattice (see eigen_solve.h).
//
// Dense path: Eigen's generalized solver on M φ = ν (K − σM) φ, ν = 1/(ω² − σ). The roles are swapped
// on purpose: K − σM (σ < 0) is well conditioned and positive definite, while M may be nearly singular
// where a node only touches a sliver of material, and a Cholesky of M would smear that over the lowest
// modes.
// Sparse path: a block Krylov iteration (solve_sparse_block) with a supernodal Cholesky of K − σM
// (sparse_cholesky.h; ordered by the lattice's nested dissection), positive definite for σ < 0: each
// step solves with 4 right-hand sides at once, so the factor is read once per 4 vectors. When it
// gives up, and on request as the reference, Spectra's single-vector shift-invert Lanczos (below).
// The six rigid modes are known in closed form, so
// they are deflated (projected out of every Krylov vector) rather than found: Lanczos sees one vector
// per distinct eigenvalue in exact arithmetic, and an exactly six-fold one would converge slowly and
// unreliably. For the same reason it can miss copies of repeated elastic frequencies, so a
// confirmation run looks for the lowest modes left once everything found is deflated too: a missed
// copy is the largest eigenvalue of that deflated operator, which Lanczos finds first. Modes it finds
// below the cut are added and the search repeats. (A Sturm count, the inertia of an LDLᵀ of K − μM,
// would check the same; no supernodal factorization here gives the inertia of an indefinite matrix,
// and a simplicial one costs several times the whole solve on 3-D lattices.)
// Every path keeps a cluster of repeated frequencies whole where the cut would split it (whole_clusters).
// Both paths end with a Rayleigh–Ritz step on K and M themselves: it makes the kept vectors exactly
// M-orthonormal and K-orthogonal (including inside clusters of repeated frequencies) and gives the
// eigenvalues as Rayleigh quotients, free of the cancellation in 1/ν + σ.
#include "modal/eigen_solve.h"

#include "modal/dissection.h"
#include "modal/sparse_cholesky.h"
#include "modal/spectrum.h"

#include <Eigen/Dense>
#include <Spectra/MatOp/SparseSymMatProd.h>
#include <Spectra/SymGEigsShiftSolver.h>
#include <algorithm>
#include <cmath>
#include <cstdint>

namespace supermodal::modal
{
namespace
{

using Dense = Eigen::MatrixXd;
using Vector = Eigen::VectorXd;

constexpr double k_shift_fraction = 1e-3;    // σ = −k · E/(ρℓ²): safely below every elastic ω²
constexpr double k_cluster_tolerance = 1e-6; // relative gap below which two ω² count as repeated
constexpr int k_max_rounds = 4;
constexpr int k_confirm_count = 3; // modes a confirmation run asks for: one more than the largest
                                   // multiplicity a lattice's cubic symmetry allows
constexpr double k_lanczos_tolerance = 1e-10;
// Block Krylov: 4 vectors a block, one more than the largest multiplicity (see k_confirm_count).
// Wider blocks converge in fewer steps but more vectors: on a 12³ lattice of 20-node cells 4 took 24
// steps (96 solves), 8 took 18 (144), and the time goes with the solves.
constexpr int k_block_size = 4;
constexpr Eigen::Index k_block_max_dim = 240; // basis and its M image: 96 MB at 25,000 dofs

/// M-orthonormalises the columns of v: v ← v L⁻ᵀ with vᵀMv = LLᵀ.
bool m_orthonormalize(const SparseMatrix& m, Dense& v)
{
    const Dense g = v.transpose() * (m * v);
    const Eigen::LLT<Dense> llt(0.5 * (g + g.transpose()));
    if (llt.info() != Eigen::Success)
        return false;
    Dense vt = v.transpose();
    llt.matrixL().solveInPlace(vt);
    v = vt.transpose();
    return true;
}

/// Rayleigh–Ritz on span(v): ascending Ritz values, Ritz vectors M-orthonormal and K-orthogonal.
bool rayleigh_ritz(const SparseMatrix& k, const SparseMatrix& m, const Dense& v, Vector& out_values,
                   Dense& out_vectors)
{
    Dense kr = v.transpose() * (k * v);
    Dense mr = v.transpose() * (m * v);
    kr = 0.5 * (kr + kr.transpose()).eval();
    mr = 0.5 * (mr + mr.transpose()).eval();
    const Eigen::GeneralizedSelfAdjointEigenSolver<Dense> es(kr, mr);
    if (es.info() != Eigen::Success)
        return false;
    out_values = es.eigenvalues();
    out_vectors = v * es.eigenvectors();
    return true;
}

/// (K − σM)⁻¹ x (from its Cholesky factor, made once per solve) followed by the M-orthogonal
/// projection away from the deflated vectors D (columns M-orthonormal): y ← y − D (MD)ᵀ y. Spectra's
/// ShiftInvert mode applies M first.
class DeflatedShiftInvert
{
  public:
    using Scalar = double;

    DeflatedShiftInvert(const SparseCholesky& cholesky, const Dense& deflate, const Dense& m_deflate)
        : m_cholesky(cholesky), m_deflate(deflate), m_m_deflate(m_deflate)
    {
    }
    [[nodiscard]] Eigen::Index rows() const { return m_cholesky.rows(); }
    [[nodiscard]] Eigen::Index cols() const { return m_cholesky.rows(); }
    void set_shift(double /*sigma*/) {} // the factor already holds the shift
    void perform_op(const double* x_in, double* y_out) const
    {
        m_cholesky.solve(x_in, y_out);
        Eigen::Map<Vector> y(y_out, rows());
        y -= m_deflate * (m_m_deflate.transpose() * y);
    }

  private:
    const SparseCholesky& m_cholesky;
    const Dense& m_deflate;
    const Dense& m_m_deflate;
};

/// A fixed pseudo-random start vector (64-bit LCG), the same on every platform.
Vector start_vector(Eigen::Index n)
{
    Vector v(n);
    uint64_t x = 0x9E3779B97F4A7C15ull;
    for (Eigen::Index i = 0; i < n; ++i) {
        x = x * 6364136223846793005ull + 1442695040888963407ull;
        v[i] = static_cast<double>(x >> 11) * 0x1.0p-53 - 0.5;
    }
    return v;
}

/// The `nev` largest eigenvalues of the deflated shift-invert operator, as M-orthonormal vectors.
/// Spectra throws on nev/ncv out of range: the caller guarantees nev + 1 < n − deflate.cols().
bool run_lanczos(const SparseCholesky& cholesky, const SparseMatrix& m, const Dense& deflate, int nev,
                 double sigma, Dense& out_vectors)
{
    using Solver = Spectra::SymGEigsShiftSolver<DeflatedShiftInvert, Spectra::SparseSymMatProd<double>,
                                                Spectra::GEigsMode::ShiftInvert>;
    const Dense m_deflate = m * deflate;
    DeflatedShiftInvert op(cholesky, deflate, m_deflate);
    Spectra::SparseSymMatProd<double> bop(m);
    const auto free_dim = static_cast<int>(m.rows() - deflate.cols());
    const int ncv = std::min(free_dim, std::max(2 * nev + 1, nev + 20));
    Solver geigs(op, bop, nev, ncv, sigma);
    Vector v0 = start_vector(m.rows());
    v0 -= deflate * (m_deflate.transpose() * v0);
    geigs.init(v0.data());
    geigs.compute(Spectra::SortRule::LargestMagn, 1000, k_lanczos_tolerance, Spectra::SortRule::SmallestAlge);
    if (geigs.info() != Spectra::CompInfo::Successful)
        return false;
    out_vectors = geigs.eigenvectors();
    return out_vectors.allFinite();
}

/// Two ω² of one cluster of repeated frequencies (relative gap within k_cluster_tolerance).
bool same_frequency(double a, double b)
{
    return std::abs(a - b) <= k_cluster_tolerance * std::max(std::abs(a), std::abs(b));
}

/// How many elastic modes to keep: `mode_count`, extended over a cluster of repeated frequencies that
/// the cut would split, up to `max_kept`. Which members of a split cluster a solver keeps is arbitrary
/// (a sphere's three-fold modes on a cubic lattice), and different picks respond differently to the
/// same load. `omega2(j)` is the j-th lowest elastic ω² and is read for j < `known` only.
template <class Omega2> int whole_clusters(int mode_count, int max_kept, int known, const Omega2& omega2)
{
    int kept = mode_count;
    while (kept < known && kept < max_kept && same_frequency(omega2(kept), omega2(kept - 1)))
        ++kept;
    return kept;
}

/// A cut μ between the wanted-th value (0-based) and the next distinct one above it.
double cut_above(const Vector& values, int wanted)
{
    const double top = values[wanted];
    for (Eigen::Index j = wanted + 1; j < values.size(); ++j)
        if (values[j] > top * (1.0 + k_cluster_tolerance))
            return 0.5 * (values[j - 1] + values[j]);
    return values[values.size() - 1] * (1.0 + k_cluster_tolerance);
}

/// Dense: the six rigid vectors, the `mode_count` lowest elastic ones (more where the cut would split a
/// cluster, whole_clusters) and the next one when there is one; not yet orthonormalised.
bool solve_dense(const LatticeModel& model, int mode_count, int max_kept, double sigma, Dense& out_vectors)
{
    const Dense k(model.stiffness), m(model.mass);
    const Dense a = k - sigma * m;
    const Eigen::GeneralizedSelfAdjointEigenSolver<Dense> es(m, a); // ascending ν = 1/(ω² − σ)
    if (es.info() != Eigen::Success)
        return false;
    const auto n = static_cast<int>(k.rows());
    const auto omega2 = [&](int j) { return 1.0 / es.eigenvalues()[n - 7 - j] + sigma; };
    const int kept = whole_clusters(mode_count, max_kept, n - 6, omega2);
    out_vectors = es.eigenvectors().rightCols(std::min(n, 6 + kept + 1));
    return out_vectors.allFinite();
}

/// Sparse: the rigid vectors followed by at least `wanted` elastic ones, confirmed complete below the
/// cut unless out_checked comes back false.
bool solve_sparse(const LatticeModel& model, const SparseCholesky& cholesky, int wanted, int max_kept,
                  double sigma, Dense& out_vectors, int& out_rounds, bool& out_checked)
{
    const SparseMatrix& k = model.stiffness;
    const SparseMatrix& m = model.mass;
    Dense rigid = rigid_body_vectors(model);
    if (!m_orthonormalize(m, rigid))
        return false;
    Dense found(k.rows(), 0);
    Vector values;
    double cut = 0.0;
    int nev = wanted + 1; // one spare: Lanczos converges the outermost wanted values last
    out_checked = false;
    out_rounds = 0;
    for (;;) {
        Dense deflate(k.rows(), rigid.cols() + found.cols());
        deflate << rigid, found;
        Dense fresh;
        if (nev + 1 >= k.rows() - deflate.cols() || !run_lanczos(cholesky, m, deflate, nev, sigma, fresh)) {
            if (out_rounds == 0)
                return false;
            break; // no room or no convergence for a confirmation: keep what was found, unchecked
        }
        if (out_rounds > 0) { // a confirmation run: done when the lowest mode left lies above the cut
            Vector left;
            Dense unused;
            if (!rayleigh_ritz(k, m, fresh, left, unused))
                return false;
            if (left[0] > cut) {
                out_checked = true;
                // A cluster kept whole may take every mode found: the lowest one left is the next above.
                const auto known = static_cast<int>(values.size());
                if (whole_clusters(wanted - 1, max_kept, known, [&](int j) { return values[j]; }) == known) {
                    found.conservativeResize(Eigen::NoChange, found.cols() + 1);
                    found.rightCols(1) = unused.col(0);
                }
                break;
            }
            if (out_rounds == k_max_rounds)
                break;
        }
        ++out_rounds; // missed copies of repeated eigenvalues (or the first search): add them
        Dense merged(k.rows(), found.cols() + fresh.cols());
        merged << found, fresh;
        if (!rayleigh_ritz(k, m, merged, values, found))
            return false;
        cut = cut_above(values, wanted - 1);
        nev = k_confirm_count;
    }
    out_vectors.resize(k.rows(), rigid.cols() + found.cols());
    out_vectors << rigid, found;
    return true;
}

/// M-orthonormalises a block in place by Cholesky QR, twice for accuracy: y_in = y_out R with R
/// upper triangular (returned in r), and my (= M y on entry) updated alongside. False when the block
/// is numerically rank deficient.
bool orthonormalize_block(Dense& y, Dense& my, Dense& r)
{
    r = Dense::Identity(y.cols(), y.cols());
    for (int pass = 0; pass < 2; ++pass) {
        const Dense g = y.transpose() * my;
        const Eigen::LLT<Dense> llt(0.5 * (g + g.transpose()));
        if (llt.info() != Eigen::Success)
            return false;
        const Dense u = llt.matrixU();
        if (u.diagonal().minCoeff() <= 1e-10 * u.diagonal().maxCoeff())
            return false;
        u.triangularView<Eigen::Upper>().solveInPlace<Eigen::OnTheRight>(y);
        u.triangularView<Eigen::Upper>().solveInPlace<Eigen::OnTheRight>(my);
        r = (u * r).eval();
    }
    return true;
}

/// A fixed pseudo-random start block: start_vector's sequence continued over the columns.
Dense start_block(Eigen::Index n, int columns)
{
    Dense v(n, columns);
    uint64_t x = 0x9E3779B97F4A7C15ull;
    for (Eigen::Index i = 0; i < v.size(); ++i) {
        x = x * 6364136223846793005ull + 1442695040888963407ull;
        v.data()[i] = static_cast<double>(x >> 11) * 0x1.0p-53 - 0.5;
    }
    return v;
}

/// Sparse, block Krylov: the rigid vectors followed by the `mode_count` lowest elastic Ritz vectors (more
/// where the cut would split a cluster, up to `max_kept`) and the next one.
/// The Krylov space of T = P (K − σM)⁻¹ M (P: M-orthogonal projection away from the rigid modes)
/// grows by a block of b vectors per step, each step one solve with b right-hand sides. The basis V
/// is kept M-orthonormal (block Gram–Schmidt, twice), so T V = V H + Y R Eᵀ with H the projected
/// operator, Y the next block and R its triangular factor; a Ritz pair (ν, s) of H has the residual
/// ‖T V s − ν V s‖_M = ‖R s_last‖, read without touching the lattice. Done when those largest ν
/// (lowest ω²) have residuals below k_lanczos_tolerance·ν. A block of b vectors finds up to b copies
/// of a repeated eigenvalue, so no confirmation run is needed while every cluster is smaller than b.
bool solve_sparse_block(const LatticeModel& model, const SparseCholesky& cholesky, int mode_count,
                        int max_kept, double sigma, Dense& out_vectors, bool& out_checked)
{
    const SparseMatrix& k = model.stiffness;
    const SparseMatrix& m = model.mass;
    const Eigen::Index n = k.rows();
    const int b = k_block_size;
    Dense rigid = rigid_body_vectors(model);
    if (!m_orthonormalize(m, rigid))
        return false;
    const Dense m_rigid = m * rigid;
    // In-place products (noalias) throughout the loop: each n × b temporary would be fresh pages.
    const auto project = [&](Dense& y) { y.noalias() -= rigid * (m_rigid.transpose() * y).eval(); };
    const Eigen::Index max_dim = std::min<Eigen::Index>(n - rigid.cols() - b, k_block_max_dim) / b * b;
    if (max_dim < mode_count + 1 + b)
        return false;

    Dense basis(n, max_dim), m_basis(n, max_dim);
    Dense h = Dense::Zero(max_dim, max_dim);
    Dense y = start_block(n, b);
    project(y);
    Dense my = m * y;
    Dense r;
    if (!orthonormalize_block(y, my, r))
        return false;
    basis.leftCols(b) = y;
    m_basis.leftCols(b) = my;
    Eigen::Index dim = b;
    out_checked = false;
    for (;;) {
        if (!cholesky.solve(m_basis.middleCols(dim - b, b), y))
            return false;
        project(y);
        for (int pass = 0; pass < 2; ++pass) { // classical Gram–Schmidt, twice
            const Dense c = m_basis.leftCols(dim).transpose() * y;
            y.noalias() -= basis.leftCols(dim) * c;
            h.block(0, dim - b, dim, b) += c;
        }
        my.noalias() = m * y;
        if (!orthonormalize_block(y, my, r))
            return false;

        const Dense hs = 0.5 * (h.topLeftCorner(dim, dim) + h.topLeftCorner(dim, dim).transpose());
        const Eigen::SelfAdjointEigenSolver<Dense> es(hs); // ascending ν: the wanted ones last
        // Converged pairs from the top (lowest ω² first); the set is done when the `mode_count` lowest,
        // extended over a cluster the cut would split, and the next one above them have converged.
        int converged = 0;
        while (converged < dim && converged <= max_kept) {
            const Eigen::Index j = dim - 1 - converged;
            const double nu = es.eigenvalues()[j];
            if (!(nu > 0.0) || (r * es.eigenvectors().col(j).tail(b)).norm() > k_lanczos_tolerance * nu)
                break;
            ++converged;
        }
        const auto omega2 = [&](int i) { return 1.0 / es.eigenvalues()[dim - 1 - i] + sigma; };
        const int kept =
            converged > mode_count ? whole_clusters(mode_count, max_kept, converged, omega2) : converged;
        if (kept < converged) {
            const int wanted = kept + 1;
            const Dense s = es.eigenvectors().rightCols(wanted).rowwise().reverse();
            out_vectors.resize(n, rigid.cols() + wanted);
            out_vectors << rigid, basis.leftCols(dim) * s;
            // Largest run of equal eigenvalues found: the block must be wider to have caught them all.
            int run = 1, largest = 1;
            for (int i = 1; i < wanted; ++i) {
                run = same_frequency(omega2(i), omega2(i - 1)) ? run + 1 : 1;
                largest = std::max(largest, run);
            }
            // A run as wide as the block may have more copies than the block caught (a sphere's
            // five-fold quadrupole modes): the Lanczos path with its confirmation run decides then.
            out_checked = largest < b;
            return out_checked && out_vectors.allFinite();
        }
        if (dim + b > max_dim)
            return false;
        h.block(dim, dim - b, b, b) = r;
        basis.middleCols(dim, b) = y;
        m_basis.middleCols(dim, b) = my;
        dim += b;
    }
}

} // namespace

Result<ModeSolution> solve_modes(const LatticeModel& model, int mode_count, ModalSolver solver,
                                 double eigenvalue_scale, SparseMethod method, ClusterCut cut)
{
    const int n = model.dof_count();
    if (mode_count > n - 6)
        return Error{"", "/lattice",
                     "the lattice has only " + std::to_string(n - 6) +
                         " elastic degrees of freedom, fewer than the modes asked for (" +
                         std::to_string(mode_count) + "): refine it or ask for fewer modes"};
    const double sigma = -k_shift_fraction * eigenvalue_scale;
    const int max_kept = cut == ClusterCut::KeepWhole ? std::max(mode_count, k_max_modes) : mode_count;
    ModeSolution out;
    out.sparse = solver == ModalSolver::Sparse || (solver == ModalSolver::Auto && n > k_dense_dof_limit);
    // Lanczos needs room beyond the wanted vectors; tiny lattices always go dense.
    out.sparse = out.sparse && mode_count + 10 < n - 6;
    Dense vectors;
    bool solved = false;
    // One factorization of K − σM serves the block iteration and, where that gives up, the reference.
    SparseCholesky cholesky;
    const bool factored = out.sparse && cholesky.compute_shifted(model.stiffness, &model.mass, sigma,
                                                                 lattice_dissection(model));
    if (!out.sparse) {
        solved = solve_dense(model, mode_count, max_kept, sigma, vectors);
    } else if (factored && method == SparseMethod::Block) {
        solved =
            solve_sparse_block(model, cholesky, mode_count, max_kept, sigma, vectors, out.inertia_checked);
        out.block = solved;
        out.rounds = 1;
    }
    if (factored && !solved) // the reference path, also when the block iteration gives up
        solved = solve_sparse(model, cholesky, mode_count + 1, max_kept, sigma, vectors, out.rounds,
                              out.inertia_checked);
    Vector values;
    Dense ritz;
    if (!solved || !rayleigh_ritz(model.stiffness, model.mass, vectors, values, ritz) ||
        values.size() < 6 + mode_count)
        return Error{"", "/lattice", "the eigensolver did not converge"};

    const RigidSplit split =
        split_rigid_modes(std::span<const double>(values.data(), values.size()), eigenvalue_scale);
    if (!split.ok)
        return Error{"", "/lattice", split.problem};
    for (int i = 0; i < 6; ++i)
        out.rigid_eigenvalues[i] = values[i];
    const int kept = whole_clusters(mode_count, max_kept, static_cast<int>(values.size()) - 6,
                                    [&](int j) { return values[6 + j]; });
    out.eigenvalues = values.segment(6, kept);
    out.vectors = ritz.middleCols(6, kept);
    if (values.size() > 6 + kept)
        out.next_eigenvalue = values[6 + kept];
    return out;
}

} // namespace supermodal::modal
