// SPDX-License-Identifier: MIT
// Supernodal sparse Cholesky of a symmetric positive definite matrix (CHOLMOD), for the shift-invert
// solves of the modal eigen solve: a fill-reducing ordering (AMD, or METIS nested dissection when AMD
// leaves much fill), then dense BLAS kernels on the supernodes.
#pragma once

#include "modal/assembly.h"

#include <memory>

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
    [[nodiscard]] bool compute(const SparseMatrix& a);
    /// y ← A⁻¹ x for one vector of length rows().
    void solve(const double* x, double* y) const;
    /// Y ← A⁻¹ X for the columns of X (rows() × b) at once: one pass over the factor for all of them
    /// (dense triangular solves and products on the supernodes), instead of b passes. False when out
    /// of memory.
    [[nodiscard]] bool solve(const Eigen::MatrixXd& x, Eigen::MatrixXd& y) const;
    [[nodiscard]] Eigen::Index rows() const { return m_rows; }
    /// Entries of L [-]: the fill the ordering left.
    [[nodiscard]] double factor_nonzeros() const;

  private:
    struct Impl;
    std::unique_ptr<Impl> m_impl;
    Eigen::Index m_rows = 0;
};

} // namespace supermodal::modal
