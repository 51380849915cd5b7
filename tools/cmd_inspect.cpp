// SPDX-License-Identifier: MIT
// `supermodal inspect`: per-body mass properties and bounds of a scene, without stepping it.
#include "cli_common.h"
#include "supermodal/modal.h"

#include <cmath>
#include <cstdio>

namespace supermodal::cli
{
namespace
{

// World-space box around the shape's oriented bounding box: |R|·a per axis. Tight for boxes and for
// axis-aligned shapes; the geometry issue brings the exact superquadric bound.
nlohmann::json bounds_json(const World& world, Entity b)
{
    const ShapeDef& s = body_shape(world, b);
    if (s.type == ShapeType::Plane)
        return nullptr;
    const Mat3 r = to_mat3(body_orientation(world, b));
    const Vec3 c = body_position(world, b);
    Vec3 half;
    for (int i = 0; i < 3; ++i)
        half[i] = std::abs(r.m[i][0]) * s.radii.x + std::abs(r.m[i][1]) * s.radii.y +
                  std::abs(r.m[i][2]) * s.radii.z;
    return {{"min", to_json(c - half)}, {"max", to_json(c + half)}};
}

nlohmann::json shape_json(const ShapeDef& s)
{
    if (s.type == ShapeType::Plane)
        return {
            {"type", "plane"}, {"normal", to_json(normalized(s.plane_normal))}, {"offset", s.plane_offset}};
    return {{"type", "superquadric"}, {"radii", to_json(s.radii)}, {"exponents", {s.epsilon1, s.epsilon2}}};
}

} // namespace

int inspect_command(const InspectOptions& opt)
{
    Result<Scene> scene = load_scene(opt.scene);
    if (!scene) {
        print_error(scene.error().message());
        return k_exit_bad_input;
    }
    Result<World> built = build_world(*scene);
    if (!built) {
        print_error(built.error().message());
        return k_exit_bad_input;
    }
    const World& world = *built;
    nlohmann::json bodies = nlohmann::json::array();
    for (Entity b : world_bodies(world)) {
        const MassProperties& mp = body_mass_properties(world, b);
        const bool dynamic = body_motion(world, b) == MotionType::Dynamic;
        bodies.push_back(
            {{"name", body_name(world, b)},
             {"motion", motion_name(body_motion(world, b))},
             {"shape", shape_json(body_shape(world, b))},
             {"volume", mp.volume},
             {"mass", dynamic ? nlohmann::json(mp.mass) : nlohmann::json(nullptr)},
             {"center_of_mass", to_json(body_position(world, b) + mp.center_of_mass)},
             {"inertia_diagonal", dynamic ? to_json(mp.inertia_diagonal) : nlohmann::json(nullptr)},
             {"bounds", bounds_json(world, b)},
             {"dynamics", body_modal_basis(world, b) ? "modal" : "rigid"},
             {"modes", body_modal_basis(world, b) ? nlohmann::json(body_modal_basis(world, b)->frequencies_hz)
                                                  : nlohmann::json::array()}});
    }
    const nlohmann::json out = {{"scene", opt.scene},
                                {"dt", world.settings().dt},
                                {"substeps", world.settings().substep_count},
                                {"gravity", to_json(world.settings().gravity)},
                                {"bodies", bodies}};
    if (opt.json) {
        std::printf("%s\n", json_text(out).c_str());
        return k_exit_ok;
    }
    std::printf("%s: %zu bodies, dt = %g s x %d substeps\n", opt.scene.c_str(), bodies.size(),
                world.settings().dt, world.settings().substep_count);
    for (const auto& b : bodies) {
        const std::string name = b["name"].get<std::string>();
        const std::string motion = b["motion"].get<std::string>();
        const std::string type = b["shape"]["type"].get<std::string>();
        if (b["mass"].is_null())
            std::printf("  %-16s %-9s %-12s\n", name.c_str(), motion.c_str(), type.c_str());
        else
            std::printf("  %-16s %-9s %-12s mass %.6g kg, volume %.6g m^3, inertia [%.6g %.6g %.6g] kg m^2\n",
                        name.c_str(), motion.c_str(), type.c_str(), b["mass"].get<double>(),
                        b["volume"].get<double>(), b["inertia_diagonal"][0].get<double>(),
                        b["inertia_diagonal"][1].get<double>(), b["inertia_diagonal"][2].get<double>());
    }
    return k_exit_ok;
}

} // namespace supermodal::cli
