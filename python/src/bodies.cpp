// SPDX-License-Identifier: MIT
// supermodal.Material, World.create_body / destroy_body and supermodal.Body: keyword arguments over
// BodyDef (and its ShapeDef and ModalBodyDef), queries and forces of one body.
#include "bindings.h"

#include <cmath>
#include <pybind11/numpy.h>
#include <pybind11/stl.h>
#include <vector>

namespace smpy
{
namespace
{

// Engine field names (Error::where) → the keyword that sets them.
constexpr std::initializer_list<std::pair<const char*, const char*>> k_body_fields = {
    {"shape.radii", "radii"},
    {"shape.exponents", "epsilon1"},
    {"shape.taper", "taper"},
    {"shape.bend", "bend"},
    {"shape.plane_normal", "plane_normal"},
    {"shape.plane_offset", "plane_offset"},
    {"pose", "position"},
    {"motion", "motion"},
    {"modal/damping_ratio", "damping_ratio"},
    {"modal/yield_stress", "yield_stress"},
    {"modal/hardening", "hardening"},
    {"modal/max_plastic_strain", "max_plastic_strain"},
    {"modal/adaptive_tolerance", "adaptive_tolerance"},
    {"modal/remould_threshold", "remould_threshold"},
    {"modal/mode_count", "mode_count"},
};

void check_range(bool ok, const char* argument, const char* expected)
{
    if (!ok)
        raise_argument(argument, std::string("expected ") + expected);
}

sm::MaterialDef make_material(const py::kwargs& kwargs)
{
    Kwargs kw("Material", kwargs);
    sm::MaterialDef m;
    m.name = kw.text("name", m.name);
    m.density = kw.number("density", m.density);
    m.young = kw.number("young", m.young);
    m.poisson = kw.number("poisson", m.poisson);
    m.friction = kw.number("friction", m.friction);
    m.restitution = kw.number("restitution", m.restitution);
    m.rolling_resistance = kw.number("rolling_resistance", m.rolling_resistance);
    m.damping_ratio = kw.number("damping_ratio", m.damping_ratio);
    m.yield_stress = kw.number_or_inf("yield_stress", m.yield_stress);
    m.hardening = kw.number("hardening", m.hardening);
    m.max_plastic_strain = kw.number_or_inf("max_plastic_strain", m.max_plastic_strain);
    m.remould_threshold = kw.number("remould_threshold", m.remould_threshold);
    kw.finish();
    // The scene loader's ranges for a material (docs/scene_format.md).
    check_range(m.density > 0.0, "density", "a density > 0 kg/m^3");
    check_range(m.young > 0.0, "young", "a Young's modulus > 0 Pa");
    check_range(m.poisson > -1.0 && m.poisson < 0.5, "poisson", "a Poisson's ratio in (-1, 0.5)");
    check_range(m.friction >= 0.0, "friction", "a friction coefficient >= 0");
    check_range(m.restitution >= 0.0 && m.restitution <= 1.0, "restitution", "a restitution in [0, 1]");
    check_range(m.rolling_resistance >= 0.0, "rolling_resistance", "a rolling resistance >= 0 m");
    check_range(m.damping_ratio >= 0.0, "damping_ratio", "a damping ratio >= 0");
    check_range(m.yield_stress > 0.0, "yield_stress", "a yield stress > 0 Pa (inf: elastic)");
    check_range(m.hardening >= 0.0, "hardening", "a hardening modulus >= 0 Pa");
    check_range(m.max_plastic_strain > 0.0, "max_plastic_strain", "a plastic strain limit > 0 (inf: none)");
    check_range(m.remould_threshold >= 0.0, "remould_threshold", "a rest-shape change >= 0 (0: never)");
    return m;
}

void apply_material(const sm::MaterialDef& m, sm::BodyDef& def)
{
    def.density = m.density;
    def.young = m.young;
    def.poisson = m.poisson;
    def.friction = m.friction;
    def.restitution = m.restitution;
    def.rolling_resistance = m.rolling_resistance;
    def.modal.damping_ratio = m.damping_ratio;
    def.modal.yield_stress = m.yield_stress;
    def.modal.hardening = m.hardening;
    def.modal.max_plastic_strain = m.max_plastic_strain;
    def.modal.remould_threshold = m.remould_threshold;
}

void read_shape(Kwargs& kw, sm::ShapeDef& s)
{
    s.type = kw.choice("shape", s.type,
                       {{"superquadric", sm::ShapeType::Superquadric}, {"plane", sm::ShapeType::Plane}});
    s.radii = kw.vec3("radii", s.radii);
    s.epsilon1 = kw.number("epsilon1", s.epsilon1);
    s.epsilon2 = kw.number("epsilon2", s.epsilon2);
    if (kw.has("taper")) {
        const py::object t = kw.object("taper");
        if (PyUnicode_Check(t.ptr()) || !PySequence_Check(t.ptr()) || py::len(t) != 2)
            raise_type("taper", "expected (kx, ky)");
        s.taper = {to_number(t[py::int_(0)], "taper[0]"), to_number(t[py::int_(1)], "taper[1]")};
    }
    if (kw.has("bend")) {
        const py::object b = kw.object("bend");
        if (PyUnicode_Check(b.ptr()) || !PySequence_Check(b.ptr()) || py::len(b) != 2)
            raise_type("bend", "expected (curvature, angle)");
        s.bend = {to_number(b[py::int_(0)], "bend[0]"), to_number(b[py::int_(1)], "bend[1]")};
    }
    s.plane_normal = kw.vec3("plane_normal", s.plane_normal);
    s.plane_offset = kw.number("plane_offset", s.plane_offset);
}

void read_modal(Kwargs& kw, sm::ModalBodyDef& m)
{
    m.enabled = kw.flag("modal", m.enabled);
    m.mode_count = kw.integer("mode_count", m.mode_count);
    if (kw.has("lattice")) {
        const sm::Vec3 l = kw.vec3("lattice", {});
        for (int i = 0; i < 3; ++i) {
            if (l[i] != std::floor(l[i]) || l[i] < 0 || l[i] > 128)
                raise_argument("lattice", "expected 3 integers in [0, 128] (0: from the aspect ratio)");
            m.lattice[static_cast<size_t>(i)] = static_cast<int>(l[i]);
        }
    }
    m.integrator = kw.choice("modal_integrator", m.integrator,
                             {{"exact", sm::ModalIntegrator::Exact},
                              {"central_difference", sm::ModalIntegrator::CentralDifference}});
    m.damping_ratio = kw.number("damping_ratio", m.damping_ratio);
    m.yield_stress = kw.number_or_inf("yield_stress", m.yield_stress);
    m.hardening = kw.number("hardening", m.hardening);
    m.max_plastic_strain = kw.number_or_inf("max_plastic_strain", m.max_plastic_strain);
    m.adaptive_tolerance = kw.number("adaptive_tolerance", m.adaptive_tolerance);
    m.remould_threshold = kw.number("remould_threshold", m.remould_threshold);
    m.static_correction = kw.flag("static_correction", m.static_correction);
}

sm::BodyDef read_body_def(const py::kwargs& kwargs)
{
    Kwargs kw("create_body", kwargs);
    sm::BodyDef def = sm::default_body_def();
    if (const py::object m = kw.object("material"); !m.is_none()) {
        if (!py::isinstance<sm::MaterialDef>(m))
            raise_type("material", "expected a supermodal.Material");
        apply_material(m.cast<const sm::MaterialDef&>(), def);
    }
    def.name = kw.text("name", def.name);
    def.motion = kw.choice("motion", def.motion,
                           {{"dynamic", sm::MotionType::Dynamic},
                            {"static", sm::MotionType::Static},
                            {"kinematic", sm::MotionType::Kinematic}});
    read_shape(kw, def.shape);
    def.density = kw.number("density", def.density);
    def.position = kw.vec3("position", def.position);
    def.orientation = kw.quat("orientation", def.orientation);
    def.linear_velocity = kw.vec3("linear_velocity", def.linear_velocity);
    def.angular_velocity = kw.vec3("angular_velocity", def.angular_velocity);
    def.gravity_scale = kw.number("gravity_scale", def.gravity_scale);
    def.friction = kw.number("friction", def.friction);
    def.restitution = kw.number("restitution", def.restitution);
    def.young = kw.number("young", def.young);
    def.poisson = kw.number("poisson", def.poisson);
    def.rolling_resistance = kw.number("rolling_resistance", def.rolling_resistance);
    def.allow_sleep = kw.flag("allow_sleep", def.allow_sleep);
    read_modal(kw, def.modal);
    kw.finish();
    return def;
}

Body create_body(const WorldPtr& box, const py::kwargs& kwargs)
{
    const sm::BodyDef def = read_body_def(kwargs);
    check_status(sm::validate(def), k_body_fields);
    if (!def.name.empty() && !sm::find_body(box->world, def.name).is_null())
        raise_argument("name", "a body named '" + def.name + "' exists already");
    if (def.modal.enabled) // the basis build can fail (too many modes for the lattice): ask first
        if (auto basis = sm::modal_basis_for(box->world, def); !basis)
            raise_argument("mode_count", "no modal basis for this body: " + basis.error().message());
    const sm::Entity e = sm::create_body(box->world, def);
    if (e.is_null())
        raise_state("the body was refused");
    return Body{box, e};
}

void destroy_body(WorldBox& box, const Body& body)
{
    if (body.box.get() != &box)
        raise_argument("body", "a body of another world");
    sm::destroy_body(box.world, live(body));
}

// A world-frame vector argument applied to a live body.
template <class Fn> void with_vec3(const Body& b, const py::handle& v, const char* name, Fn fn)
{
    const sm::Entity e = live(b);
    fn(b.box->world, e, to_vec3(v, name));
}

py::array_t<double> modal_vector(const Body& b, bool rates)
{
    sm::BodyModalState s = sm::body_modal_state(b.box->world, live(b));
    auto* kept = new std::vector<double>(rates ? std::move(s.velocities) : std::move(s.amplitudes));
    py::capsule owner(kept, [](void* p) { delete static_cast<std::vector<double>*>(p); });
    py::array_t<double> out({static_cast<py::ssize_t>(kept->size())}, {sizeof(double)}, kept->data(), owner);
    py::detail::array_proxy(out.ptr())->flags &= ~py::detail::npy_api::NPY_ARRAY_WRITEABLE_;
    return out;
}

// Per mode, the displacement of each point for a unit amplitude: what an animation tool stores as one
// shape key (morph target) per mode, driven by the amplitudes. (r, n, 3); (0, n, 3) for a rigid body.
py::array_t<double> mode_shapes(const Body& b, const py::object& points_arg)
{
    const sm::Entity e = live(b);
    const std::vector<sm::Vec3> points = to_points(points_arg, "points");
    const auto n = static_cast<py::ssize_t>(points.size());
    const sm::ModalBasis* basis = sm::body_modal_basis(b.box->world, e);
    const py::ssize_t r = basis == nullptr ? 0 : basis->mode_count;
    py::array_t<double> out({r, n, py::ssize_t{3}});
    auto o = out.mutable_unchecked<3>();
    std::vector<double> unit(static_cast<size_t>(r), 0.0);
    for (py::ssize_t i = 0; i < n && r > 0; ++i) {
        const sm::LatticeWeights w = sm::modal_weights(*basis, points[static_cast<size_t>(i)]);
        for (py::ssize_t k = 0; k < r; ++k) {
            unit[static_cast<size_t>(k)] = 1.0;
            const sm::Vec3 d = sm::modal_displacement(*basis, w, unit);
            unit[static_cast<size_t>(k)] = 0.0;
            o(k, i, 0) = d.x;
            o(k, i, 1) = d.y;
            o(k, i, 2) = d.z;
        }
    }
    return out;
}

} // namespace

sm::Entity live(const Body& body)
{
    if (!sm::world_valid(body.box->world, body.entity))
        raise_state("the body was destroyed");
    return body.entity;
}

void register_bodies(py::module_& m)
{
    py::class_<sm::MaterialDef>(m, "Material",
                                R"(A named material (MaterialDef), for World.create_body(material=...).

Keywords (defaults in brackets): name [''], density [1000] kg/m^3 > 0, young [1e9] Pa > 0,
poisson [0.3] in (-1, 0.5), friction [0.5] >= 0, restitution [0.2] in [0, 1], rolling_resistance [0] m
>= 0, damping_ratio [0.01] >= 0 (modal), yield_stress [inf] Pa > 0, hardening [0] Pa >= 0,
max_plastic_strain [inf] > 0, remould_threshold [0.02] >= 0 (0: never). Read-only once made.)")
        .def(py::init(&make_material))
        .def_readonly("name", &sm::MaterialDef::name)
        .def_readonly("density", &sm::MaterialDef::density)
        .def_readonly("young", &sm::MaterialDef::young)
        .def_readonly("poisson", &sm::MaterialDef::poisson)
        .def_readonly("friction", &sm::MaterialDef::friction)
        .def_readonly("restitution", &sm::MaterialDef::restitution)
        .def_readonly("rolling_resistance", &sm::MaterialDef::rolling_resistance)
        .def_readonly("damping_ratio", &sm::MaterialDef::damping_ratio)
        .def_readonly("yield_stress", &sm::MaterialDef::yield_stress)
        .def_readonly("hardening", &sm::MaterialDef::hardening)
        .def_readonly("max_plastic_strain", &sm::MaterialDef::max_plastic_strain)
        .def_readonly("remould_threshold", &sm::MaterialDef::remould_threshold)
        .def("__repr__", [](const sm::MaterialDef& d) {
            return "Material(name='" + d.name + "', density=" + std::string(py::str(py::float_(d.density))) +
                   ")";
        });

    py::class_<Body> b(
        m, "Body", "A body of a World (a handle; it keeps its world alive). Made by World.create_body().");
    b.def_property_readonly("name", [](const Body& x) { return sm::body_name(x.box->world, live(x)); });
    b.def_property_readonly(
        "index", [](const Body& x) { return x.entity.index; },
        "Entity slot index: the order of World.bodies and of the arrays.");
    b.def_property_readonly(
        "valid", [](const Body& x) { return sm::world_valid(x.box->world, x.entity); },
        "False once destroyed.");
    b.def_property_readonly(
        "motion", [](const Body& x) { return motion_name(sm::body_motion(x.box->world, live(x))); });
    b.def_property_readonly(
        "mass", [](const Body& x) { return sm::body_mass_properties(x.box->world, live(x)).mass; },
        "[kg]; 0 for static and kinematic bodies' infinite mass.");
    b.def_property(
        "position", [](const Body& x) { return from_vec3(sm::body_position(x.box->world, live(x))); },
        [](const Body& x, py::object v) { with_vec3(x, v, "position", sm::set_body_position); },
        "Shape origin [m], world frame (x, y, z).");
    b.def_property(
        "orientation", [](const Body& x) { return from_quat(sm::body_orientation(x.box->world, live(x))); },
        [](const Body& x, py::object v) {
            const sm::Entity e = live(x);
            sm::set_body_orientation(x.box->world, e, sm::normalized(to_quat(v, "orientation")));
        },
        "world_from_body rotation, unit quaternion (w, x, y, z); set values are normalised.");
    b.def_property(
        "linear_velocity",
        [](const Body& x) { return from_vec3(sm::body_linear_velocity(x.box->world, live(x))); },
        [](const Body& x, py::object v) { with_vec3(x, v, "linear_velocity", sm::set_body_linear_velocity); },
        "Of the centre of mass [m/s], world frame.");
    b.def_property(
        "angular_velocity",
        [](const Body& x) { return from_vec3(sm::body_angular_velocity(x.box->world, live(x))); },
        [](const Body& x, py::object v) {
            with_vec3(x, v, "angular_velocity", sm::set_body_angular_velocity);
        },
        "[rad/s], world frame.");
    b.def_property_readonly(
        "center_of_mass",
        [](const Body& x) { return from_vec3(sm::body_center_of_mass(x.box->world, live(x))); },
        "[m], world frame.");
    b.def_property_readonly(
        "kinetic_energy", [](const Body& x) { return sm::body_kinetic_energy(x.box->world, live(x)); },
        "[J].");
    b.def_property_readonly(
        "potential_energy", [](const Body& x) { return sm::body_potential_energy(x.box->world, live(x)); },
        "Gravitational potential energy -m g.x relative to the world origin [J]; 0 unless dynamic.");
    b.def_property_readonly("awake", [](const Body& x) { return sm::body_is_awake(x.box->world, live(x)); });
    b.def(
        "wake", [](const Body& x) { sm::wake_body(x.box->world, live(x)); },
        "Wakes the body and its island.");
    b.def_property_readonly(
        "interpolated_position",
        [](const Body& x) { return from_vec3(sm::body_interpolated_position(x.box->world, live(x))); },
        "Position blended by World.interpolation_alpha [m], for drawing between steps.");
    b.def_property_readonly("interpolated_orientation", [](const Body& x) {
        return from_quat(sm::body_interpolated_orientation(x.box->world, live(x)));
    });
    b.def_property_readonly(
        "mode_count",
        [](const Body& x) { return sm::body_modal_state(x.box->world, live(x)).amplitudes.size(); },
        "Modes r of a modal body; 0 when rigid.");
    b.def_property_readonly(
        "modal_amplitudes", [](const Body& x) { return modal_vector(x, false); },
        "(r,) float64, read-only: modal amplitudes q [sqrt(kg)*m]; empty when rigid. A copy "
        "the engine makes (body_modal_state), handed to numpy without a second copy.");
    b.def_property_readonly(
        "modal_velocities", [](const Body& x) { return modal_vector(x, true); },
        "(r,) float64, read-only: modal rates [sqrt(kg)*m/s]; a copy as modal_amplitudes.");
    b.def("mode_shapes", &mode_shapes, py::arg("points"),
          "(r, n, 3) float64: per mode k, the displacement [m] of each rest point of `points` ((n, 3) [m], "
          "shape frame) for q_k = 1 sqrt(kg)*m, shape frame; the deformed point is p + sum_k q_k "
          "mode_shapes[k]. (0, n, 3) for a rigid body.");
    b.def(
        "apply_force",
        [](const Body& x, py::object force, py::object point) {
            const sm::Entity e = live(x);
            const sm::Vec3 f = to_vec3(force, "force");
            if (point.is_none())
                sm::apply_force_at_center(x.box->world, e, f);
            else
                sm::apply_force(x.box->world, e, f, to_vec3(point, "point"));
        },
        py::arg("force"), py::arg("point") = py::none(),
        "Adds a force [N] for the next step, world frame, at `point` [m] (world) or the centre of mass.");
    b.def(
        "apply_torque", [](const Body& x, py::object t) { with_vec3(x, t, "torque", sm::apply_torque); },
        py::arg("torque"), "Adds a torque [N*m], world frame, for the next step.");
    b.def(
        "apply_impulse",
        [](const Body& x, py::object impulse, py::object point) {
            const sm::Entity e = live(x);
            const sm::Vec3 j = to_vec3(impulse, "impulse");
            const sm::Vec3 p =
                point.is_none() ? sm::body_center_of_mass(x.box->world, e) : to_vec3(point, "point");
            sm::apply_linear_impulse(x.box->world, e, j, p);
        },
        py::arg("impulse"), py::arg("point") = py::none(),
        "Changes momentum at once by an impulse [N*s] at `point` [m] (world; default the centre of mass).");
    b.def("__eq__", [](const Body& x, const Body& y) { return x.box == y.box && x.entity == y.entity; });
    b.def("__hash__", [](const Body& x) {
        return py::hash(
            py::make_tuple(reinterpret_cast<uintptr_t>(x.box.get()), x.entity.index, x.entity.generation));
    });
    b.def("__repr__", [](const Body& x) {
        const bool ok = sm::world_valid(x.box->world, x.entity);
        return "Body(index=" + std::to_string(x.entity.index) +
               (ok ? ", name='" + sm::body_name(x.box->world, x.entity) + "')" : ", destroyed)");
    });

    auto world = py::reinterpret_borrow<py::class_<WorldBox, WorldPtr>>(m.attr("World"));
    world.def("create_body", &create_body,
              R"(Makes a body from keywords mirroring BodyDef (defaults in brackets).

material: a supermodal.Material whose fields come first (explicit keywords override them).
name [''] (unique when given); motion ['dynamic'|'static'|'kinematic'].
shape ['superquadric'|'plane']; radii [(0.5, 0.5, 0.5)] m > 0; epsilon1, epsilon2 [1] in (0, 4];
taper [(0, 0)] in [-1, 1]; bend [(0, 0)]: (curvature 1/m >= 0, angle rad); plane_normal [(0, 1, 0)];
plane_offset [0] m (planes are static).
density [1000] kg/m^3 > 0; position [(0, 0, 0)] m; orientation [(1, 0, 0, 0)] (w, x, y, z);
linear_velocity [(0, 0, 0)] m/s; angular_velocity [(0, 0, 0)] rad/s; gravity_scale [1];
friction [0.5] >= 0; restitution [0.2] in [0, 1]; young [1e9] Pa > 0; poisson [0.3] in (-1, 0.5);
rolling_resistance [0] m >= 0; allow_sleep [True].
modal [False]: deform through the lowest modes; mode_count [12] in [1, 256] (0: all);
lattice [(0, 0, 0)] cells per axis in [0, 128] (0: from the aspect ratio);
modal_integrator ['exact'|'central_difference']; damping_ratio [0.01] >= 0; yield_stress [inf] Pa;
hardening [0] Pa; max_plastic_strain [inf]; adaptive_tolerance [0] m (> 0: adaptive modes);
remould_threshold [0.02] >= 0 (rest-shape change past which the modes are rebuilt; 0: never);
static_correction [False]: add the static answer of the modes left out to the surface (mode acceleration).

Raises ArgumentError / ArgumentTypeError naming the keyword; the world is then unchanged.)");
    world.def("destroy_body", &destroy_body, py::arg("body"), "Destroys a body; its handles become invalid.");
    world.def_property_readonly(
        "bodies",
        [](const WorldPtr& box) {
            py::list out;
            for (sm::Entity e : sm::world_bodies(box->world))
                out.append(Body{box, e});
            return out;
        },
        "Live bodies in entity-index order (the order of the pose arrays).");
    world.def(
        "find_body",
        [](const WorldPtr& box, py::object name) -> py::object {
            const sm::Entity e = sm::find_body(box->world, to_text(name, "name"));
            return e.is_null() ? py::none() : py::cast(Body{box, e});
        },
        py::arg("name"), "The body with this name, or None.");
}

} // namespace smpy
