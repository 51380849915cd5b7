// Tests for engine/src/modal/spectrum.cpp.
#include "modal/spectrum.h"

#include <gtest/gtest.h>
#include <vector>

namespace modal = supermodal::modal;

namespace
{
constexpr double k_scale = 1e7; // E/(ρℓ²) [rad²/s²]
}

TEST(ModalSpectrum, SixRoundOffZerosThenElastic)
{
    const std::vector<double> v{-3e-9, 1e-10, 2e-9, 4e-9, 5e-9, 7e-9, 1.5e6, 1.5e6, 4e6};
    const modal::RigidSplit s = modal::split_rigid_modes(v, k_scale);
    EXPECT_TRUE(s.ok) << s.problem;
    EXPECT_NEAR(s.rigid_ratio, 7e-9 / 1.5e6, 1e-20);
}

TEST(ModalSpectrum, SeventhZeroModeIsAMechanism)
{
    // Two pieces on one lattice: twelve zeros. A hinge: seven. Both must be refused, even though the
    // ratio test alone would pass (the "first elastic" one is itself round-off).
    const std::vector<double> v{0, 0, 0, 0, 0, 0, 1e-9, 1.5e6};
    const modal::RigidSplit s = modal::split_rigid_modes(v, k_scale);
    EXPECT_FALSE(s.ok);
    EXPECT_NE(s.problem.find("more than six"), std::string::npos);
}

TEST(ModalSpectrum, FiveZerosDoNotSeparate)
{
    // A constrained body (one rigid mode missing) has its sixth value elastic: not a free body.
    const std::vector<double> v{0, 0, 0, 0, 0, 2e6, 2.1e6, 5e6};
    EXPECT_FALSE(modal::split_rigid_modes(v, k_scale).ok);
    EXPECT_FALSE(modal::split_rigid_modes(std::vector<double>{0, 0, 0}, k_scale).ok);
}
