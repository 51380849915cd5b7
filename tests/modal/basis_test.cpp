// Tests for engine/src/modal/basis.cpp.
#include "modal/modal_scenes.h"
#include "supermodal/modal.h"
#include "supermodal/shape.h"

#include <cmath>
#include <gtest/gtest.h>
#include <numbers>
#include <vector>

namespace sm = supermodal;
namespace modal = supermodal::modal;
namespace test = supermodal::test;

namespace
{

sm::ModalBasis build_or_die(const sm::ModalBasisDef& def)
{
    sm::Result<sm::ModalBasis> b = sm::build_modal_basis(def);
    EXPECT_TRUE(b) << b.error().message();
    return b ? std::move(*b) : sm::ModalBasis{};
}

/// Displacement [m] of the board's tip centre in mode k at unit amplitude.
sm::Vec3 tip(const sm::ModalBasis& b, int k)
{
    std::vector<double> q(b.mode_count, 0.0);
    q[k] = 1.0;
    return sm::modal_displacement(b, sm::Vec3{0.5, 0.0, 0.0}, q);
}

/// First flatwise (tip moves along y) and edgewise (along z) bending frequencies [Hz].
struct BoardBending {
    double flat_hz = 0.0, edge_hz = 0.0;
};
BoardBending first_bending(const sm::ModalBasis& b)
{
    BoardBending out;
    for (int k = 0; k < b.mode_count; ++k) {
        if (b.kinds[k] != sm::ModeKind::Bend)
            continue;
        const sm::Vec3 u = tip(b, k);
        double& slot = std::abs(u.y) > std::abs(u.z) ? out.flat_hz : out.edge_hz;
        if (slot == 0.0)
            slot = b.frequencies_hz[k];
    }
    return out;
}

const modal::BeamSection k_flat = test::board_section(test::k_board_thickness);
const modal::BeamSection k_edge = test::board_section(test::k_board_width);

} // namespace

TEST(ModalBasis, BoardBendingWithinThreePercentOfEulerBernoulli)
{
    // 16 × 1 × 1 twenty-node cells (600 dofs). Euler–Bernoulli ignores shear and rotary inertia, so the
    // solid sits below it: −0.4% flatwise, −2.6% edgewise (L/h ≈ 11; docs/modal.md). Timoshenko
    // (κ = 10(1+ν)/(12+11ν)) is the tight bound: measured +0.10% flatwise, +0.18% edgewise.
    const sm::ModalBasis b = build_or_die(test::board_def({16, 1, 1}));
    const BoardBending f = first_bending(b);
    const double eb_flat = modal::euler_bernoulli_free_free_hz(k_flat, 1);
    const double eb_edge = modal::euler_bernoulli_free_free_hz(k_edge, 1);
    EXPECT_NEAR(f.flat_hz / eb_flat, 1.0, 0.03);
    EXPECT_NEAR(f.edge_hz / eb_edge, 1.0, 0.03);
    EXPECT_NEAR(f.flat_hz / modal::timoshenko_free_free_hz(k_flat, 1), 1.0, 0.004);
    EXPECT_NEAR(f.edge_hz / modal::timoshenko_free_free_hz(k_edge, 1), 1.0, 0.004);
    EXPECT_EQ(b.kinds[0], sm::ModeKind::Bend);
    EXPECT_EQ(b.frequencies_hz[0], f.flat_hz); // flatwise is the lowest mode
}

TEST(ModalBasis, BoardConvergesUnderRefinement)
{
    // Error against Timoshenko, measured: flatwise +3.12%, +0.48%, +0.10%; edgewise +1.70%, +0.30%,
    // +0.18% at 4, 8, 16 cells along the length (docs/modal.md has the full table).
    const double timo_flat = modal::timoshenko_free_free_hz(k_flat, 1);
    const double timo_edge = modal::timoshenko_free_free_hz(k_edge, 1);
    double last_flat = 1.0, last_edge = 1.0;
    for (const int n : {4, 8, 16}) {
        const BoardBending f = first_bending(build_or_die(test::board_def({n, 1, 1})));
        const double flat = std::abs(f.flat_hz / timo_flat - 1.0);
        const double edge = std::abs(f.edge_hz / timo_edge - 1.0);
        EXPECT_LT(flat, 0.6 * last_flat) << n << " cells";
        EXPECT_LT(edge, 0.7 * last_edge) << n << " cells";
        EXPECT_GT(f.flat_hz, timo_flat); // Rayleigh–Ritz with consistent mass: from above
        last_flat = flat;
        last_edge = edge;
    }
}

