// SPDX-License-Identifier: MIT
// supermodal.load_scene: a scene file, a dict (written as JSON text for the loader) or JSON text.
#include "bindings.h"

#include <filesystem>
#include <string>
#include <vector>

namespace smpy
{
namespace
{

WorldPtr build(const sm::Result<sm::Scene>& scene, const std::string& source)
{
    if (!scene)
        raise_scene(scene.error());
    sm::Result<sm::World> world = sm::build_world(*scene);
    if (!world)
        raise_scene(world.error());
    auto box = std::make_shared<WorldBox>(std::move(*world));
    box->duration = scene->duration;
    box->source = source;
    // build_world creates the scene's bodies in file order: world_bodies() lists them in that order.
    const std::vector<sm::Entity> bodies = sm::world_bodies(box->world);
    for (size_t i = 0; i < bodies.size() && i < scene->bodies.size(); ++i)
        if (scene->bodies[i].render_mesh)
            box->render_meshes.emplace(bodies[i], scene->bodies[i].render_mesh);
    return box;
}

// JSON text of a value, as json.dumps writes it (no NaN or infinity: JSON has none).
std::string json_dumps(const py::handle& value, const std::string& argument)
{
    try {
        return py::module_::import("json")
            .attr("dumps")(value, py::arg("allow_nan") = false)
            .cast<std::string>();
    } catch (const py::error_already_set& e) { // a NaN, or a value JSON cannot hold
        raise_argument(argument, std::string("not representable as JSON: ") + e.what());
    }
}

// {pointer: value} as SceneOverrides, in the dict's order; None: none.
std::vector<sm::SceneOverride> to_overrides(const py::object& overrides)
{
    std::vector<sm::SceneOverride> out;
    if (overrides.is_none())
        return out;
    if (!py::isinstance<py::dict>(overrides))
        raise_type("overrides",
                   "expected a dict of JSON pointer to value, got " +
                       py::str(py::type::handle_of(overrides).attr("__name__")).cast<std::string>());
    for (const auto& [key, value] : py::reinterpret_borrow<py::dict>(overrides)) {
        const std::string pointer = to_text(key, "overrides");
        out.push_back({pointer, json_dumps(value, "overrides[" + pointer + "]")});
    }
    return out;
}

WorldPtr load_scene(const py::object& source, const py::object& overrides)
{
    const std::vector<sm::SceneOverride> edits = to_overrides(overrides);
    if (py::isinstance<py::dict>(source))
        return build(sm::parse_scene(json_dumps(source, "scene"), "<dict>", edits), "<dict>");
    if (PyUnicode_Check(source.ptr()) || py::isinstance(source, py::module_::import("os").attr("PathLike"))) {
        const std::string path = py::str(py::module_::import("os").attr("fspath")(source));
        return build(sm::load_scene(path, edits), path);
    }
    raise_type("source", "expected a path (str or os.PathLike) or a dict");
}

WorldPtr parse_scene(const py::object& text, const py::object& overrides)
{
    return build(sm::parse_scene(to_text(text, "text"), "<string>", to_overrides(overrides)), "<string>");
}

} // namespace

void register_scene(py::module_& m)
{
    m.def("load_scene", &load_scene, py::arg("source"), py::arg("overrides") = py::none(),
          R"(Makes a World from a scene: a file path, or a dict in the scene format (docs/scene_format.md),
written to JSON text and read by the same loader. Relative mesh paths in a dict are read from the
current directory. ``overrides``, {JSON pointer: value}, sets values in the scene's JSON before it is
checked, as ``supermodal run --set`` does ({"/bodies/0/material/density": 500}). Raises SceneError whose
``pointer`` is the JSON pointer of the bad value.)");
    m.def("parse_scene", &parse_scene, py::arg("text"), py::arg("overrides") = py::none(),
          "Makes a World from scene JSON text (as load_scene).");
}

} // namespace smpy
