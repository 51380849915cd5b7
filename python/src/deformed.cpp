// SPDX-License-Identifier: MIT
// Deformed points as numpy arrays: Body.deformed_points (a fresh array, point by point through
// body_deformed_point), Body.track_points (supermodal.DeformedPoints: the lattice weights found once,
// one buffer refilled by update() and shared with numpy without a copy) and Body.render_mesh.
#include "bindings.h"

#include <algorithm>
#include <cmath>
#include <pybind11/numpy.h>
#include <string>
#include <vector>

namespace smpy
{
namespace
{

static_assert(sizeof(sm::Vec3) == 3 * sizeof(double), "Vec3 rows are viewed as (n, 3) float64");

/// Rest points of one body with their lattice weights, and the buffer of their deformed positions.
struct DeformedPoints {
    WorldPtr box;
    sm::Entity entity;
    std::vector<sm::Vec3> rest;              ///< [m], shape frame.
    const sm::ModalBasis* basis = nullptr;   ///< The basis `weights` were found in; null: rigid.
    std::vector<sm::LatticeWeights> weights; ///< Per rest point; empty when rigid.
    std::vector<sm::Vec3> nodal;             ///< Scratch: the lattice nodes' displacements [m].
    std::vector<sm::Vec3> positions;         ///< [m], world frame; sized once, so views stay valid.
};

void read_only(py::array& a)
{
    py::detail::array_proxy(a.ptr())->flags &= ~py::detail::npy_api::NPY_ARRAY_WRITEABLE_;
}

// An (n, 3) float64 view of Vec3 rows owned by `base`.
py::array view(const std::vector<sm::Vec3>& rows, const py::handle& base)
{
    py::array out(py::dtype::of<double>(), {static_cast<py::ssize_t>(rows.size()), py::ssize_t{3}},
                  {static_cast<py::ssize_t>(sizeof(sm::Vec3)), static_cast<py::ssize_t>(sizeof(double))},
                  rows.data(), base);
    read_only(out);
    return out;
}

// (Re)finds the weights when the body's basis is not the one they were found in.
void match_basis(DeformedPoints& d)
{
    const sm::ModalBasis* now = sm::body_modal_basis(d.box->world, d.entity);
    if (now == d.basis && (now == nullptr || d.weights.size() == d.rest.size()))
        return;
    d.weights.clear();
    if (now != nullptr) {
        d.weights.reserve(d.rest.size());
        for (const sm::Vec3& p : d.rest)
            d.weights.push_back(sm::modal_weights(*now, p));
    }
    d.basis = now;
}

// body_deformed_point's formula with the weights found once and the modes summed once per lattice node
// (modal_nodal_displacements): the same products in the same order, so the same bits.
void update(DeformedPoints& d)
{
    const sm::Entity e = live(Body{d.box, d.entity});
    const sm::World& w = d.box->world;
    match_basis(d);
    const sm::Vec3 centre = sm::body_center_of_mass(w, e);
    const sm::Quat orientation = sm::body_orientation(w, e);
    const sm::Vec3 com = sm::body_mass_properties(w, e).center_of_mass;
    // A remoulded body's rest offsets and the static correction, added as body_deformed_point does.
    std::vector<sm::Vec3> moulded, correction;
    if (d.basis != nullptr) {
        sm::modal_nodal_displacements(*d.basis, sm::body_modal_state(w, e).amplitudes, d.nodal);
        moulded = sm::body_remould(w, e).rest_offsets;
        correction = sm::body_static_correction(w, e);
    }
    for (size_t i = 0; i < d.rest.size(); ++i) {
        sm::Vec3 local = d.rest[i] - com;
        if (d.basis != nullptr)
            local += sm::interpolate_nodal(d.weights[i], d.nodal);
        if (!correction.empty())
            local += sm::interpolate_nodal(d.weights[i], correction);
        if (!moulded.empty())
            local += sm::interpolate_nodal(d.weights[i], moulded);
        d.positions[i] = centre + sm::rotate(orientation, local);
    }
}

// A writable, C-contiguous (n, 3) float64 array to fill, or a TypeError/ArgumentError naming `out`.
py::array_t<double> check_out(const py::object& out, py::ssize_t n)
{
    if (!py::isinstance<py::array_t<double>>(out) || !(py::array(out).flags() & py::array::c_style) ||
        !py::array(out).writeable())
        raise_type("out", "expected a writable C-contiguous float64 numpy array");
    py::array_t<double> a = py::reinterpret_borrow<py::array_t<double>>(out);
    if (a.ndim() != 2 || a.shape(0) != n || a.shape(1) != 3)
        raise_argument("out", "expected shape (" + std::to_string(n) + ", 3), as points");
    return a;
}

py::array_t<double> deformed_points(const Body& b, const py::object& points_arg, const py::object& out_arg)
{
    const sm::Entity e = live(b);
    const std::vector<sm::Vec3> points = to_points(points_arg, "points");
    const auto n = static_cast<py::ssize_t>(points.size());
    py::array_t<double> out =
        out_arg.is_none() ? py::array_t<double>({n, py::ssize_t{3}}) : check_out(out_arg, n);
    double* o = out.mutable_data(); // written only after every check passed
    for (const sm::Vec3& p : points) {
        const sm::Vec3 q = sm::body_deformed_point(b.box->world, e, p);
        *o++ = q.x;
        *o++ = q.y;
        *o++ = q.z;
    }
    return out;
}

DeformedPoints track_points(const Body& b, const py::object& points_arg)
{
    DeformedPoints d{b.box, live(b), to_points(points_arg, "points"), nullptr, {}, {}, {}};
    d.positions.resize(d.rest.size());
    update(d);
    return d;
}

// The scene's render mesh of a body: (vertices (n, 3) [m] shape frame, triangles (m, 3)), copies.
py::object render_mesh(const Body& b)
{
    const auto it = b.box->render_meshes.find(live(b));
    if (it == b.box->render_meshes.end())
        return py::none();
    const sm::TriangleMesh& mesh = *it->second;
    py::array vertices = view(mesh.positions, py::handle()); // no base: numpy copies the rows
    py::array_t<uint32_t> triangles({static_cast<py::ssize_t>(mesh.indices.size() / 3), py::ssize_t{3}});
    std::copy(mesh.indices.begin(), mesh.indices.end(), triangles.mutable_data());
    read_only(triangles);
    return py::make_tuple(vertices, triangles);
}

} // namespace

std::vector<sm::Vec3> to_points(const py::object& value, const std::string& argument)
{
    // Real numbers only (no bools, strings or complex numbers), then float64 rows.
    py::array raw;
    try {
        raw = py::array::ensure(value);
    } catch (const py::error_already_set&) {
    }
    if (!raw || std::string("iuf").find(raw.dtype().kind()) == std::string::npos || raw.ndim() != 2 ||
        raw.shape(1) != 3)
        raise_type(argument, "expected an (n, 3) array of real numbers");
    const auto points = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(raw);
    const auto p = points.unchecked<2>();
    std::vector<sm::Vec3> out(static_cast<size_t>(p.shape(0)));
    for (py::ssize_t i = 0; i < p.shape(0); ++i) {
        out[static_cast<size_t>(i)] = {p(i, 0), p(i, 1), p(i, 2)};
        if (!std::isfinite(p(i, 0)) || !std::isfinite(p(i, 1)) || !std::isfinite(p(i, 2)))
            raise_argument(argument, "row " + std::to_string(i) + " is not finite");
    }
    return out;
}

void register_deformed(py::module_& m)
{
    py::class_<DeformedPoints>(
        m, "DeformedPoints",
        R"(Rest points of one body and their deformed positions, made by Body.track_points.

The lattice weights of each point are found once; update() then costs one modal sum per lattice node
and 20 weights per point, and refills one buffer owned by this object. `array` and update()'s result are
read-only numpy views of that buffer, not copies: they change at the next update() (copy one with
numpy.array(view) to keep it) and keep this object and its buffer alive as long as they exist.
The buffer is not refreshed by stepping; call update() after World.step().)")
        .def(
            "update",
            [](py::object self) {
                DeformedPoints& d = self.cast<DeformedPoints&>();
                update(d);
                return view(d.positions, self);
            },
            "Refills the buffer from the body's current pose and modal amplitudes and returns its view: "
            "(n, 3) float64, read-only, world frame [m], equal bit for bit to Body.deformed_points(rest).")
        .def_property_readonly(
            "array", [](py::object self) { return view(self.cast<DeformedPoints&>().positions, self); },
            "(n, 3) float64 read-only view of the buffer as the last update() left it (no copy).")
        .def_property_readonly(
            "rest", [](const DeformedPoints& d) { return view(d.rest, py::handle()); },
            "(n, 3) float64 read-only copy of the rest points [m], shape frame.")
        .def_property_readonly(
            "body",
            [](const DeformedPoints& d) {
                return Body{d.box, d.entity};
            },
            "The body tracked.")
        .def("__len__", [](const DeformedPoints& d) { return d.rest.size(); })
        .def("__repr__", [](const DeformedPoints& d) {
            return "DeformedPoints(points=" + std::to_string(d.rest.size()) +
                   ", body=" + std::to_string(d.entity.index) + ")";
        });

    auto body = py::reinterpret_borrow<py::class_<Body>>(m.attr("Body"));
    body.def("deformed_points", &deformed_points, py::arg("points"), py::arg("out") = py::none(),
             "(n, 3) float64: where the material points with rest positions `points` ((n, 3) [m], shape "
             "frame) are now [m], world frame: the pose plus the modal displacement (body_deformed_point, "
             "point by point), the pose alone for a rigid body. `out`: a writable C-contiguous (n, 3) "
             "float64 array to fill and return instead of a new one. For the same points every frame, "
             "track_points is faster.");
    body.def("track_points", &track_points, py::arg("points"),
             "A DeformedPoints for the rest points `points` ((n, 3) [m], shape frame), already updated: "
             "their weights found once, their deformed positions in a buffer numpy views share.");
    body.def_property_readonly(
        "render_mesh", &render_mesh,
        "(vertices, triangles): the scene's render mesh of this body (\"mesh\"), vertices (n, 3) float64 "
        "[m] in the shape frame (rest), triangles (m, 3) uint32; read-only copies. None without one. "
        "body.track_points(vertices) deforms it.");
}

} // namespace smpy
