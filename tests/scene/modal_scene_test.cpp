// Tests for the modal part of engine/src/scene/body_reader.cpp and build_world: "dynamics" of type
// "modal" with the material's E, ν, ρ and damping ratio.
#include "supermodal/body.h"
#include "supermodal/modal.h"
#include "supermodal/scene.h"
#include "supermodal/world.h"

#include <gtest/gtest.h>
#include <string>
#include <string_view>

namespace sm = supermodal;

namespace
{

// A board of material "wood" with the given "dynamics" object (and optional extra body fields).
std::string board_scene(std::string_view dynamics, std::string_view extra = "")
{
    return R"({"materials": {"wood": {"density": 450, "young": 11e9, "poisson": 0.25, "damping_ratio": 0.02}},
  "bodies": [{"name": "board", "material": "wood", )" +
           std::string(extra) + R"("shape": {"type": "superquadric", "radii": [0.5, 0.019, 0.0445],
  "exponents": [0.05, 0.05]}, "dynamics": )" +
           std::string(dynamics) + "}]}";
}

::testing::AssertionResult fails_at(const std::string& json, std::string_view where, std::string_view phrase)
{
    const sm::Result<sm::Scene> scene = sm::parse_scene(json, "test.json");
    if (scene)
        return ::testing::AssertionFailure() << "parsed without error";
    const sm::Error& e = scene.error();
    if (e.where != where || e.what.find(phrase) == std::string::npos)
        return ::testing::AssertionFailure()
               << "got \"" << e.message() << "\"; wanted where \"" << where << "\" and \"" << phrase << "\"";
    return ::testing::AssertionSuccess();
}

} // namespace

TEST(SceneModal, ReadsDynamicsAndMaterial)
{
    const sm::Result<sm::Scene> scene = sm::parse_scene(board_scene(
        R"({"type": "modal", "modes": 6, "lattice": [8, 1, 1], "integrator": "central_difference"})"));
    ASSERT_TRUE(scene) << scene.error().message();
    const sm::SceneBody& body = scene->bodies[0];
    EXPECT_EQ(body.dynamics, sm::DynamicsType::Modal);
    const sm::ModalBodyDef& modal = body.def.modal;
    EXPECT_TRUE(modal.enabled);
    EXPECT_EQ(modal.mode_count, 6);
    EXPECT_EQ(modal.lattice, (std::array<int, 3>{8, 1, 1}));
    EXPECT_EQ(modal.integrator, sm::ModalIntegrator::CentralDifference);
    EXPECT_EQ(body.def.young, 11e9); // one material per body: the modes use it too
    EXPECT_EQ(body.def.poisson, 0.25);
    EXPECT_EQ(modal.damping_ratio, 0.02); // from the material
    EXPECT_EQ(body.def.density, 450.0);

    // Defaults: 12 modes, automatic lattice, exact integrator; the body's damping ratio wins.
    const sm::Result<sm::Scene> defaults =
        sm::parse_scene(board_scene(R"({"type": "modal", "damping_ratio": 0.5})"));
    ASSERT_TRUE(defaults) << defaults.error().message();
    EXPECT_EQ(defaults->bodies[0].def.modal.mode_count, 12);
    EXPECT_EQ(defaults->bodies[0].def.modal.lattice, (std::array<int, 3>{0, 0, 0}));
    EXPECT_EQ(defaults->bodies[0].def.modal.integrator, sm::ModalIntegrator::Exact);
    EXPECT_EQ(defaults->bodies[0].def.modal.damping_ratio, 0.5);

    // A rigid body ignores the modal fields.
    const sm::Result<sm::Scene> rigid = sm::parse_scene(board_scene(R"({"type": "rigid", "modes": 6})"));
    ASSERT_TRUE(rigid);
    EXPECT_FALSE(rigid->bodies[0].def.modal.enabled);
}

TEST(SceneModal, BuildsAModalBodyWithItsBasis)
{
    const sm::Result<sm::Scene> scene =
        sm::parse_scene(board_scene(R"({"type": "modal", "modes": 4, "lattice": [8, 1, 1]})"));
    ASSERT_TRUE(scene) << scene.error().message();
    sm::Result<sm::World> world = sm::build_world(*scene);
    ASSERT_TRUE(world) << world.error().message();
    const sm::Entity board = sm::find_body(*world, "board");
    const sm::ModalBasis* basis = sm::body_modal_basis(*world, board);
    ASSERT_NE(basis, nullptr);
    EXPECT_EQ(basis->mode_count, 4);
    EXPECT_EQ(basis->cells, (std::array<int, 3>{8, 1, 1}));
    EXPECT_EQ(basis->young, 11e9);
    EXPECT_EQ(basis->poisson, 0.25);
    EXPECT_EQ(basis->density, 450.0);
    EXPECT_EQ(sm::body_modal_state(*world, board).amplitudes.size(), 4u);
}

