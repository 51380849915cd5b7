// SPDX-License-Identifier: MIT
// The coarse stability map (docs/stability.md): the corners and a few interior points
// of each slice of bench/stability_map's grid. Every cell is a configuration validate() accepts.
// Asserted everywhere: no NaN/Inf. Asserted wherever the engine claims stability: energy gain ≤ 1% of
// the energy the scene can dissipate (tests/stability/stability_cells.h: E_ref, gain_all, gain_free).
// Every accepted cell is claimed. Three failures were found by the map and fixed (docs/stability.md
// "Found and fixed"): pointed and concave bodies (ε ≥ 2) on a tip gained 37–226% until a touching pair
// held its contact spring per unit of point area (contact/penalty.cpp, hold_stiffness); thin ε = 1.5
// discs landing on a rim gained 21–63% until smooth bodies stopped carrying manifold points from earlier
// substeps (contact/manifold.cpp, keeps_old_points); the exact modal integrator under contact until
// contact loads were stepped as a kick (ModalExactStepTimesEpsilon is its regression).
#include "stability/stability_cells.h"

#include <gtest/gtest.h>
#include <string>

namespace st = supermodal::stability;

namespace
{

// 1% of E_ref, the bound. Every scene dissipates (restitution 0.5, friction 0.5), so a correct
// step only loses energy; the map's claimed cells measured at most −1e-6·E_ref of "gain" (the first
// step's rounding), so 1% is far from any noise. gain_all leaves out the springs' stored energy (≥ 0)
// and can only understate a gain while a contact is on; gain_free (contact-free steps) is exact.
constexpr double k_max_gain = 0.01;

void expect_finite(const st::CellResult& r)
{
    ASSERT_TRUE(r.accepted) << r.refusal;
    EXPECT_FALSE(r.non_finite);
    EXPECT_EQ(r.warnings.non_finite_bodies, 0u);
    EXPECT_EQ(r.warnings.modal_non_finite, 0u);
}

void expect_claimed_stable(const std::string& label, st::CellDef def, supermodal::ContactSolver solver)
{
    def.solver = solver;
    const st::CellResult r = st::run_cell(def);
    SCOPED_TRACE(label + " " + st::csv_row("", def, r));
    expect_finite(r);
    EXPECT_LE(r.gain_all, k_max_gain);
    EXPECT_LE(r.gain_free, k_max_gain);
}

} // namespace

// Every slice on both contact solvers (the parameter, named in the test). The soft solver is implicit, so
// no cell may gain either, including the steps far past the penalty limit and the stiff impacts; there
// frequency_hz sets its spring. Heavy on light (mass ratio 10^6) on the soft solver is the regression of
// the lower body's scaled mass (contact_solve.cpp, scale_heavy_on_light): unscaled, the passes could not
// stop the heavy body on the light one's effective mass and shot the light body out (measured gain
// 1.5·10^9 E_ref at dt/limit 0.1, 14.6 at mass ratio 1000); docs/contact.md.
class StabilityMap : public ::testing::TestWithParam<supermodal::ContactSolver>
{
};

TEST_P(StabilityMap, DropEpsilonTimesAspect)
{
    // Corners of ε 0.01…4 × aspect 1…1000, a box, an ellipsoid and an octahedron inside, and the former
    // failures: ε 1.5 (rim) and ε 2, 4 (tip) at aspect 30.
    for (const double e : {0.01, 0.3, 1.0, 1.5, 2.0, 4.0})
        for (const double a : {1.0, 30.0, 1000.0})
            expect_claimed_stable(
                "drop", {.scene = st::Scene::Drop, .epsilon = e, .aspect = a, .seconds = 0.6}, GetParam());
}

TEST_P(StabilityMap, StackMassRatioTimesStep)
{
    // Light on heavy and heavy on light to 10^6, with dt from 0.1 to 10 × the contact limit 1/(10 f).
    for (const double m : {1e-6, 1.0, 1e6})
        for (const double r : {0.1, 1.0, 10.0})
            expect_claimed_stable("stack",
                                  {.scene = st::Scene::Stack, .mass_ratio = m, .dt_ratio = r, .seconds = 0.6},
                                  GetParam());
}

TEST_P(StabilityMap, ImpactFrequencyTimesSpeed)
{
    // Contact frequency 1 Hz … 20 × the penalty cap (50 Hz at dt = 2 ms) × speed 1 cm/s … 1 km/s.
    for (const double f : {1.0, 50.0, 1000.0})
        for (const double v : {0.01, 3.0, 1000.0})
            expect_claimed_stable("impact",
                                  {.scene = st::Scene::Impact, .frequency_hz = f, .speed = v, .seconds = 0.4},
                                  GetParam());
}

TEST_P(StabilityMap, ModalCentralDifferenceStepTimesEpsilon)
{
    // Central difference below and past its limit 2/ω_max (the guard steps the modes past it exactly).
    // ε = 3 at dt/limit 0.1 and 0.3 is the regression of the fix in penalty.cpp: the modal inverse mass
    // taken at the contact centroid, between two tips of the star, let the spring throw the tips' modes
    // to 68× and 74× E_ref (docs/stability.md "Found and fixed").
    for (const double e : {0.3, 1.0, 3.0})
        for (const double r : {0.1, 0.3, 1.1, 10.0})
            expect_claimed_stable(
                "modal", {.scene = st::Scene::ModalDrop, .epsilon = e, .dt_ratio = r, .seconds = 0.5},
                GetParam());
}

TEST_P(StabilityMap, ModalExactStepTimesEpsilon)
{
    // The exact integrator over the same grid as central difference (it needs no guard). ε 1 and 2 at
    // dt/limit 0.1 are the regression of the kick split in modal_world.cpp: the held-force step gained
    // +67% and +108% E_ref there (docs/stability.md "Found and fixed").
    for (const double e : {0.3, 1.0, 2.0, 3.0})
        for (const double r : {0.1, 0.3, 1.1, 10.0})
            expect_claimed_stable("modal exact",
                                  {.scene = st::Scene::ModalDrop,
                                   .epsilon = e,
                                   .dt_ratio = r,
                                   .seconds = 0.5,
                                   .exact_modal = true},
                                  GetParam());
}

TEST_P(StabilityMap, ModalStaticCorrectionStepTimesEpsilon)
{
    // The exact grid with the static correction on: the surface then also moves by the dropped modes'
    // static answer to the last substep's contact loads, a lagged compliance in series with the contact
    // spring. Its stored energy is not in the modal energy, so gain_all understates a gain while the
    // contact is on; gain_free (the correction is zero once no load is left) is exact.
    for (const double e : {0.3, 1.0, 2.0, 3.0})
        for (const double r : {0.1, 0.3, 1.1, 10.0})
            expect_claimed_stable("modal corrected",
                                  {.scene = st::Scene::ModalDrop,
                                   .epsilon = e,
                                   .dt_ratio = r,
                                   .seconds = 0.5,
                                   .exact_modal = true,
                                   .static_correction = true},
                                  GetParam());
}

INSTANTIATE_TEST_SUITE_P(Solvers, StabilityMap,
                         ::testing::Values(supermodal::ContactSolver::Penalty,
                                           supermodal::ContactSolver::Soft),
                         [](const auto& info) {
                             return std::string(info.param == supermodal::ContactSolver::Soft ? "soft"
                                                                                              : "penalty");
                         });
