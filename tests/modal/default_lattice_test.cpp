// The default lattice (engine/src/modal/lattice.cpp resolve_cells) against converged lattices of the
// same solid: every family of default_lattice_cases.h within 2% on its six lowest elastic frequencies.
// The references are stored (refining to convergence takes up to a minute per body); the program that
// produced them recomputes and compares them: `default_lattice_table --check` (not part of ctest).
#include "modal/default_lattice_cases.h"
#include "modal/lattice.h"
#include "supermodal/modal.h"

#include <gtest/gtest.h>
#include <string>

namespace sm = supermodal;
namespace test = supermodal::test;

namespace
{

/// Builds the family's body on the default lattice and compares its six lowest frequencies with the
/// stored converged ones, rank by rank; returns the basis for further checks.
sm::ModalBasis expect_default_within_tolerance(const std::string& name)
{
    const test::LatticeCase* c = test::find_lattice_case(name);
    if (c == nullptr) {
        ADD_FAILURE() << "no family " << name;
        return {};
    }
    sm::Result<sm::ModalBasis> b = sm::build_modal_basis(test::lattice_case_def(*c));
    if (!b) {
        ADD_FAILURE() << b.error().message();
        return {};
    }
    for (int k = 0; k < test::k_compared_modes; ++k)
        EXPECT_NEAR(b->frequencies_hz[k] / c->reference_hz[k], 1.0, test::k_default_lattice_tolerance)
            << name << " mode " << k << " on the default lattice " << b->cells[0] << "x" << b->cells[1] << "x"
            << b->cells[2];
    return std::move(*b);
}

/// A board's first torsion mode is among the six compared (so the tolerance covers it), within 2%.
void expect_torsion_within_tolerance(const std::string& name)
{
    const sm::ModalBasis b = expect_default_within_tolerance(name);
    const test::LatticeCase* c = test::find_lattice_case(name);
    ASSERT_NE(c, nullptr);
    int torsion = -1;
    for (int k = 0; k < b.mode_count && torsion < 0; ++k)
        if (b.kinds[k] == sm::ModeKind::Torsion)
            torsion = k;
    ASSERT_GE(torsion, 0) << name << ": no torsion mode among the lowest six";
    EXPECT_NEAR(b.frequencies_hz[torsion] / c->reference_hz[torsion], 1.0, test::k_default_lattice_tolerance);
}

} // namespace

TEST(DefaultLattice, ThinDirectionsGetAtLeastThreeCells)
{
    // The 2x4 board: 16 along its length, 3 through thickness and width (1 each gave +6% in torsion).
    EXPECT_EQ(sm::modal::resolve_cells({}, 2, {1.0, 0.038, 0.089}), (std::array<int, 3>{16, 3, 3}));
    // 1:50: still 3 through the thickness.
    EXPECT_EQ(sm::modal::resolve_cells({}, 2, {1.0, 0.02, 0.1}), (std::array<int, 3>{16, 3, 3}));
    // Compact: the dof cap takes a cube down to 5³.
    EXPECT_EQ(sm::modal::resolve_cells({}, 2, {1, 1, 1}), (std::array<int, 3>{5, 5, 5}));
    EXPECT_LE(sm::modal::lattice_dof_bound({5, 5, 5}, 2), sm::modal::k_default_max_dofs);
    EXPECT_GT(sm::modal::lattice_dof_bound({6, 6, 6}, 2), sm::modal::k_default_max_dofs);
}

TEST(DefaultLattice, Board2x4IncludingTorsion)
{
    expect_torsion_within_tolerance("board_2x4");
}

TEST(DefaultLattice, Board1To10IncludingTorsion)
{
    expect_torsion_within_tolerance("board_1_10");
}

TEST(DefaultLattice, Board1To50IncludingTorsion)
{
    expect_torsion_within_tolerance("board_1_50");
}

TEST(DefaultLattice, RoundedSlat1To30)
{
    expect_default_within_tolerance("slat_1_30");
}

TEST(DefaultLattice, Needle1To50)
{
    expect_default_within_tolerance("needle_1_50");
}

TEST(DefaultLattice, Cube)
{
    expect_default_within_tolerance("cube");
}

TEST(DefaultLattice, Sphere)
{
    expect_default_within_tolerance("sphere");
}

TEST(DefaultLattice, Ellipsoid)
{
    expect_default_within_tolerance("ellipsoid");
}

TEST(DefaultLattice, RoundedBox)
{
    expect_default_within_tolerance("rounded_box");
}

TEST(DefaultLattice, Epsilon0p1)
{
    expect_default_within_tolerance("eps_0.1");
}

TEST(DefaultLattice, Epsilon2)
{
    expect_default_within_tolerance("eps_2");
}

TEST(DefaultLattice, Taper)
{
    expect_default_within_tolerance("taper");
}

TEST(DefaultLattice, Bend)
{
    expect_default_within_tolerance("bend");
}

TEST(DefaultLattice, TooLargeALatticeIsRefusedBeforeItIsBuilt)
{
    sm::ModalBasisDef def = sm::default_modal_basis_def();
    def.lattice.cells = {128, 128, 128};
    const sm::Status s = sm::validate(def);
    ASSERT_FALSE(s);
    EXPECT_EQ(s.error().where, "/lattice/cells");
    // Two given axes with the third left automatic pass validate() (at least one cell there) but not
    // the build, which refuses after choosing the third and before any quadrature.
    def.lattice.cells = {128, 100, 0};
    ASSERT_FALSE(sm::validate(def)) << "128 × 100 × 1 is already over the cap";
    // 60 × 40 × 1 is 51909 dofs; the third axis gets at least 3 cells: 111321, over the cap.
    def.lattice.cells = {60, 40, 0};
    ASSERT_TRUE(sm::validate(def));
    const sm::Result<sm::ModalBasis> b = sm::build_modal_basis(def);
    ASSERT_FALSE(b);
    EXPECT_EQ(b.error().where, "/lattice/cells");
    EXPECT_NE(b.error().what.find("degrees of freedom"), std::string::npos) << b.error().what;
}

TEST(DefaultLattice, MoreModesThanTheLatticeCanHoldIsRefusedBeforeItIsBuilt)
{
    // One 20-node cell over a full box: 20 nodes, 60 dofs, at most 54 elastic modes.
    sm::ModalBasisDef def = sm::default_modal_basis_def();
    def.lattice.cells = {1, 1, 1};
    def.mode_count = 55;
    const sm::Result<sm::ModalBasis> b = sm::build_modal_basis(def);
    ASSERT_FALSE(b);
    EXPECT_EQ(b.error().where, "/mode_count");
    EXPECT_NE(b.error().what.find("at most 54 elastic modes"), std::string::npos) << b.error().what;
}
