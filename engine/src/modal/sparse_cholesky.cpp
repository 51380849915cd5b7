// SPDX-License-Identifier: MIT
// CHOLMOD behind SparseCholesky (see sparse_cholesky.h).
#include "modal/sparse_cholesky.h"

#include <algorithm>
#include <cholmod.h>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <mutex>
#include <sys/mman.h>

namespace supermodal::modal
{

namespace
{

constexpr size_t k_huge_page = size_t{2} << 20; // bytes

/// CHOLMOD's allocations, with large blocks (the factor, above all) on 2 MB transparent huge pages
/// where the kernel allows them on request: the factor is written once right after it is allocated,
/// and touching it 4 kB page by page costs about as much as computing it (page faults in a VM).
void* cholmod_block_alloc(size_t bytes)
{
    if (bytes < 4 * k_huge_page)
        return std::malloc(bytes);
    void* p = std::aligned_alloc(k_huge_page, (bytes + k_huge_page - 1) / k_huge_page * k_huge_page);
    if (p != nullptr)
        madvise(p, bytes, MADV_HUGEPAGE); // advice only: a refusal changes nothing but speed
    return p;
}

void* cholmod_block_calloc(size_t count, size_t size)
{
    if (count != 0 && size > std::numeric_limits<size_t>::max() / count)
        return nullptr;
    void* p = cholmod_block_alloc(count * size);
    if (p != nullptr)
        std::memset(p, 0, count * size);
    return p;
}

void use_huge_pages_for_cholmod()
{
    static std::once_flag once;
    std::call_once(once, [] {
        SuiteSparse_config.malloc_func = cholmod_block_alloc;
        SuiteSparse_config.calloc_func = cholmod_block_calloc;
    });
}

} // namespace

struct SparseCholesky::Impl {
    cholmod_common common{};
    cholmod_factor* factor = nullptr;
    // Solve workspaces, reused across solves (cholmod_solve2 grows them on first use).
    cholmod_dense* x = nullptr;
    cholmod_dense* y = nullptr;
    cholmod_dense* e = nullptr;
    cholmod_dense* b = nullptr;
    // The same for block solves (their own, so that sizes do not alternate).
    cholmod_dense* xs = nullptr;
    cholmod_dense* ys = nullptr;
    cholmod_dense* es = nullptr;

    Impl()
    {
        use_huge_pages_for_cholmod();
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
        cholmod_free_dense(&xs, &common);
        cholmod_free_dense(&ys, &common);
        cholmod_free_dense(&es, &common);
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

bool SparseCholesky::solve(const Eigen::MatrixXd& x, Eigen::MatrixXd& y) const
{
    Impl& s = *m_impl;
    // A view of x's columns (CHOLMOD only reads B); x is contiguous column-major.
    cholmod_dense view{};
    view.nrow = static_cast<size_t>(x.rows());
    view.ncol = static_cast<size_t>(x.cols());
    view.nzmax = view.nrow * view.ncol;
    view.d = view.nrow;
    view.x = const_cast<double*>(x.data());
    view.xtype = CHOLMOD_REAL;
    view.dtype = CHOLMOD_DOUBLE;
    if (!cholmod_solve2(CHOLMOD_A, s.factor, &view, nullptr, &s.xs, nullptr, &s.ys, &s.es, &s.common) ||
        s.xs == nullptr)
        return false;
    y = Eigen::Map<const Eigen::MatrixXd>(static_cast<const double*>(s.xs->x), x.rows(), x.cols());
    return true;
}

double SparseCholesky::factor_nonzeros() const
{
    return m_impl->common.lnz;
}

} // namespace supermodal::modal
