// SPDX-License-Identifier: MIT
// The numeric half of a supernodal sparse Cholesky: given the supernodes of L (from a symbolic
// analysis), fill L = chol(P A Pᵀ) and solve with it. The dense work on a supernode goes through
// Eigen's products and fixed-size vector sweeps, whose rounding depends only on this build (not on the
// CPU's cache sizes: every product's depth is cut below the depth Eigen would block on any cache), so a
// basis is the same on every x86-64 machine running the same build.
#pragma once

#include "modal/assembly.h"

#include <cstddef>

namespace supermodal::modal
{

/// Views of a supernodal symbolic factor (CHOLMOD's layout). Supernode s holds columns
/// [super[s], super[s+1]) of L; its row indices are rows[pi[s] .. pi[s+1]) (its own columns first,
/// ascending); its values are a dense column-major block at px[s] of the value array, one column per
/// L column, leading dimension pi[s+1] − pi[s]. perm: row i of P A Pᵀ is row perm[i] of A.
struct SupernodalPattern {
    int n = 0;
    int nsuper = 0;
    const int* super = nullptr;
    const int* pi = nullptr;
    const int* px = nullptr;
    const int* rows = nullptr;
    const int* perm = nullptr;
    std::size_t value_count = 0; ///< length of the value array
};

/// A = K − σM, both symmetric with both triangles stored, in the original order; M's pattern inside
/// K's (the symbolic factor is K's). No M: A = K.
struct ShiftedMatrix {
    const SparseMatrix* k = nullptr;
    const SparseMatrix* m = nullptr;
    double sigma = 0.0;
};

/// Fills `values` (pattern.value_count) with L. False when A is not numerically positive definite
/// (a pivot ≤ 0 or not finite).
[[nodiscard]] bool supernodal_factor(const SupernodalPattern& pattern, const ShiftedMatrix& a,
                                     double* values);

using RowMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

/// Y ← (P A Pᵀ)⁻¹ Y in the permuted order: four columns in one pass over L, other counts a column at
/// a time.
void supernodal_solve(const SupernodalPattern& pattern, const double* values, RowMatrix& y);

} // namespace supermodal::modal
