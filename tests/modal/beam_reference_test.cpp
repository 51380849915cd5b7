// Tests for engine/src/modal/beam_reference.cpp.
#include "modal/beam_reference.h"
#include "modal/modal_scenes.h"

#include <cmath>
#include <gtest/gtest.h>

namespace modal = supermodal::modal;
namespace test = supermodal::test;

TEST(ModalBeamReference, FreeFreeRootsMatchTables)
{
    // cos x cosh x = 1: 4.73004074, 7.85320462, 10.99560784 (Blevins, Formulas for Natural Frequency).
    EXPECT_NEAR(modal::free_free_beta_l(1), 4.73004074, 1e-8);
    EXPECT_NEAR(modal::free_free_beta_l(2), 7.85320462, 1e-8);
    EXPECT_NEAR(modal::free_free_beta_l(3), 10.99560784, 1e-8);
    EXPECT_NEAR(modal::rectangle_shear_coefficient(0.3), 13.0 / 15.3, 1e-15);
}

TEST(ModalBeamReference, TimoshenkoTendsToEulerBernoulliForSlenderBeams)
{
    // Shear and rotary inertia corrections scale like (β depth / length)²: at L/h = 2000 they are
    // ~5e-6 for mode 3, so the transfer-matrix root must reproduce cos x cosh x = 1.
    modal::BeamSection slender = test::board_section(test::k_board_thickness);
    slender.second_moment = slender.area * 0.25e-6 / 12.0; // depth 0.5 mm
    for (const int n : {1, 2, 3}) {
        const double eb = modal::euler_bernoulli_free_free_hz(slender, n);
        EXPECT_NEAR(modal::timoshenko_free_free_hz(slender, n) / eb, 1.0, 1e-5) << "mode " << n;
    }
}

TEST(ModalBeamReference, BoardEdgewiseModesSitBelowEulerBernoulli)
{
    // For the board's edgewise bending (L/h ≈ 11) Timoshenko sits about 3% below
    // Euler–Bernoulli for mode 1 and about 7% for mode 2; flatwise (L/h ≈ 26) under 1% and ~1.5%.
    const modal::BeamSection edge = test::board_section(test::k_board_width);
    const modal::BeamSection flat = test::board_section(test::k_board_thickness);
    const auto drop = [](const modal::BeamSection& s, int n) {
        return 1.0 - modal::timoshenko_free_free_hz(s, n) / modal::euler_bernoulli_free_free_hz(s, n);
    };
    EXPECT_NEAR(drop(edge, 1), 0.027, 0.003);
    EXPECT_NEAR(drop(edge, 2), 0.072, 0.005);
    EXPECT_NEAR(drop(flat, 1), 0.005, 0.001);
    EXPECT_NEAR(drop(flat, 2), 0.0146, 0.002);
    // Euler–Bernoulli in closed form: f = (β₁L)² / (2πL²) · √(EI/ρA) = 193.12 Hz flatwise.
    EXPECT_NEAR(modal::euler_bernoulli_free_free_hz(flat, 1), 193.123, 1e-3);
}
