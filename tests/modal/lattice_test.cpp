// Tests for engine/src/modal/lattice.cpp.
#include "modal/lattice.h"
#include "supermodal/modal.h"

#include <cmath>
#include <gtest/gtest.h>

namespace sm = supermodal;
namespace modal = supermodal::modal;

namespace
{
constexpr double k_round_off = 1e-13;

// A few points inside and on the natural cube, off every symmetry plane.
const std::array<double, 3> k_points[] = {{0.1, -0.3, 0.7}, {-0.9, 0.25, -0.4}, {1.0, -1.0, 0.33}, {0, 0, 0}};
} // namespace

TEST(ModalLattice, LocalNodeTables)
{
    EXPECT_EQ(modal::cell_nodes_of_order(1).count, 8);
    EXPECT_EQ(modal::cell_nodes_of_order(2).count, 20);
    EXPECT_EQ(sm::lattice_nodes_per_cell(1), 8);
    EXPECT_EQ(sm::lattice_nodes_per_cell(2), 20);
}

TEST(ModalLattice, ShapeFunctionsAreKroneckerAtNodesAndSumToOne)
{
    for (const int order : {1, 2}) {
        const modal::CellNodes& nodes = modal::cell_nodes_of_order(order);
        double n[20];
        std::array<double, 3> dn[20];
        for (int a = 0; a < nodes.count; ++a) {
            modal::shape_functions(order, nodes.xi[a], n, dn);
            for (int b = 0; b < nodes.count; ++b)
                EXPECT_NEAR(n[b], a == b ? 1.0 : 0.0, k_round_off) << "order " << order << " node " << a;
        }
        // Partition of unity, and linear completeness: Σ N_a ξ_a = ξ (so rigid motions are exact).
        for (const auto& xi : k_points) {
            modal::shape_functions(order, xi, n, dn);
            double sum = 0.0, grad_sum[3] = {0, 0, 0};
            std::array<double, 3> reproduced{};
            for (int a = 0; a < nodes.count; ++a) {
                sum += n[a];
                for (int d = 0; d < 3; ++d) {
                    grad_sum[d] += dn[a][d];
                    reproduced[d] += n[a] * nodes.xi[a][d];
                }
            }
            EXPECT_NEAR(sum, 1.0, k_round_off);
            for (int d = 0; d < 3; ++d) {
                EXPECT_NEAR(grad_sum[d], 0.0, k_round_off);
                EXPECT_NEAR(reproduced[d], xi[d], k_round_off);
            }
        }
    }
}

TEST(ModalLattice, SerendipityReproducesQuadratics)
{
    // The 20-node cell spans every complete quadratic: that is what lets it bend without locking.
    const modal::CellNodes& nodes = modal::cell_nodes_of_order(2);
    const auto f = [](const std::array<double, 3>& x) {
        return 0.3 + x[0] - 2 * x[1] + 0.5 * x[0] * x[0] - x[1] * x[2] + 0.7 * x[2] * x[2] +
               0.2 * x[0] * x[1];
    };
    double n[20];
    std::array<double, 3> dn[20];
    for (const auto& xi : k_points) {
        modal::shape_functions(2, xi, n, dn);
        double value = 0.0;
        for (int a = 0; a < nodes.count; ++a)
            value += n[a] * f(nodes.xi[a]);
        EXPECT_NEAR(value, f(xi), 1e-12);
    }
}

TEST(ModalLattice, DerivativesMatchFiniteDifferences)
{
    constexpr double h = 1e-6;
    for (const int order : {1, 2}) {
        double n[20], np[20], nm[20];
        std::array<double, 3> dn[20], unused[20];
        for (const auto& xi : k_points) {
            modal::shape_functions(order, xi, n, dn);
            for (int d = 0; d < 3; ++d) {
                std::array<double, 3> plus = xi, minus = xi;
                plus[d] += h;
                minus[d] -= h;
                modal::shape_functions(order, plus, np, unused);
                modal::shape_functions(order, minus, nm, unused);
                for (int a = 0; a < modal::cell_nodes_of_order(order).count; ++a)
                    EXPECT_NEAR(dn[a][d], (np[a] - nm[a]) / (2 * h), 1e-8);
            }
        }
    }
}

TEST(ModalLattice, DefaultResolutionFollowsAspectRatio)
{
    // Slender board: 16 along the length, at least 3 through thickness and width.
    EXPECT_EQ(modal::resolve_cells({}, 2, {1.0, 0.038, 0.089}), (std::array<int, 3>{16, 3, 3}));
    // Compact sphere: the 3000-dof cap gives 5³.
    EXPECT_EQ(modal::resolve_cells({}, 2, {1, 1, 1}), (std::array<int, 3>{5, 5, 5}));
    EXPECT_EQ(modal::resolve_cells({}, 1, {1, 1, 1}), (std::array<int, 3>{8, 8, 8}));
    // Requested counts are kept; only zeros are chosen.
    EXPECT_EQ(modal::resolve_cells({3, 0, 5}, 2, {1.0, 0.5, 1.0}), (std::array<int, 3>{3, 8, 5}));
}

TEST(ModalLattice, NumberingAndLocate)
{
    modal::Lattice lat;
    lat.cells = {4, 2, 3};
    lat.order = 2;
    lat.min = {-1, -0.5, -1.5};
    lat.cell_size = {0.5, 0.5, 1.0};
    EXPECT_EQ(lat.cell_count(), 24);
    EXPECT_EQ(lat.grid_count(), 9 * 5 * 7);
    int32_t g[20];
    lat.cell_grid_nodes(1, 0, 2, g);
    const sm::Vec3 corner = lat.grid_position(2, 0, 4); // low corner of cell (1, 0, 2)
    EXPECT_EQ(g[0], lat.grid_index(2, 0, 4));
    EXPECT_NEAR(corner.x, -0.5, k_round_off);
    EXPECT_NEAR(corner.z, 0.5, k_round_off);
    std::array<int, 3> cell{};
    std::array<double, 3> xi{};
    modal::locate(lat, {-0.25, 0.4, 1.0}, cell, xi);
    EXPECT_EQ(cell, (std::array<int, 3>{1, 1, 2}));
    EXPECT_NEAR(xi[0], 0.0, k_round_off);
    EXPECT_NEAR(xi[1], 0.6, k_round_off);
    EXPECT_NEAR(xi[2], 0.0, k_round_off);
    // Outside the box: clamped onto it.
    modal::locate(lat, {5, -5, std::nan("")}, cell, xi);
    EXPECT_EQ(cell, (std::array<int, 3>{3, 0, 0}));
    EXPECT_EQ(xi[0], 1.0);
    EXPECT_EQ(xi[1], -1.0);
}