TEST(ModalBasis, RigidModesAreZeroBeforeTheyAreDropped)
{
    for (const sm::ModalSolver solver : {sm::ModalSolver::Dense, sm::ModalSolver::Sparse}) {
        sm::ModalBasisDef def = test::board_def({8, 1, 1});
        def.solver = solver;
        const sm::ModalBasis b = build_or_die(def);
        EXPECT_EQ(b.diagnostics.sparse_solver, solver == sm::ModalSolver::Sparse);
        EXPECT_LT(b.diagnostics.rigid_ratio, 1e-6);
        for (const double l : b.diagnostics.rigid_eigenvalues)
            EXPECT_LT(std::abs(l), 1e-6 * b.diagnostics.first_elastic_eigenvalue);
        const double omega0 = 2.0 * std::numbers::pi * b.frequencies_hz[0];
        EXPECT_NEAR(b.diagnostics.first_elastic_eigenvalue, omega0 * omega0, 1e-9 * omega0 * omega0);
    }
}

TEST(ModalBasis, ModesAreMassNormalised)
{
    // Independent of the engine's M: integrate ρ φ_k·φ_l over the board (a box here, so 3×3×3 Gauss
    // per cell is exact for the quadratic cells) through modal_displacement.
    const sm::ModalBasis b = build_or_die(test::board_def({8, 1, 1}));
    EXPECT_LT(b.diagnostics.mass_orthonormality_error, 1e-9);
    const int r = b.mode_count;
    const double g[3] = {-std::sqrt(0.6), 0.0, std::sqrt(0.6)}, w[3] = {5.0 / 9, 8.0 / 9, 5.0 / 9};
    std::vector<double> gram(static_cast<size_t>(r) * r, 0.0), q(r, 0.0);
    std::vector<sm::Vec3> u(r);
    const sm::Vec3 h = b.cell_size;
    for (int c = 0; c < b.cells[0]; ++c)
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j)
                for (int k = 0; k < 3; ++k) {
                    const sm::Vec3 p{b.lattice_min.x + h.x * (c + 0.5 + 0.5 * g[i]),
                                     b.lattice_min.y + h.y * (0.5 + 0.5 * g[j]),
                                     b.lattice_min.z + h.z * (0.5 + 0.5 * g[k])};
                    const double weight = 450.0 * w[i] * w[j] * w[k] * h.x * h.y * h.z / 8.0;
                    for (int m = 0; m < r; ++m) {
                        q.assign(r, 0.0);
                        q[m] = 1.0;
                        u[m] = sm::modal_displacement(b, p, q);
                    }
                    for (int m = 0; m < r; ++m)
                        for (int n = 0; n < r; ++n)
                            gram[static_cast<size_t>(m) * r + n] += weight * sm::dot(u[m], u[n]);
                }
    for (int m = 0; m < r; ++m)
        for (int n = 0; n < r; ++n)
            EXPECT_NEAR(gram[static_cast<size_t>(m) * r + n], m == n ? 1.0 : 0.0, 1e-9) << m << "," << n;
}

TEST(ModalBasis, DisplacementInterpolatesTheModeShapes)
{
    const sm::ModalBasis b = build_or_die(test::board_def({4, 1, 1}, 3));
    const std::vector<double> q{0.3, -1.0, 2.0};
    for (size_t a = 0; a < b.node_positions.size(); ++a) {
        const sm::LatticeWeights w = sm::modal_weights(b, b.node_positions[a]);
        double sum = 0.0;
        for (int i = 0; i < w.count; ++i)
            sum += w.weights[i];
        EXPECT_NEAR(sum, 1.0, 1e-13);
        const sm::Vec3 u = sm::modal_displacement(b, w, q);
        for (int d = 0; d < 3; ++d) {
            double expected = 0.0;
            for (int k = 0; k < 3; ++k)
                expected += b.mode_shapes[(a * 3 + d) * 3 + k] * q[k];
            EXPECT_NEAR(u[d], expected, 1e-12);
        }
    }
    // Fewer amplitudes than modes: the rest count as zero.
    const sm::Vec3 p{0.31, 0.01, -0.02};
    const sm::Vec3 two = sm::modal_displacement(b, p, std::vector<double>{0.3, -1.0});
    const sm::Vec3 three = sm::modal_displacement(b, p, std::vector<double>{0.3, -1.0, 0.0});
    EXPECT_EQ(two, three);
}

