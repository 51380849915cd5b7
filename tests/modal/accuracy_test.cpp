// Tests for engine/src/modal/accuracy.cpp through body_modal_accuracy: the full lattice's residual on
// the reduced solution and the static energy of the truncated modes.
#include "modal_scenes.h"
#include "supermodal/body.h"
#include "supermodal/modal.h"
#include "supermodal/world.h"

#include <cmath>
#include <gtest/gtest.h>
#include <numbers>
#include <vector>

namespace sm = supermodal;

namespace
{

// The 2x4 board on a 4×1×1 lattice of 20-node cells: 168 dofs, so all 162 elastic modes fit in a basis.
constexpr int k_all_modes = 162;

sm::BodyDef board(int modes)
{
    sm::BodyDef def = sm::default_body_def();
    def.shape = sm::test::board_def({4, 1, 1}).shape;
    def.density = 450.0;
    def.modal.enabled = true;
    def.modal.mode_count = modes;
    def.modal.lattice = {4, 1, 1};
    def.young = 11e9;
    def.poisson = 0.3;
    def.modal.damping_ratio = 0.02;
    return def;
}

// An off-centre, oblique 100 N load on the top face (every mode family is loaded), one 1 ms step.
const sm::Vec3 k_point{0.31, sm::test::k_board_thickness / 2, 0.02};
const sm::Vec3 k_force{10.0, -100.0, 30.0};

sm::ModalAccuracy loaded_report(int modes)
{
    sm::WorldDef wd = sm::default_world_def();
    wd.dt = 1e-3;
    wd.gravity = {};
    sm::World world(wd);
    const sm::Entity b = sm::create_body(world, board(modes));
    sm::apply_force(world, b, k_force, sm::body_position(world, b) + k_point);
    world.step();
    return sm::body_modal_accuracy(world, b);
}

} // namespace

TEST(ModalAccuracy, AllModesKeptLeaveNoResidual)
{
    const sm::ModalAccuracy a = loaded_report(k_all_modes);
    // F is the load lumped on the 20 nodes of its cell: ‖F‖₂ ≤ |f| (weights summing to 1 spread it).
    ASSERT_GT(a.load_norm, 0.3 * length(k_force));
    ASSERT_LE(a.load_norm, length(k_force) * (1.0 + 1e-12));
    std::printf("[ measured ] all %d modes: residual %.3e, truncated fraction %.3e\n", k_all_modes,
                a.residual, a.truncated_fraction);
    // With every mode kept, [Ψ Φ] is a complete M-orthonormal basis and M [Ψ Φ][Ψ Φ]ᵀ = I: R vanishes up
    // to the eigensolver's orthonormality (2e-15) times the conditioning of M and K (cut-free lattice,
    // dense solve). 1e-8 leaves room for that and is far below the 1e-2..1 of truncated bases below.
    EXPECT_LT(a.residual, 1e-8);
    EXPECT_GT(a.static_energy, 0.0);
    EXPECT_LT(a.truncated_fraction, 1e-8);
}

TEST(ModalAccuracy, ResidualAndTruncatedEnergyGrowAsModesAreDropped)
{
    // The reference: the full basis's mode sums, an independent route to the truncated energy (the
    // report gets it from a static solve of the pinned full lattice).
    sm::World world(sm::default_world_def());
    const sm::Entity full = sm::create_body(world, board(k_all_modes));
    const sm::ModalBasis& basis = *sm::body_modal_basis(world, full);
    std::vector<double> energy_of_mode(k_all_modes);
    double total = 0.0;
    for (int k = 0; k < k_all_modes; ++k) {
        std::vector<double> unit(k_all_modes, 0.0);
        unit[k] = 1.0;
        const double load = dot(sm::modal_displacement(basis, k_point, unit), k_force);
        const double omega = 2.0 * std::numbers::pi * basis.frequencies_hz[k];
        energy_of_mode[k] = 0.5 * load * load / (omega * omega);
        total += energy_of_mode[k];
    }
    double previous_residual = 0.0, previous_energy = 0.0;
    for (const int r : {96, 48, 24, 12, 6, 3, 1}) {
        const sm::ModalAccuracy a = loaded_report(r);
        double truncated = 0.0;
        for (int k = r; k < k_all_modes; ++k)
            truncated += energy_of_mode[k];
        // Same lattice, same modes (no repeated frequency is split here): the static solve and the mode
        // sum agree to solver precision; 1e-6 of the total allows for the pinned factorisation's error.
        EXPECT_NEAR(a.static_energy, total, 1e-6 * total) << r << " modes";
        EXPECT_NEAR(a.truncated_energy, truncated, 1e-6 * total) << r << " modes";
        // Fewer modes: neither measure may fall (the M⁻¹ norm of R is Σ over the dropped modes'
        // (φ_kᵀF)², so it is monotone; 1e-12 absorbs rounding).
        EXPECT_GE(a.residual, previous_residual - 1e-12) << r << " modes";
        EXPECT_GE(a.truncated_energy, previous_energy * (1.0 - 1e-9)) << r << " modes";
        previous_residual = a.residual;
        previous_energy = a.truncated_energy;
        std::printf("[ measured ] r = %2d: residual %.4f, truncated energy %.4e J (%.4f of %.4e J)\n", r,
                    a.residual, a.truncated_energy, a.truncated_fraction, a.static_energy);
    }
    EXPECT_GT(previous_residual, 0.5); // one mode cannot represent a point load
}

TEST(ModalAccuracy, FreeVibrationHasOnlyTheEigenResidual)
{
    // No load: R = (K Φ − M Φ Ω²) q, the eigenpairs' own residual (ModalDiagnostics::mode_residuals,
    // below 1e-10 on this lattice), relative to ‖K u‖.
    sm::World world(sm::default_world_def());
    const sm::Entity b = sm::create_body(world, board(12));
    std::vector<double> q(12, 1e-4), v(12, 0.0);
    ASSERT_TRUE(sm::set_body_modal_state(world, b, q, v).ok());
    const sm::ModalAccuracy a = sm::body_modal_accuracy(world, b);
    EXPECT_EQ(a.load_norm, 0.0);
    EXPECT_LT(a.residual, 1e-9);
    EXPECT_EQ(a.truncated_energy, 0.0);
}

TEST(ModalAccuracy, RigidBodyReportsZeros)
{
    sm::World world(sm::default_world_def());
    sm::BodyDef def = board(6);
    def.modal.enabled = false;
    const sm::Entity b = sm::create_body(world, def);
    const sm::ModalAccuracy a = sm::body_modal_accuracy(world, b);
    EXPECT_EQ(a.residual, 0.0);
    EXPECT_EQ(a.static_energy, 0.0);
}
