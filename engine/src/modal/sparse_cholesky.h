// SPDX-License-Identifier: MIT
// Supernodal sparse Cholesky of a symmetric positive definite matrix, for the shift-invert solves of the
// modal eigen solve: the ordering (a given one or AMD, whichever fills less; CHOLMOD's AMD/METIS choice
// when none is given) and the supernodes from CHOLMOD's symbolic analysis, then the numeric factor and
// the solves on dense Eigen kernels (supernodal.h), on the calling thread, with the same rounding on
// every CPU for one build.
#pragma once

#include "modal/assembly.h"

#include <memory>
#include <span>

namespace supermodal::modal
{

class SparseCholesky
{
  public:
    SparseCholesky();
    ~SparseCholesky();
    SparseCholesky(const SparseCholesky&) = delete;
    SparseCholesky& operator=(const SparseCholesky&) = delete;

    /// Factors A = LLᵀ. A is symmetric with both triangles stored; only the upper one is read. False
    /// when A is not numerically positive definite (or out of memory): solve must not be called then.
    [[nodiscard]] bool compute(const SparseMatrix& a) { return compute_shifted(a, nullptr, 0.0, {}); }
    /// Factors A = K − σM without forming it where M's pattern lies inside K's (else the sum is formed);
    /// both symmetric, both triangles stored. `order`, when given (entry k: the row eliminated k-th),
    /// is tried against AMD and the one with less fill kept; else AMD, and METIS where AMD leaves
    /// much fill.
    [[nodiscard]] bool compute_shifted(const SparseMatrix& k, const SparseMatrix* m, double sigma,
                                       std::span<const int> order);
    /// y ← A⁻¹ x for one vector of length rows().
    void solve(const double* x, double* y) const;
    /// Y ← A⁻¹ X for the columns of X (rows() × b) at once: one pass over the factor for all of them
    /// (dense triangular solves and products on the supernodes), instead of b passes. False when out
    /// of memory.
    [[nodiscard]] bool solve(Eigen::Ref<const Eigen::MatrixXd> x, Eigen::MatrixXd& y) const;
    [[nodiscard]] Eigen::Index rows() const { return m_rows; }
    /// Entries of L [-]: the fill the ordering left.
    [[nodiscard]] double factor_nonzeros() const;

  private:
    struct Impl;
    std::unique_ptr<Impl> m_impl;
    Eigen::Index m_rows = 0;
    bool m_factored = false;
};

} // namespace supermodal::modal
