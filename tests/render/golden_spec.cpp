// SPDX-License-Identifier: MIT
#include "golden_spec.h"

#include "supermodal/body.h"
#include "supermodal/scene.h"
#include "supermodal/world.h"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

namespace supermodal::golden
{

std::vector<std::string> spec_names()
{
    std::vector<std::string> out;
    for (const auto& e : std::filesystem::directory_iterator(std::string(SM_SOURCE_DIR) + "/tests/golden"))
        if (e.path().extension() == ".json")
            out.push_back(e.path().stem().string());
    std::sort(out.begin(), out.end());
    return out;
}

Result<Spec> load_spec(const std::string& name)
{
    const std::string path = std::string(SM_SOURCE_DIR) + "/tests/golden/" + name + ".json";
    std::ifstream in(path);
    std::stringstream text;
    text << in.rdbuf();
    const nlohmann::json j = nlohmann::json::parse(text.str(), nullptr, false);
    if (!in || j.is_discarded() || !j.is_object())
        return Error{path, "", "cannot read a JSON object"};
    Spec s;
    s.name = name;
    try {
        s.scene = j.at("scene").get<std::string>();
        s.width = j.at("size").at(0).get<int>();
        s.height = j.at("size").at(1).get<int>();
        s.steps = j.value("steps", 0LL);
        s.deformation_scale = j.value("deformation_scale", 1.0);
        s.tolerance = j.at("tolerance").get<int>();
        s.max_fraction = j.at("max_fraction").get<double>();
    } catch (const nlohmann::json::exception& e) {
        return Error{path, "", e.what()};
    }
    if (j.contains("camera")) {
        // The scene loader checks the camera: read it as the camera of an otherwise empty scene.
        Result<Scene> camera_only = parse_scene(nlohmann::json{{"camera", j["camera"]}}.dump(), path);
        if (!camera_only)
            return camera_only.error();
        s.has_camera = true;
        s.camera = camera_only->camera;
    }
    return s;
}

Result<Image> render_spec(const Spec& spec, RenderFault fault)
{
    Result<Scene> scene = load_scene(std::string(SM_SOURCE_DIR) + "/" + spec.scene);
    if (!scene)
        return scene.error();
    Result<World> world = build_world(*scene);
    if (!world)
        return world.error();
    for (long long i = 0; i < spec.steps; ++i)
        world->step();
    RenderDef def = default_render_def();
    def.width = spec.width;
    def.height = spec.height;
    def.deformation_scale = spec.deformation_scale;
    def.fault = fault;
    Result<Renderer> renderer = Renderer::create(def);
    if (!renderer)
        return renderer.error();
    const std::vector<Vec3> colors = scene_body_colors(*scene);
    const std::vector<Entity> bodies = world_bodies(*world);
    for (size_t i = 0; i < bodies.size() && i < colors.size(); ++i)
        renderer->set_body_color(bodies[i], colors[i]);
    Image image;
    if (Status s = renderer->render(*world, spec.has_camera ? spec.camera : scene->camera, image); !s)
        return s.error();
    return image;
}

} // namespace supermodal::golden
