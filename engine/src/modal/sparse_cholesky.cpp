// SPDX-License-Identifier: MIT
// CHOLMOD behind SparseCholesky (see sparse_cholesky.h).
#include "modal/sparse_cholesky.h"

#include <algorithm>
#include <cholmod.h>
#include <cstring>
#include <limits>

namespace supermodal::modal
{

struct SparseCholesky::Impl {
    cholmod_common common{};
    cholmod_factor* factor = nullptr;
    // Solve workspaces, reused across solves (cholmod_solve2 grows them on first use).
    cholmod_dense* x = nullptr;
    cholmod_dense* y = nullptr;
    cholmod_dense* e = nullptr;
    cholmod_dense* b = nullptr;

    Impl()
    {
        cholmod_start(&common);
        common.print = 0; // errors come back as a status, never on stderr
        common.supernodal = CHOLMOD_SUPERNODAL;
        // Default orderings: AMD, and METIS when AMD's fill is high; the one with less fill is kept.
        // Both are deterministic, so the factor (and every mode) is the same on every run.
    }
    ~Impl()
    {
        cholmod_free_dense(&x, &common);
        cholmod_free_dense(&y, &common);
        cholmod_free_dense(&e, &common);
        cholmod_free_dense(&b, &common);
        cholmod_free_factor(&factor, &common);
        cholmod_finish(&common);
    }
};

SparseCholesky::SparseCholesky() : m_impl(std::make_unique<Impl>()) {}

SparseCholesky::~SparseCholesky() = default;

bool SparseCholesky::compute(const SparseMatrix& a)
{
    Impl& s = *m_impl;
    cholmod_free_factor(&s.factor, &s.common);
    cholmod_free_dense(&s.b, &s.common);
    m_rows = a.rows();
    if (!a.isCompressed() || a.rows() != a.cols())
        return false;
    // A view of Eigen's compressed columns: stype 1 reads the upper triangle only.
    cholmod_sparse view{};
    view.nrow = view.ncol = static_cast<size_t>(a.rows());
    view.nzmax = static_cast<size_t>(a.nonZeros());
    view.p = const_cast<int*>(a.outerIndexPtr());
    view.i = const_cast<int*>(a.innerIndexPtr());
    view.x = const_cast<double*>(a.valuePtr());
    view.stype = 1;
    view.itype = CHOLMOD_INT;
    view.xtype = CHOLMOD_REAL;
    view.dtype = CHOLMOD_DOUBLE;
    view.sorted = 1;
    view.packed = 1;
    s.factor = cholmod_analyze(&view, &s.common);
    if (s.factor == nullptr)
        return false;
    if (!cholmod_factorize(&view, s.factor, &s.common) || s.common.status != CHOLMOD_OK ||
        s.factor->minor < s.factor->n)
        return false;
    s.b = cholmod_allocate_dense(view.nrow, 1, view.nrow, CHOLMOD_REAL, &s.common);
    return s.b != nullptr;
}

void SparseCholesky::solve(const double* x, double* y) const
{
    Impl& s = *m_impl;
    const auto n = static_cast<size_t>(m_rows);
    std::memcpy(s.b->x, x, n * sizeof(double));
    if (!cholmod_solve2(CHOLMOD_A, s.factor, s.b, nullptr, &s.x, nullptr, &s.y, &s.e, &s.common) ||
        s.x == nullptr) { // out of memory: NaNs make the eigen solve report no convergence
        std::fill(y, y + n, std::numeric_limits<double>::quiet_NaN());
        return;
    }
    std::memcpy(y, s.x->x, n * sizeof(double));
}

double SparseCholesky::factor_nonzeros() const
{
    return m_impl->common.lnz;
}

} // namespace supermodal::modal
