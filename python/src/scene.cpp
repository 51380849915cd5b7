// SPDX-License-Identifier: MIT
// supermodal.load_scene: a scene file, a dict (written as JSON text for the loader) or JSON text.
#include "bindings.h"

#include <filesystem>

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
    return box;
}

WorldPtr load_scene(const py::object& source)
{
    if (py::isinstance<py::dict>(source)) {
        std::string text;
        try {
            text = py::module_::import("json")
                       .attr("dumps")(source, py::arg("allow_nan") = false)
                       .cast<std::string>();
        } catch (const py::error_already_set& e) { // a NaN, or a value JSON cannot hold
            raise_argument("scene", std::string("not representable as JSON: ") + e.what());
        }
        return build(sm::parse_scene(text, "<dict>"), "<dict>");
    }
    if (PyUnicode_Check(source.ptr()) || py::isinstance(source, py::module_::import("os").attr("PathLike"))) {
        const std::string path = py::str(py::module_::import("os").attr("fspath")(source));
        return build(sm::load_scene(path), path);
    }
    raise_type("source", "expected a path (str or os.PathLike) or a dict");
}

WorldPtr parse_scene(const py::object& text)
{
    return build(sm::parse_scene(to_text(text, "text"), "<string>"), "<string>");
}

} // namespace

void register_scene(py::module_& m)
{
    m.def("load_scene", &load_scene, py::arg("source"),
          R"(Makes a World from a scene: a file path, or a dict in the scene format (docs/scene_format.md),
written to JSON text and read by the same loader. Relative mesh paths in a dict are read from the
current directory. Raises SceneError whose ``pointer`` is the JSON pointer of the bad value.)");
    m.def("parse_scene", &parse_scene, py::arg("text"),
          "Makes a World from scene JSON text (as load_scene).");
}

} // namespace smpy
