// Tests for engine/src/modal/dissection.cpp.
#include "modal/assembly.h"
#include "modal/dissection.h"
#include "modal/modal_scenes.h"

#include <algorithm>
#include <gtest/gtest.h>

namespace modal = supermodal::modal;
namespace test = supermodal::test;

TEST(LatticeDissection, IsAPermutationWithEachNodesDofsTogether)
{
    for (int order : {1, 2}) {
        supermodal::Result<modal::LatticeModel> model =
            modal::assemble_lattice_model(test::sphere_def(5, order));
        ASSERT_TRUE(model);
        const std::vector<int> p = modal::lattice_dissection(*model);
        ASSERT_EQ(p.size(), static_cast<size_t>(model->dof_count()));
        std::vector<int> seen(p.size(), 0);
        for (size_t k = 0; k < p.size(); ++k) {
            ASSERT_GE(p[k], 0);
            ASSERT_LT(p[k], model->dof_count());
            ++seen[static_cast<size_t>(p[k])];
            if (k % 3 != 0) {
                EXPECT_EQ(p[k], p[k - 1] + 1) << "dof " << k << " of order " << order;
            }
        }
        EXPECT_EQ(std::count(seen.begin(), seen.end(), 1), model->dof_count()) << order;
    }
}

TEST(LatticeDissection, TheLastPlaneSplitsTheRestIntoUncoupledHalves)
{
    // The nodes ordered last share one node-grid coordinate (a plane of cell faces); every node
    // before them lies on one side, the first side's nodes all before the other's, and the stiffness
    // couples no node of one side to a node of the other: their blocks of L stay apart.
    supermodal::Result<modal::LatticeModel> model = modal::assemble_lattice_model(test::sphere_def(6));
    ASSERT_TRUE(model);
    const std::vector<int> p = modal::lattice_dissection(*model);
    std::vector<int> nodes;
    for (size_t k = 0; k < p.size(); k += 3)
        nodes.push_back(p[k] / 3);
    const auto grid = [&](int n, int axis) { return model->node_grid[static_cast<size_t>(n)][axis]; };
    // The plane: the longest run at the end with one coordinate equal on some axis.
    int best_axis = 0;
    size_t best_run = 0;
    for (int axis = 0; axis < 3; ++axis) {
        size_t run = 0;
        while (run < nodes.size() && grid(nodes[nodes.size() - 1 - run], axis) == grid(nodes.back(), axis))
            ++run;
        if (run > best_run) {
            best_run = run;
            best_axis = axis;
        }
    }
    const int plane = grid(nodes.back(), best_axis);
    ASSERT_GT(best_run, 10u);
    ASSERT_LT(best_run, nodes.size() / 4);
    std::vector<int> side(static_cast<size_t>(model->node_count()), 0);
    int switches = 0;
    for (size_t k = 0; k + best_run < nodes.size(); ++k) {
        const int g = grid(nodes[k], best_axis);
        ASSERT_NE(g, plane);
        side[static_cast<size_t>(nodes[k])] = g < plane ? -1 : 1;
        switches += k > 0 && side[static_cast<size_t>(nodes[k])] != side[static_cast<size_t>(nodes[k - 1])];
    }
    EXPECT_EQ(switches, 1);
    const modal::SparseMatrix& k = model->stiffness;
    int couplings = 0;
    for (int col = 0; col < k.cols(); ++col)
        for (modal::SparseMatrix::InnerIterator it(k, col); it; ++it)
            couplings += side[static_cast<size_t>(col / 3)] * side[static_cast<size_t>(it.row() / 3)] < 0;
    EXPECT_EQ(couplings, 0);
}
