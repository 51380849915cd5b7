// The lattice of an auto body (engine/src/modal/auto_lattice.cpp): refined until the kept modes'
// frequencies settle, within a cap, and what the run reports of it.
#include "modal/auto_lattice.h"
#include "supermodal/modal.h"
#include "supermodal/scene.h"
#include "supermodal/world.h"

#include <gtest/gtest.h>

namespace sm = supermodal;

namespace
{

// A pine slat 0.6 × 0.04 × 0.02 m, rounded box: slender, with a rounded section the cut cells must
// resolve.
sm::ModalBasisDef slat(int modes)
{
    sm::ModalBasisDef def = sm::default_modal_basis_def();
    def.shape.radii = {0.3, 0.02, 0.01};
    def.shape.epsilon1 = def.shape.epsilon2 = 0.3;
    def.density = 450;
    def.young = 11e9;
    def.mode_count = modes;
    return def;
}

} // namespace

TEST(AutoLattice, TwiceTheChangeFromTheHalvedDefaultBoundsItsError)
{
    // The slat's default 16×3×3 lattice (2808 dofs) is compared with 8×2×2; doubling it (32×6×6) passes
    // the 3000-dof cap, so the default is kept.
    sm::ModalBasisCache cache;
    const sm::Result<sm::modal::LatticeChoice> choice = sm::modal::choose_lattice(cache, slat(4));
    ASSERT_TRUE(choice) << choice.error().message();
    EXPECT_EQ(choice->basis->cells, (std::array<int, 3>{16, 3, 3}));
    ASSERT_EQ(choice->frequency_changes.size(), 4u);
    // Against a lattice twice as fine across (32×4×4; it differs from 64×8×8 by under 0.3%), each mode's
    // error is within k_lattice_change_safety (2) times its reported change, and within the default
    // lattice's 2%. The change alone is not a bound in general: cut cells' boundary quadrature converges
    // unevenly as the cross-section refines (on 16×2×2: error 1.9%, change 1.24%).
    sm::ModalBasisDef finer = slat(4);
    finer.lattice.cells = {32, 4, 4};
    const sm::Result<std::shared_ptr<const sm::ModalBasis>> reference = cache.get_or_build(finer);
    ASSERT_TRUE(reference) << reference.error().message();
    for (size_t k = 0; k < 4; ++k) {
        const double f = (*reference)->frequencies_hz[k];
        const double error = std::abs(choice->basis->frequencies_hz[k] - f) / f;
        EXPECT_LE(error, sm::modal::k_lattice_change_safety * choice->frequency_changes[k]) << k;
        EXPECT_LT(error, 0.02) << k;
    }
}

TEST(AutoLattice, RefinesWhileTheKeptModesMove)
{
    // 8-node cells lock: the slat's 16×2×2 default moves its modes far from 8×2×2, so it is doubled to
    // 32×4×4 (2475 dofs); the next doubling passes the cap.
    sm::ModalBasisCache cache;
    sm::ModalBasisDef def = slat(4);
    def.lattice.element_order = 1;
    const sm::Result<sm::modal::LatticeChoice> choice = sm::modal::choose_lattice(cache, def);
    ASSERT_TRUE(choice) << choice.error().message();
    EXPECT_EQ(choice->basis->cells, (std::array<int, 3>{32, 4, 4}));
    EXPECT_FALSE(choice->met);
    EXPECT_GT(choice->frequency_change, sm::modal::k_auto_lattice_target);
}

TEST(AutoLattice, ACompactBodyKeepsTheDefaultLattice)
{
    // A ball's default 5×5×5 lattice already agrees with 3×3×3 within the target for 6 modes.
    sm::ModalBasisCache cache;
    sm::ModalBasisDef ball = sm::default_modal_basis_def();
    ball.shape.radii = {0.025, 0.025, 0.025};
    ball.mode_count = 6;
    const sm::Result<sm::modal::LatticeChoice> choice = sm::modal::choose_lattice(cache, ball);
    ASSERT_TRUE(choice) << choice.error().message();
    EXPECT_TRUE(choice->met);
    EXPECT_EQ(choice->basis->cells, (std::array<int, 3>{5, 5, 5}));
    EXPECT_GE(choice->frequency_change, 0.0);
}

TEST(AutoLattice, StopsAtTheDegreeOfFreedomCapAndSaysSo)
{
    // A target no lattice meets: the default (2808 dofs) is kept, as its doubling passes the cap.
    sm::ModalBasisCache cache;
    const sm::Result<sm::modal::LatticeChoice> capped = sm::modal::choose_lattice(cache, slat(4), 1e-6, 3000);
    ASSERT_TRUE(capped) << capped.error().message();
    EXPECT_FALSE(capped->met);
    EXPECT_LE(3 * static_cast<int>(capped->basis->node_positions.size()), 3000);
    EXPECT_GT(capped->frequency_change, 1e-6);
}

TEST(AutoLattice, TheRunReportsTheChosenLatticeAndAnExplicitOneIsKept)
{
    // On the penalty solver, where the bound was measured; on the soft one the estimate is 4.0e-5 m.
    auto activity = [](const char* lattice) {
        const std::string text =
            std::string(
                R"({"settings": {"dt": 0.0005, "accuracy": {"displacement": 1e-4}, "contact": {"solver": "penalty"}},
          "materials": {"pine": {"density": 450, "young": 11e9}},
          "bodies": [{"name": "floor", "shape": {"type": "plane"}},
                     {"name": "slat", "material": "pine", "position": [0, 0.08, 0], "velocity": [0, -1, 0],
                      "orientation": [0.9962, 0, 0, 0.0872],
                      "dynamics": {"type": "auto", "modes": 4)") +
            lattice + R"(},
                      "shape": {"type": "superquadric", "radii": [0.3, 0.02, 0.01], "exponents": [0.3, 0.3]}}]})";
        const sm::Result<sm::Scene> scene = sm::parse_scene(text);
        EXPECT_TRUE(scene) << scene.error().message();
        sm::Result<sm::World> world = sm::build_world(*scene);
        EXPECT_TRUE(world) << world.error().message();
        for (int s = 0; s < 200; ++s)
            world->step();
        return sm::body_modal_activity(*world, sm::find_body(*world, "slat"));
    };
    const sm::BodyModalActivity chosen = activity("");
    EXPECT_GT(chosen.lattice_cells[0], 8);
    // 16×3×3 moved more than 2% from 8×2×2; stopped by the cap.
    EXPECT_FALSE(chosen.lattice_converged);
    EXPECT_GE(chosen.lattice_frequency_change, 0.0);
    EXPECT_GT(chosen.most_active_modes, 0); // the landing bends it
    EXPECT_GT(chosen.lattice_error_estimate, 0.0);
    EXPECT_LT(chosen.lattice_error_estimate, 0.25e-4); // inside a quarter of the 0.1 mm budget
    const sm::BodyModalActivity given = activity(R"(, "lattice": [8, 1, 1])");
    EXPECT_EQ(given.lattice_cells, (std::array<int, 3>{8, 1, 1}));
    EXPECT_EQ(given.lattice_frequency_change, -1.0);
    EXPECT_EQ(given.lattice_error_estimate, 0.0);
}