TEST(SceneModal, SharesOneBasisBetweenIdenticalBodies)
{
    const std::string json =
        R"({"materials": {"wood": {"density": 450, "young": 11e9}}, "bodies": [
      {"name": "a", "material": "wood", "shape": {"type": "superquadric", "radii": [0.5, 0.02, 0.05]},
       "dynamics": {"type": "modal", "modes": 3, "lattice": [8, 1, 1]}},
      {"name": "b", "material": "wood", "position": [0, 1, 0],
       "shape": {"type": "superquadric", "radii": [0.5, 0.02, 0.05]},
       "dynamics": {"type": "modal", "modes": 3, "lattice": [8, 1, 1], "damping_ratio": 0.3}}]})";
    const sm::Result<sm::Scene> scene = sm::parse_scene(json);
    ASSERT_TRUE(scene) << scene.error().message();
    sm::Result<sm::World> world = sm::build_world(*scene);
    ASSERT_TRUE(world) << world.error().message();
    // Damping is per body, not part of the basis: both share it.
    EXPECT_EQ(sm::body_modal_basis(*world, sm::find_body(*world, "a")),
              sm::body_modal_basis(*world, sm::find_body(*world, "b")));
}

TEST(SceneModal, ErrorsNameThePointer)
{
    EXPECT_TRUE(fails_at(board_scene(R"({"type": "modal", "modes": 0})"), "/bodies/0/dynamics/modes",
                         "expected an integer in [1, 256], found 0"));
    EXPECT_TRUE(
        fails_at(board_scene(R"({"type": "modal", "modes": 300})"), "/bodies/0/dynamics/modes", "found 300"));
    EXPECT_TRUE(fails_at(board_scene(R"({"type": "modal", "lattice": [8, 0, 1]})"),
                         "/bodies/0/dynamics/lattice/1", "expected an integer in [1, 128], found 0"));
    EXPECT_TRUE(fails_at(board_scene(R"({"type": "modal", "lattice": [8, 1]})"), "/bodies/0/dynamics/lattice",
                         "expected an array of 3 integers"));
    // Each count in range, together over k_max_lattice_dofs: refused while reading, before a world
    // would start building it (128³ 20-node cells: 25 million dofs).
    EXPECT_TRUE(fails_at(board_scene(R"({"type": "modal", "lattice": [128, 128, 128]})"),
                         "/bodies/0/dynamics/lattice",
                         "expected a lattice of at most 100000 degrees of freedom"));
    EXPECT_TRUE(fails_at(board_scene(R"({"type": "modal", "integrator": "verlet"})"),
                         "/bodies/0/dynamics/integrator", "\"exact\""));
    EXPECT_TRUE(fails_at(board_scene(R"({"type": "modal", "damping_ratio": -0.1})"),
                         "/bodies/0/dynamics/damping_ratio", "expected a number >= 0"));
    EXPECT_TRUE(fails_at(board_scene(R"({"type": "modal", "static_correction": 1})"),
                         "/bodies/0/dynamics/static_correction", "expected true or false"));
    EXPECT_TRUE(
        fails_at(board_scene(R"({"type": "modal", "mode": 3})"), "/bodies/0/dynamics/mode", "\"modes\""));
    EXPECT_TRUE(fails_at(board_scene(R"({"type": "modal"})", R"("motion": "kinematic", )"),
                         "/bodies/0/dynamics/type", "modal dynamics need a \"dynamic\" body"));
}

TEST(SceneModal, BasisBuildFailureIsReportedByBuildWorld)
{
    // One 20-node cell has 60 dofs, 54 of them elastic: 100 modes cannot exist.
    const sm::Result<sm::Scene> scene =
        sm::parse_scene(board_scene(R"({"type": "modal", "modes": 100, "lattice": [1, 1, 1]})"));
    ASSERT_TRUE(scene) << scene.error().message();
    const sm::Result<sm::World> world = sm::build_world(*scene);
    ASSERT_FALSE(world);
    EXPECT_EQ(world.error().where, "/bodies/0/dynamics");
    EXPECT_NE(world.error().what.find("cannot build the modal basis"), std::string::npos);
}

