// SPDX-License-Identifier: MIT
// Left-looking supernodal Cholesky (see supernodal.h): each supernode gathers its columns of A,
// subtracts the updates of the supernodes below it in the elimination tree that touch its rows, then
// factors its own dense block.
#include "modal/supernodal.h"

#include <algorithm>
#include <cmath>
#include <type_traits>
#include <vector>

namespace supermodal::modal
{

namespace
{

using Block = Eigen::Map<Eigen::MatrixXd, 0, Eigen::OuterStride<>>;
using ConstBlock = Eigen::Map<const Eigen::MatrixXd, 0, Eigen::OuterStride<>>;

/// Product depth per call. Eigen cuts a product's depth into slices that fit the L1 size it reads
/// from the CPU, and the cut sets the rounding; for a 16 kB L1 the slices are at least 248 deep with
/// SSE2, 120 with AVX and 248 with AVX-512. Depths up to this are never cut, so each entry of a
/// product is summed in one order, the build's own, on any CPU. (96 is as fast as 128 here.)
constexpr Eigen::Index k_depth = 96;
/// Columns of a dense panel factored by column sweeps, and rows of an update's top strips.
constexpr Eigen::Index k_panel = 32;

/// c −= a·btᵀ, the depth (a's columns, bt's columns) in slices of k_depth.
template <class C, class A, class B> void subtract_product(C&& c, const A& a, const B& bt)
{
    const Eigen::Index depth = a.cols();
    for (Eigen::Index k = 0; k < depth; k += k_depth) {
        const Eigen::Index w = std::min(k_depth, depth - k);
        c.noalias() -= a.middleCols(k, w) * bt.middleCols(k, w).transpose();
    }
}

/// c −= a·a.topRows(c.cols())ᵀ where the result is read: below the diagonal, and on it. The square on
/// top goes in strips of k_panel rows, so only the strips' own corners are computed beyond it.
template <class A> void subtract_lower_product(Eigen::Map<Eigen::MatrixXd>& c, const A& a)
{
    const Eigen::Index cols = c.cols(), below = c.rows() - cols;
    for (Eigen::Index r0 = 0; r0 < cols; r0 += k_panel) {
        const Eigen::Index h = std::min(k_panel, cols - r0);
        subtract_product(c.block(r0, 0, h, r0 + h), a.middleRows(r0, h), a.topRows(r0 + h));
    }
    subtract_product(c.bottomRows(below), a.bottomRows(below), a.topRows(cols));
}

/// Supernode s's columns of the factor, column-major (a read-only view where `values` is const).
template <class T> auto supernode_block(const SupernodalPattern& p, T* values, int s)
{
    using View = std::conditional_t<std::is_const_v<T>, ConstBlock, Block>;
    const int nrow = p.pi[s + 1] - p.pi[s];
    return View{values + p.px[s], nrow, p.super[s + 1] - p.super[s], Eigen::OuterStride<>(nrow)};
}

/// Factors a panel in place: its top square becomes lower triangular L₁₁, the rows below L₂₁ L₁₁ᵀ = B.
/// Column sweeps: each column is updated by the ones before it as whole vectors.
bool factor_panel(Eigen::Block<Block> p)
{
    const Eigen::Index m = p.rows();
    for (Eigen::Index j = 0; j < p.cols(); ++j) {
        for (Eigen::Index k = 0; k < j; ++k)
            p.col(j).tail(m - j) -= p(j, k) * p.col(k).tail(m - j);
        const double d = p(j, j);
        if (!(d > 0.0) || !std::isfinite(d))
            return false;
        p.col(j).tail(m - j) /= std::sqrt(d);
    }
    return true;
}

/// Factors a supernode's dense block (its updates already subtracted), left-looking in panels.
bool factor_block(Block x)
{
    const Eigen::Index nrow = x.rows();
    for (Eigen::Index c0 = 0; c0 < x.cols(); c0 += k_panel) {
        const Eigen::Index w = std::min(k_panel, x.cols() - c0);
        subtract_product(x.block(c0, c0, nrow - c0, w), x.block(c0, 0, nrow - c0, c0), x.block(c0, 0, w, c0));
        if (!factor_panel(x.block(c0, c0, nrow - c0, w)))
            return false;
    }
    return true;
}

/// The bookkeeping of the left-looking sweep: which finished supernodes still update later ones.
struct Sweep {
    std::vector<int> pinv;     ///< A's row → permuted row
    std::vector<int> super_of; ///< permuted column → its supernode
    std::vector<int> local;    ///< permuted row → its position in the current supernode's rows
    std::vector<int> head;     ///< per supernode: the first descendant waiting to update it
    std::vector<int> next;     ///< per supernode: the next in its waiting list
    std::vector<int> pos;      ///< per supernode: its first row not yet applied
    std::vector<int> rel;      ///< an update's rows' positions in the target
    std::vector<double> c;     ///< an update's values

