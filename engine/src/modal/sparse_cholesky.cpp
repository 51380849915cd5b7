// SPDX-License-Identifier: MIT
// SparseCholesky (see sparse_cholesky.h): CHOLMOD orders and finds the supernodes; the numeric
// factorization and the solves are supernodal.cpp's.
#include "modal/sparse_cholesky.h"

#include "modal/supernodal.h"

#include <algorithm>
#include <cholmod.h>
#include <cstdlib>
#include <limits>
#include <sys/mman.h>
#include <vector>

namespace supermodal::modal
{

namespace
{

constexpr size_t k_huge_page = size_t{2} << 20; // bytes

/// The factor's values on 2 MB transparent huge pages where the kernel allows them on request: the
/// factor is written once right after it is allocated, and touching it 4 kB page by page costs about
/// as much as computing it (page faults in a VM). Freed with std::free.
double* alloc_on_huge_pages(size_t count)
{
    if (count > std::numeric_limits<size_t>::max() / sizeof(double) - k_huge_page)
        return nullptr;
    const size_t bytes = count * sizeof(double);
    if (bytes < 4 * k_huge_page)
        return static_cast<double*>(std::malloc(bytes));
    void* p = std::aligned_alloc(k_huge_page, (bytes + k_huge_page - 1) / k_huge_page * k_huge_page);
    if (p != nullptr)
        madvise(p, bytes, MADV_HUGEPAGE); // advice only: a refusal changes nothing but speed
    return static_cast<double*>(p);
}

/// True when every entry of M's pattern is in K's (both compressed, same size).
bool pattern_inside(const SparseMatrix& m, const SparseMatrix& k)
{
    if (!m.isCompressed() || m.rows() != k.rows() || m.cols() != k.cols())
        return false;
    const int *ko = k.outerIndexPtr(), *ki = k.innerIndexPtr();
    const int *mo = m.outerIndexPtr(), *mi = m.innerIndexPtr();
    for (Eigen::Index j = 0; j < k.cols(); ++j) {
        int p = ko[j];
        for (int q = mo[j]; q < mo[j + 1]; ++q) {
            while (p < ko[j + 1] && ki[p] < mi[q])
                ++p;
            if (p == ko[j + 1] || ki[p] != mi[q])
                return false;
        }
    }
    return true;
}

/// A view of Eigen's compressed columns: stype 1 reads the upper triangle only.
cholmod_sparse view_of(const SparseMatrix& a)
{
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
    return view;
}

} // namespace

struct SparseCholesky::Impl {
    cholmod_common common{};
    cholmod_factor* symbolic = nullptr; ///< CHOLMOD's ordering and supernodes; the values are ours
    SupernodalPattern pattern;
    std::unique_ptr<double, decltype(&std::free)> values{nullptr, &std::free};
    mutable RowMatrix work; ///< a solve's right-hand sides in the factor's order

    Impl()
    {
        cholmod_start(&common);
        common.print = 0; // errors come back as a status, never on stderr
        common.supernodal = CHOLMOD_SUPERNODAL;
    }
    ~Impl()
    {
        cholmod_free_factor(&symbolic, &common);
        cholmod_finish(&common);
    }

    bool analyze(const SparseMatrix& a, std::span<const int> order);
    void solve(const Eigen::Ref<const Eigen::MatrixXd>& x, Eigen::MatrixXd& y) const;
};

bool SparseCholesky::Impl::analyze(const SparseMatrix& a, std::span<const int> order)
{
    cholmod_sparse view = view_of(a);
    // All orderings are deterministic, so the factor (and every mode) is the same on every run.
    if (order.size() == static_cast<size_t>(a.rows())) {
        common.nmethods = 2; // method 0: the given order, method 1: AMD
        symbolic = cholmod_analyze_p(&view, const_cast<int*>(order.data()), nullptr, 0, &common);
    } else {
        common.nmethods = 0; // AMD, and METIS when AMD's fill is high
        symbolic = cholmod_analyze(&view, &common);
    }
    if (symbolic == nullptr || !symbolic->is_super)
        return false;
    pattern.n = static_cast<int>(a.rows());
    pattern.nsuper = static_cast<int>(symbolic->nsuper);
    pattern.super = static_cast<const int*>(symbolic->super);
    pattern.pi = static_cast<const int*>(symbolic->pi);
    pattern.px = static_cast<const int*>(symbolic->px);
    pattern.rows = static_cast<const int*>(symbolic->s);
    pattern.perm = static_cast<const int*>(symbolic->Perm);
    pattern.value_count = symbolic->xsize;
    values.reset(alloc_on_huge_pages(pattern.value_count));
    return values != nullptr;
}

void SparseCholesky::Impl::solve(const Eigen::Ref<const Eigen::MatrixXd>& x, Eigen::MatrixXd& y) const
{
    work.resize(x.rows(), x.cols());
    for (int i = 0; i < pattern.n; ++i)
        work.row(i) = x.row(pattern.perm[i]);
    supernodal_solve(pattern, values.get(), work);
    y.resize(x.rows(), x.cols());
    for (int i = 0; i < pattern.n; ++i)
        y.row(pattern.perm[i]) = work.row(i);
}

SparseCholesky::SparseCholesky() : m_impl(std::make_unique<Impl>()) {}

SparseCholesky::~SparseCholesky() = default;

bool SparseCholesky::compute_shifted(const SparseMatrix& k, const SparseMatrix* m, double sigma,
                                     std::span<const int> order)
{
    Impl& s = *m_impl;
    cholmod_free_factor(&s.symbolic, &s.common);
    s.values.reset();
    m_factored = false;
    m_rows = k.rows();
    if (!k.isCompressed() || k.rows() != k.cols())
        return false;
    if (m != nullptr && !pattern_inside(*m, k)) { // rare: form the sum, then factor it
        SparseMatrix sum = k - sigma * *m;
        sum.makeCompressed();
        return compute_shifted(sum, nullptr, 0.0, order);
    }
    if (!s.analyze(k, order))
        return false;
    m_factored = supernodal_factor(s.pattern, {&k, m, sigma}, s.values.get());
    return m_factored;
}

void SparseCholesky::solve(const double* x, double* y) const
{
    Eigen::MatrixXd v;
    if (!solve(Eigen::Map<const Eigen::MatrixXd>(x, m_rows, 1), v)) // the eigen solve sees no convergence
        v.setConstant(m_rows, 1, std::numeric_limits<double>::quiet_NaN());
    std::copy(v.data(), v.data() + m_rows, y);
}

bool SparseCholesky::solve(Eigen::Ref<const Eigen::MatrixXd> x, Eigen::MatrixXd& y) const
{
    if (!m_factored || x.rows() != m_rows)
        return false;
    m_impl->solve(x, y);
    return true;
}

double SparseCholesky::factor_nonzeros() const
{
    return m_impl->common.lnz;
}

} // namespace supermodal::modal