TEST(SceneModal, ReadsPlasticityFromTheMaterial)
{
    const std::string json =
        R"({"materials": {"clay": {"density": 1800, "young": 2e6, "yield_stress": 2e4, "hardening": 1e5,
      "max_plastic_strain": 0.3}}, "bodies": [
      {"name": "ball", "material": "clay", "shape": {"type": "superquadric", "radii": [0.1, 0.1, 0.1]},
       "dynamics": {"type": "modal", "modes": 6}}]})";
    const sm::Result<sm::Scene> scene = sm::parse_scene(json);
    ASSERT_TRUE(scene) << scene.error().message();
    const sm::ModalBodyDef& modal = scene->bodies[0].def.modal;
    EXPECT_EQ(modal.yield_stress, 2e4);
    EXPECT_EQ(modal.hardening, 1e5);
    EXPECT_EQ(modal.max_plastic_strain, 0.3);
    sm::Result<sm::World> world = sm::build_world(*scene);
    ASSERT_TRUE(world) << world.error().message();
    EXPECT_EQ(sm::body_plastic_state(*world, sm::find_body(*world, "ball")).yield_stress, 2e4);

    const auto material_error = [](std::string_view fields, std::string_view where, std::string_view phrase) {
        const std::string text = R"({"materials": {"clay": {)" + std::string(fields) + R"(}}, "bodies": []})";
        return fails_at(text, where, phrase);
    };
    EXPECT_TRUE(material_error(R"("hardening": -1)", "/materials/clay/hardening", "expected a number >= 0"));
    EXPECT_TRUE(material_error(R"("max_plastic_strain": 0)", "/materials/clay/max_plastic_strain",
                               "expected a number > 0"));
    EXPECT_TRUE(material_error(R"("yield_stres": 1)", "/materials/clay/yield_stres", "\"yield_stress\""));
}

TEST(SceneModal, ReadsTheRemouldThresholdFromTheMaterial)
{
    const std::string json =
        R"({"materials": {"clay": {"young": 2e6, "yield_stress": 2e4, "remould_threshold": 0.05}}, "bodies": [
      {"name": "ball", "material": "clay", "shape": {"type": "superquadric", "radii": [0.1, 0.1, 0.1]},
       "dynamics": {"type": "modal", "modes": 6}}]})";
    const sm::Result<sm::Scene> scene = sm::parse_scene(json);
    ASSERT_TRUE(scene) << scene.error().message();
    EXPECT_EQ(scene->bodies[0].def.modal.remould_threshold, 0.05);
    const sm::Result<sm::Scene> plain = sm::parse_scene(R"({"bodies": [{"name": "ball", "shape":
      {"type": "superquadric", "radii": [0.1, 0.1, 0.1]}, "dynamics": {"type": "modal", "modes": 6}}]})");
    ASSERT_TRUE(plain) << plain.error().message();
    EXPECT_EQ(plain->bodies[0].def.modal.remould_threshold, sm::ModalBodyDef{}.remould_threshold);
    for (const char* bad : {"-0.1", "\"x\"", "null"})
        EXPECT_TRUE(fails_at(R"({"materials": {"clay": {"remould_threshold": )" + std::string(bad) +
                                 R"(}}, "bodies": []})",
                             "/materials/clay/remould_threshold", "expected"))
            << bad;
}

TEST(SceneModal, AutoIsAdaptiveModalWithTheScenesBudgetOrRigidWhereItCannotDeform)
{
    std::string json = board_scene(R"({"type": "auto", "modes": 16})");
    json.insert(1, R"("settings": {"accuracy": {"displacement": 2e-4}}, )");
    const sm::Result<sm::Scene> scene = sm::parse_scene(json);
    ASSERT_TRUE(scene) << scene.error().message();
    const sm::SceneBody& body = scene->bodies[0];
    EXPECT_EQ(body.dynamics, sm::DynamicsType::Auto);
    EXPECT_TRUE(body.def.modal.enabled);
    EXPECT_EQ(body.def.modal.mode_count, 16);
    EXPECT_EQ(body.def.modal.adaptive_tolerance, 2e-4);
    EXPECT_EQ(scene->accuracy.displacement, 2e-4);

    // Written and read back: still auto, same budget.
    const sm::Result<sm::Scene> again = sm::parse_scene(sm::scene_to_json(*scene));
    ASSERT_TRUE(again) << again.error().message();
    EXPECT_EQ(again->bodies[0].dynamics, sm::DynamicsType::Auto);
    EXPECT_EQ(again->bodies[0].def.modal.adaptive_tolerance, 2e-4);

    // A static body cannot deform: auto makes it rigid, without an error. Default budget: 1 mm.
    const sm::Result<sm::Scene> fixed =
        sm::parse_scene(board_scene(R"({"type": "auto"})", R"("motion": "static", )"));
    ASSERT_TRUE(fixed) << fixed.error().message();
    EXPECT_FALSE(fixed->bodies[0].def.modal.enabled);
    EXPECT_EQ(fixed->accuracy.displacement, 1e-3);
}

