// SPDX-License-Identifier: MIT
// Superquadric fitting (supermodal/fit.h) and GLB animation export (supermodal/export.h).
#include "bindings.h"

#include <pybind11/numpy.h>
#include <supermodal/export.h>
#include <supermodal/fit.h>

namespace smpy
{
namespace
{

py::dict fit(const py::object& points_arg, const py::kwargs& kwargs)
{
    const std::vector<sm::Vec3> data = to_points(points_arg, "points");
    Kwargs kw("fit", kwargs);
    sm::FitDef def = sm::default_fit_def();
    def.taper = kw.flag("taper", def.taper);
    def.bend = kw.flag("bend", def.bend);
    def.epsilon_min = kw.number("epsilon_min", def.epsilon_min);
    def.epsilon_max = kw.number("epsilon_max", def.epsilon_max);
    def.max_iterations = kw.integer("max_iterations", def.max_iterations);
    def.max_points = kw.integer("max_points", def.max_points);
    def.acceptable_rms_relative = kw.number("acceptable_rms_relative", def.acceptable_rms_relative);
    kw.finish();
    sm::Result<sm::FitResult> r = [&] {
        py::gil_scoped_release release;
        return sm::fit_superquadric(data, def);
    }();
    if (!r)
        raise_argument(r.error().where.empty() ? "points" : r.error().where, r.error().what);
    py::dict body;
    body["radii"] = from_vec3(r->shape.radii);
    body["epsilon1"] = r->shape.epsilon1;
    body["epsilon2"] = r->shape.epsilon2;
    body["taper"] = py::make_tuple(r->shape.taper.kx, r->shape.taper.ky);
    body["bend"] = py::make_tuple(r->shape.bend.curvature, r->shape.bend.angle);
    body["position"] = from_vec3(r->position);
    body["orientation"] = from_quat(r->orientation);
    py::dict out;
    out["body"] = body;
    out["rms_m"] = r->rms_m;
    out["max_m"] = r->max_m;
    out["rms_relative"] = r->rms_relative;
    out["size_m"] = r->size_m;
    out["iterations"] = r->iterations;
    out["acceptable"] = r->acceptable;
    return out;
}

py::dict export_glb(WorldBox& box, const py::object& path_arg, const py::kwargs& kwargs)
{
    const std::string path = py::str(py::module_::import("os").attr("fspath")(path_arg));
    Kwargs kw("export_glb", kwargs);
    sm::ExportDef def = sm::default_export_def();
    def.seconds = kw.number("seconds", def.seconds);
    def.fps = kw.number("fps", def.fps);
    def.tessellation = kw.integer("tessellation", def.tessellation);
    def.morph_targets = kw.flag("morph_targets", def.morph_targets);
    kw.finish();
    check_status(sm::validate(def));
    // Recording steps the world; a refused or failed export puts it back as it was.
    const sm::Snapshot before = box.world.snapshot();
    sm::Result<sm::ExportRecording> rec = sm::record_animation(box.world, def);
    if (rec)
        if (sm::Status written = sm::write_glb(*rec, path); !written)
            rec = sm::Result<sm::ExportRecording>(written.error());
    if (!rec) {
        (void)box.world.restore(before);
        raise_argument(rec.error().where.empty() ? "path" : rec.error().where, rec.error().message());
    }
    py::dict out;
    out["frames"] = rec->times.size();
    out["bodies"] = rec->bodies.size();
    return out;
}

} // namespace

void register_assets(py::module_& m)
{
    m.def("fit", &fit, py::arg("points"),
          R"(Fits one superquadric to points, an (n, 3) array [m] (n >= 16, spanning 3-D). Keywords (FitDef):
taper [False], bend [False], epsilon_min [0.1], epsilon_max [2.0], max_iterations [200],
max_points [4000], acceptable_rms_relative [0.02]. Returns a dict: 'body' holds create_body keywords
(radii, epsilon1, epsilon2, taper, bend, position, orientation), then rms_m, max_m, rms_relative,
size_m, iterations and acceptable.)");
    auto world = py::reinterpret_borrow<py::class_<WorldBox, WorldPtr>>(m.attr("World"));
    world.def("export_glb", &export_glb, py::arg("path"),
              R"(Steps the world for `seconds` and writes the motion as glTF binary (GLB): one node per body,
morph targets for the modes. Keywords (ExportDef): seconds [1] s in (0, 3600], fps [30] in
(0, 1/dt], tessellation [32] in [8, 512], morph_targets [True]. The world ends `seconds` later; on
an error it is restored to where it was. Returns {'frames': n, 'bodies': n}.)");
}

} // namespace smpy