    explicit Sweep(const SupernodalPattern& p)
        : pinv(p.n), super_of(p.n), local(p.n, 0), head(p.nsuper, -1), next(p.nsuper, -1), pos(p.nsuper, 0)
    {
        for (int i = 0; i < p.n; ++i)
            pinv[p.perm[i]] = i;
        for (int s = 0; s < p.nsuper; ++s)
            std::fill(super_of.begin() + p.super[s], super_of.begin() + p.super[s + 1], s);
    }

    /// Queues finished supernode d for the supernode holding its row at position `at`.
    void queue(const SupernodalPattern& p, int d, int at)
    {
        const int nrow = p.pi[d + 1] - p.pi[d];
        pos[d] = at;
        if (at >= nrow)
            return;
        const int target = super_of[p.rows[p.pi[d] + at]];
        next[d] = head[target];
        head[target] = d;
    }
};

/// Writes A's entries of supernode s's columns (lower triangle of P A Pᵀ) into its zeroed block:
/// K's, then −σ times M's (the same bits as K − σM formed first).
void gather_columns(const SupernodalPattern& p, const ShiftedMatrix& a, const Sweep& w, int s, Block x)
{
    for (int j = p.super[s]; j < p.super[s + 1]; ++j) {
        for (SparseMatrix::InnerIterator it(*a.k, p.perm[j]); it; ++it)
            if (const int i = w.pinv[it.row()]; i >= j)
                x(w.local[i], j - p.super[s]) += it.value();
        if (a.m == nullptr)
            continue;
        for (SparseMatrix::InnerIterator it(*a.m, p.perm[j]); it; ++it)
            if (const int i = w.pinv[it.row()]; i >= j)
                x(w.local[i], j - p.super[s]) -= a.sigma * it.value();
    }
}

/// Subtracts descendant d's update from supernode s and re-queues d for its next target.
void apply_update(const SupernodalPattern& p, const double* values, Sweep& w, int d, int s, Block x)
{
    const ConstBlock ld = supernode_block(p, values, d);
    const int* rows = p.rows + p.pi[d];
    const int nrow = p.pi[d + 1] - p.pi[d];
    const int p1 = w.pos[d];
    int p2 = p1;
    while (p2 < nrow && rows[p2] < p.super[s + 1])
        ++p2;
    const int m = nrow - p1;
    const int cols = p2 - p1;
    w.c.assign(static_cast<size_t>(m) * cols, 0.0);
    Eigen::Map<Eigen::MatrixXd> c(w.c.data(), m, cols);
    subtract_lower_product(c, ld.middleRows(p1, m)); // −L_d Lᵀ_d on these rows
    w.rel.resize(static_cast<size_t>(m));
    for (int i = 0; i < m; ++i)
        w.rel[i] = w.local[rows[p1 + i]];
    for (int j = 0; j < cols; ++j) {
        double* xc = x.col(rows[p1 + j] - p.super[s]).data();
        for (int i = j; i < m; ++i)
            xc[w.rel[i]] += c(i, j);
    }
    w.queue(p, d, p2);
}

template <int B> using Row = Eigen::Matrix<double, 1, B>;

/// L z = y on one supernode's rows (gathered, B values a row): columns four at a time, so each
/// row's values are read and written once per four columns of L.
template <int B> void sweep_forward(const ConstBlock& l, double* ys)
{
    const auto row = [ys](Eigen::Index i) { return Eigen::Map<Row<B>>(ys + i * B); };
    const Eigen::Index ncol = l.cols(), nrow = l.rows();
    for (Eigen::Index j = 0; j < ncol; j += 4) {
        const Eigen::Index w = std::min<Eigen::Index>(4, ncol - j);
        for (Eigen::Index k = 0; k < w; ++k) {
            row(j + k) /= l(j + k, j + k);
            for (Eigen::Index q = k + 1; q < w; ++q)
                row(j + q) -= l(j + q, j + k) * row(j + k);
        }
        if (w == 4) {
            const Row<B> t0 = row(j), t1 = row(j + 1), t2 = row(j + 2), t3 = row(j + 3);
            const double *c0 = l.col(j).data(), *c1 = l.col(j + 1).data(), *c2 = l.col(j + 2).data(),
                         *c3 = l.col(j + 3).data();
            for (Eigen::Index i = j + 4; i < nrow; ++i)
                row(i) -= c0[i] * t0 + c1[i] * t1 + c2[i] * t2 + c3[i] * t3;
            continue;
        }
        for (Eigen::Index k = 0; k < w; ++k) {
            const Row<B> t = row(j + k);
            const double* c = l.col(j + k).data();
            for (Eigen::Index i = j + w; i < nrow; ++i)
                row(i) -= c[i] * t;
        }
    }
}

/// Lᵀ x = z on one supernode's rows (those below its columns already solved), last columns first.
template <int B> void sweep_backward(const ConstBlock& l, double* ys)
{
    const auto row = [ys](Eigen::Index i) { return Eigen::Map<Row<B>>(ys + i * B); };
    const Eigen::Index ncol = l.cols(), nrow = l.rows();
    for (Eigen::Index j = (ncol - 1) / 4 * 4; j >= 0; j -= 4) {
        const Eigen::Index w = std::min<Eigen::Index>(4, ncol - j);
        if (w == 4) {
            Row<B> a0 = Row<B>::Zero(), a1 = Row<B>::Zero(), a2 = Row<B>::Zero(), a3 = Row<B>::Zero();
            const double *c0 = l.col(j).data(), *c1 = l.col(j + 1).data(), *c2 = l.col(j + 2).data(),
                         *c3 = l.col(j + 3).data();
            for (Eigen::Index i = j + 4; i < nrow; ++i) {
                const Row<B> r = row(i);
                a0 += c0[i] * r;
                a1 += c1[i] * r;
                a2 += c2[i] * r;
                a3 += c3[i] * r;
            }
            row(j) -= a0;
            row(j + 1) -= a1;
            row(j + 2) -= a2;
            row(j + 3) -= a3;
        } else {
            for (Eigen::Index k = 0; k < w; ++k) {
                Row<B> a = Row<B>::Zero();
                const double* c = l.col(j + k).data();
                for (Eigen::Index i = j + w; i < nrow; ++i)
                    a += c[i] * row(i);
                row(j + k) -= a;
            }
        }
        for (Eigen::Index k = w - 1; k >= 0; --k) {
            for (Eigen::Index q = k + 1; q < w; ++q)
                row(j + k) -= l(j + q, j + k) * row(j + q);
            row(j + k) /= l(j + k, j + k);
        }
    }
}

/// Both sweeps over every supernode for B right-hand sides stored row by row in y.
template <int B>
void solve_rows(const SupernodalPattern& p, const double* values, double* y, std::vector<double>& ys)
{
    const auto gather = [&](int s) {
        const int* rows = p.rows + p.pi[s];
        const int nrow = p.pi[s + 1] - p.pi[s];
        ys.resize(static_cast<size_t>(nrow) * B);
        for (int i = 0; i < nrow; ++i)
            std::copy_n(y + static_cast<size_t>(rows[i]) * B, B, ys.data() + static_cast<size_t>(i) * B);
    };
    const auto scatter = [&](int s, int count) {
        const int* rows = p.rows + p.pi[s];
        for (int i = 0; i < count; ++i)
            std::copy_n(ys.data() + static_cast<size_t>(i) * B, B, y + static_cast<size_t>(rows[i]) * B);
    };
    for (int s = 0; s < p.nsuper; ++s) {
        gather(s);
        sweep_forward<B>(supernode_block(p, values, s), ys.data());
        scatter(s, p.pi[s + 1] - p.pi[s]);
    }
    for (int s = p.nsuper - 1; s >= 0; --s) {
        gather(s);
        sweep_backward<B>(supernode_block(p, values, s), ys.data());
        scatter(s, p.super[s + 1] - p.super[s]);
    }
}

} // namespace

bool supernodal_factor(const SupernodalPattern& p, const ShiftedMatrix& a, double* values)
{
    Sweep w(p);
    for (int s = 0; s < p.nsuper; ++s) {
        Block x = supernode_block(p, values, s);
        x.setZero();
        const int* rows = p.rows + p.pi[s];
        for (Eigen::Index i = 0; i < x.rows(); ++i)
            w.local[rows[i]] = static_cast<int>(i);
        gather_columns(p, a, w, s, x);
        for (int d = w.head[s]; d != -1;) {
            const int after = w.next[d];
            apply_update(p, values, w, d, s, x);
            d = after;
        }
        if (!factor_block(x))
            return false;
        w.queue(p, s, static_cast<int>(x.cols()));
    }
    return true;
}

void supernodal_solve(const SupernodalPattern& p, const double* values, RowMatrix& y)
{
    std::vector<double> ys;
    if (y.cols() == 4) {
        solve_rows<4>(p, values, y.data(), ys);
        return;
    }
    Eigen::VectorXd column(y.rows()); // other counts: one column at a time
    for (Eigen::Index c = 0; c < y.cols(); ++c) {
        column = y.col(c);
        solve_rows<1>(p, values, column.data(), ys);
        y.col(c) = column;
    }
}

} // namespace supermodal::modal