TEST(SceneModal, FullKeepsEveryModeOfTheLatticeSoNothingIsTruncated)
{
    // "full": every elastic mode of the lattice, 3n − 6 for n nodes. Board on 4×1×1 20-node cells:
    // 56 nodes, 168 dofs, 162 modes. Under a held point load the accuracy report's truncated static
    // energy is a rounding-level fraction (the kept modes span the whole lattice: 2e-22 measured; bound
    // 1e-9), while 12 modes leave a visible part (0.6% measured; bound 1e-3).
    const sm::Result<sm::Scene> scene =
        sm::parse_scene(board_scene(R"({"type": "full", "lattice": [4, 1, 1]})"));
    ASSERT_TRUE(scene) << scene.error().message();
    EXPECT_EQ(scene->bodies[0].dynamics, sm::DynamicsType::Full);
    EXPECT_EQ(scene->bodies[0].def.modal.mode_count, sm::k_all_modes);
    const sm::Result<sm::Scene> twelve =
        sm::parse_scene(board_scene(R"({"type": "modal", "modes": 12, "lattice": [4, 1, 1]})"));
    ASSERT_TRUE(twelve) << twelve.error().message();
    double fraction[2] = {};
    for (int i = 0; i < 2; ++i) {
        sm::Result<sm::World> world = sm::build_world(i == 0 ? *scene : *twelve);
        ASSERT_TRUE(world) << world.error().message();
        const sm::Entity board = sm::find_body(*world, "board");
        const sm::ModalBasis* basis = sm::body_modal_basis(*world, board);
        ASSERT_NE(basis, nullptr);
        if (i == 0) {
            EXPECT_EQ(basis->diagnostics.dof_count, 168);
            EXPECT_EQ(basis->mode_count, 162);
        }
        for (int step = 0; step < 20; ++step) {
            sm::apply_force(*world, board, {0.0, -50.0, 10.0},
                            sm::body_position(*world, board) + sm::Vec3{0.3, 0.019, 0});
            world->step();
        }
        fraction[i] = sm::body_modal_accuracy(*world, board).truncated_fraction;
    }
    EXPECT_LT(fraction[0], 1e-9);
    EXPECT_GT(fraction[1], 1e-3);
}

TEST(SceneModal, FullErrorsNameThePointer)
{
    EXPECT_TRUE(fails_at(board_scene(R"({"type": "full", "modes": 12})"), "/bodies/0/dynamics/modes",
                         "keeps every mode"));
    EXPECT_TRUE(fails_at(board_scene(R"({"type": "full"})", R"("motion": "static", )"),
                         "/bodies/0/dynamics/type", "modal dynamics need a \"dynamic\" body"));
    // 16×4×4 20-node cells: far more than 1536 dofs, refused when the world is built.
    const sm::Result<sm::Scene> big =
        sm::parse_scene(board_scene(R"({"type": "full", "lattice": [16, 4, 4]})"));
    ASSERT_TRUE(big) << big.error().message();
    const sm::Result<sm::World> world = sm::build_world(*big);
    ASSERT_FALSE(world);
    EXPECT_EQ(world.error().where, "/bodies/0/dynamics");
    EXPECT_NE(world.error().what.find("coarsen the lattice"), std::string::npos) << world.error().message();
}

TEST(SceneModal, FullRoundTripsThroughTheWriter)
{
    const sm::Result<sm::Scene> scene =
        sm::parse_scene(board_scene(R"({"type": "full", "lattice": [4, 1, 1]})"));
    ASSERT_TRUE(scene) << scene.error().message();
    const sm::Result<sm::Scene> again = sm::parse_scene(sm::scene_to_json(*scene));
    ASSERT_TRUE(again) << again.error().message();
    EXPECT_EQ(again->bodies[0].dynamics, sm::DynamicsType::Full);
    EXPECT_EQ(again->bodies[0].def.modal.mode_count, sm::k_all_modes);
}