TEST(ModalBasis, NodalThenInterpolatedEqualsTheDirectDisplacement)
{
    // The render mesh path (modes summed per node once, then weights per vertex) is the same sum in
    // another order: equal to rounding, 1e-15 relative to the largest displacement.
    const sm::ModalBasis b = build_or_die(test::board_def({4, 1, 1}, 3));
    const std::vector<double> q{0.3, -1.0, 2.0};
    std::vector<sm::Vec3> nodal;
    sm::modal_nodal_displacements(b, q, nodal);
    ASSERT_EQ(nodal.size(), b.node_positions.size());
    double largest = 0.0, worst = 0.0;
    for (int i = 0; i < 200; ++i) {
        const double t = (i + 0.5) / 200;
        const sm::Vec3 p{0.5 * std::cos(9.0 * t), 0.019 * std::sin(37.0 * t), 0.0445 * std::cos(53.0 * t)};
        const sm::LatticeWeights w = sm::modal_weights(b, p);
        const sm::Vec3 direct = sm::modal_displacement(b, w, q);
        largest = std::max(largest, sm::length(direct));
        worst = std::max(worst, sm::length(sm::interpolate_nodal(w, nodal) - direct));
    }
    EXPECT_GT(largest, 0.0);
    EXPECT_LT(worst, 1e-15 * largest * 20); // 20 weights, each rounding once more
}

TEST(ModalBasis, SphereMatchesLambsTorsionalMode)
{
    // A free elastic sphere's lowest mode is Lamb's torsional ₀T₂, ω R / c_s = 2.5011 (root of
    // j₂(x) = x j₃(x)), five-fold; the cubic lattice splits it into 3 + 2. On 3³ twenty-node cells
    // (624 dofs, 26 of 27 cells cut): measured −0.02% and +0.23%.
    const sm::ModalBasis b = build_or_die(test::sphere_def(3, 2, 6));
    const double c_s = std::sqrt(1e7 / (2.0 * 1.3) / 1000.0);
    const double t2 = 2.5011326 * c_s / (2.0 * std::numbers::pi * 0.5);
    for (int k = 0; k < 5; ++k)
        EXPECT_NEAR(b.frequencies_hz[k] / t2, 1.0, 0.005) << k;
    EXPECT_GT(b.frequencies_hz[5] / t2, 1.04); // next: spheroidal ₀S₂, ~6% higher
    // Repeated frequencies come out as exact pairs/triples (the lattice keeps the cube's symmetry).
    EXPECT_NEAR(b.frequencies_hz[1] / b.frequencies_hz[0], 1.0, 1e-9);
    EXPECT_NEAR(b.frequencies_hz[4] / b.frequencies_hz[3], 1.0, 1e-9);
    EXPECT_LT(b.diagnostics.mass_orthonormality_error, 1e-9);
}

TEST(ModalBasis, DeformedShapesAndHyperquadricsBuild)
{
    // Tapered and bent superquadrics and hyperquadrics go through the geometry layer's shape_measure
    // and world_aabb: their lattice mass must match the closed-form mass properties (coarse lattices,
    // first-order indicator quadrature: measured −1.2%, −0.7%, +0.9%).
    sm::ModalBasisDef taper = test::sphere_def(0, 2, 3);
    taper.shape.radii = {0.2, 0.2, 0.6};
    taper.shape.taper = {0.5, 0.3};
    taper.lattice.cells = {2, 2, 5};
    sm::ModalBasisDef bend = taper;
    bend.shape.taper = {};
    bend.shape.bend = {1.0, 0.3};
    sm::ModalBasisDef hyper = test::sphere_def(0, 2, 3);
    hyper.shape.type = sm::ShapeType::Hyperquadric;
    hyper.shape.terms = {{{2, 0, 0}, 0, 4}, {{0, 2, 0}, 0, 4}, {{0, 0, 4}, 0, 4}};
    hyper.lattice.cells = {3, 3, 2};
    for (const sm::ModalBasisDef& def : {taper, bend, hyper}) {
        const sm::ModalBasis b = build_or_die(def);
        EXPECT_NEAR(b.mass / sm::compute_mass_properties(def.shape, def.density).mass, 1.0, 0.02);
        EXPECT_LT(b.diagnostics.rigid_ratio, 1e-6);
    }
}

TEST(ModalBasis, EightNodeCellsLockInBending)
{
    // Fully integrated 8-node cells are far too stiff in bending on a coarse lattice;
    // the same lattice of 20-node cells is within half a percent.
    sm::ModalBasisDef def = test::board_def({8, 2, 2}, 1);
    def.lattice.element_order = 1;
    const double locked = build_or_die(def).frequencies_hz[0];
    const double serendipity = build_or_die(test::board_def({8, 1, 1}, 1)).frequencies_hz[0];
    const double timo = modal::timoshenko_free_free_hz(k_flat, 1);
    EXPECT_GT(locked / timo, 2.0);
    EXPECT_NEAR(serendipity / timo, 1.0, 0.005);
}

TEST(ModalBasis, CacheSharesIdenticalBodies)
{
    sm::ModalBasisCache cache;
    const sm::ModalBasisDef def = test::board_def({4, 1, 1}, 2);
    const auto a = cache.get_or_build(def);
    const auto b = cache.get_or_build(def);
    ASSERT_TRUE(a && b);
    EXPECT_EQ(a->get(), b->get());
    EXPECT_EQ(cache.size(), 1);
    sm::ModalBasisDef stiffer = def;
    stiffer.young *= 2.0;
    const auto c = cache.get_or_build(stiffer);
    ASSERT_TRUE(c);
    EXPECT_NE(c->get(), a->get());
    EXPECT_NEAR((*c)->frequencies_hz[0] / (*a)->frequencies_hz[0], std::sqrt(2.0), 1e-9);
    sm::ModalBasisDef bad = def;
    bad.mode_count = 1000;
    EXPECT_FALSE(cache.get_or_build(bad));
    EXPECT_EQ(cache.size(), 2);
    cache.clear();
    EXPECT_EQ(cache.size(), 0);
}

TEST(ModalBasis, ValidateNamesTheBadField)
{
    const auto where = [](auto edit) {
        sm::ModalBasisDef def = sm::default_modal_basis_def();
        edit(def);
        const sm::Status s = sm::validate(def);
        return s ? std::string("ok") : s.error().where;
    };
    EXPECT_EQ(where([](sm::ModalBasisDef&) {}), "ok");
    EXPECT_EQ(where([](sm::ModalBasisDef& d) { d.density = 0; }), "/density");
    EXPECT_EQ(where([](sm::ModalBasisDef& d) { d.young = NAN; }), "/young");
    EXPECT_EQ(where([](sm::ModalBasisDef& d) { d.poisson = 0.5; }), "/poisson");
    EXPECT_EQ(where([](sm::ModalBasisDef& d) { d.lattice.cells[1] = -1; }), "/lattice/cells");
    EXPECT_EQ(where([](sm::ModalBasisDef& d) { d.lattice.element_order = 3; }), "/lattice/element_order");
    EXPECT_EQ(where([](sm::ModalBasisDef& d) { d.lattice.cut_cell_subdivisions = 0; }),
              "/lattice/cut_cell_subdivisions");
    EXPECT_EQ(where([](sm::ModalBasisDef& d) { d.mode_count = -1; }), "/mode_count");
    EXPECT_EQ(where([](sm::ModalBasisDef& d) { d.mode_count = 257; }), "/mode_count");
    EXPECT_EQ(where([](sm::ModalBasisDef& d) { d.mode_count = sm::k_all_modes; }), "ok"); // every mode
    EXPECT_EQ(where([](sm::ModalBasisDef& d) { d.shape.type = sm::ShapeType::Plane; }), "/shape/type");
    EXPECT_STREQ(sm::mode_kind_name(sm::ModeKind::Torsion), "torsion");
}

TEST(ModalBasis, MoreModesThanTheLatticeHoldsIsAnError)
{
    // 2 × 1 × 1 trilinear cells: 12 nodes, 36 dofs, 30 elastic.
    sm::ModalBasisDef def = test::board_def({2, 1, 1}, 31);
    def.lattice.element_order = 1;
    const sm::Result<sm::ModalBasis> b = sm::build_modal_basis(def);
    ASSERT_FALSE(b);
    EXPECT_NE(b.error().what.find("30 elastic"), std::string::npos) << b.error().what;
    def.mode_count = 30;
    EXPECT_TRUE(sm::build_modal_basis(def));
}
