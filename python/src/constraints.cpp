// SPDX-License-Identifier: MIT
// World.create_constraint and supermodal.Constraint: keyword arguments over ConstraintDef.
#include "bindings.h"

#include <pybind11/stl.h>

namespace smpy
{
namespace
{

constexpr std::initializer_list<std::pair<const char*, const char*>> k_constraint_fields = {
    {"frequency", "frequency_hz"},
};

// An anchor: a point (x, y, z) in the body's shape frame, or a dict {"point": ...}, {"direction": ...}
// or {"eta": ..., "omega": ...} (AnchorDef kinds).
sm::AnchorDef read_anchor(const py::object& value, const std::string& argument)
{
    sm::AnchorDef a;
    if (!py::isinstance<py::dict>(value)) {
        a.point = to_vec3(value, argument);
        return a;
    }
    py::kwargs kwargs = py::reinterpret_borrow<py::kwargs>(value);
    Kwargs kw(argument.c_str(), kwargs);
    if (kw.has("point")) {
        a.point = kw.vec3("point", a.point);
    } else if (kw.has("direction")) {
        a.kind = sm::AnchorKind::Direction;
        a.direction = kw.vec3("direction", a.direction);
    } else if (kw.has("eta") || kw.has("omega")) {
        a.kind = sm::AnchorKind::Surface;
        a.eta = kw.number("eta", 0.0);
        a.omega = kw.number("omega", 0.0);
    }
    kw.finish();
    return a;
}

sm::Entity body_argument(const WorldBox& box, const py::object& value, const char* argument)
{
    if (!py::isinstance<Body>(value))
        raise_type(argument, "expected a supermodal.Body");
    const Body& b = value.cast<const Body&>();
    if (b.box.get() != &box)
        raise_argument(argument, "a body of another world");
    if (!sm::world_valid(box.world, b.entity))
        raise_argument(argument, "the body was destroyed");
    return b.entity;
}

Constraint create_constraint(const WorldPtr& box, const py::kwargs& kwargs)
{
    Kwargs kw("create_constraint", kwargs);
    sm::ConstraintDef def = sm::default_constraint_def();
    def.name = kw.text("name", def.name);
    def.type = kw.choice("type", def.type,
                         {{"point", sm::ConstraintType::Point},
                          {"distance", sm::ConstraintType::Distance},
                          {"weld", sm::ConstraintType::Weld}});
    if (!kw.has("a"))
        raise_type("a", "create_constraint() needs the body a");
    def.a = body_argument(*box, kw.object("a"), "a");
    if (const py::object b = kw.object("b"); !b.is_none())
        def.b = body_argument(*box, b, "b");
    if (kw.has("anchor_a"))
        def.anchor_a = read_anchor(kw.object("anchor_a"), "anchor_a");
    if (kw.has("anchor_b"))
        def.anchor_b = read_anchor(kw.object("anchor_b"), "anchor_b");
    def.frequency_hz = kw.number("frequency_hz", def.frequency_hz);
    def.damping_ratio = kw.number("damping_ratio", def.damping_ratio);
    def.rest_length = kw.number("rest_length", def.rest_length);
    def.swing_limit = kw.number("swing_limit", def.swing_limit);
    def.twist_limit = kw.number("twist_limit", def.twist_limit);
    def.axis_a = kw.vec3("axis_a", def.axis_a);
    def.angular_damping = kw.number("angular_damping", def.angular_damping);
    def.break_force = kw.number_or_inf("break_force", def.break_force);
    def.collide_connected = kw.flag("collide_connected", def.collide_connected);
    kw.finish();
    check_status(sm::validate(def), k_constraint_fields);
    const sm::Constraint c = sm::create_constraint(box->world, def);
    if (c.is_null())
        raise_state("the constraint was refused");
    return Constraint{box, c};
}

} // namespace

sm::Constraint live(const Constraint& constraint)
{
    if (!sm::world_valid(constraint.box->world, constraint.handle))
        raise_state("the constraint was destroyed");
    return constraint.handle;
}

void register_constraints(py::module_& m)
{
    py::class_<Constraint> c(m, "Constraint",
                             "A joint of a World (a handle). Made by World.create_constraint().");
    c.def_property_readonly(
        "name", [](const Constraint& x) { return sm::constraint_def(x.box->world, live(x)).name; });
    c.def_property_readonly("valid",
                            [](const Constraint& x) { return sm::world_valid(x.box->world, x.handle); });
    c.def_property_readonly(
        "broken", [](const Constraint& x) { return sm::constraint_broken(x.box->world, live(x)); },
        "True once its force passed break_force.");
    c.def_property_readonly(
        "force", [](const Constraint& x) { return from_vec3(sm::constraint_force(x.box->world, live(x))); },
        "Spring force on body a in the last substep [N], world frame.");
    c.def_property_readonly(
        "error",
        [](const Constraint& x) {
            const sm::ConstraintError e = sm::constraint_error(x.box->world, live(x));
            return py::make_tuple(e.linear, e.angular);
        },
        "(linear [m], angular [rad]) distance from holding after the last step.");
    c.def("__eq__",
          [](const Constraint& x, const Constraint& y) { return x.box == y.box && x.handle == y.handle; });
    c.def("__hash__", [](const Constraint& x) {
        return py::hash(
            py::make_tuple(reinterpret_cast<uintptr_t>(x.box.get()), x.handle.index, x.handle.generation));
    });

    auto world = py::reinterpret_borrow<py::class_<WorldBox, WorldPtr>>(m.attr("World"));
    world.def("create_constraint", &create_constraint, R"(Makes a joint from keywords mirroring ConstraintDef.

type ['point'|'distance'|'weld']; a (a Body, required); b [None: the world]; name [''].
anchor_a, anchor_b [(0, 0, 0)]: a point in the body's shape frame [m] (in the world when b is None),
  or {'direction': (x, y, z)} (where that ray leaves the surface), or {'eta': rad, 'omega': rad}.
frequency_hz [30] Hz > 0; damping_ratio [0.7] >= 0; rest_length [-1] m (< 0: as created);
swing_limit, twist_limit [-1] rad (< 0: none; point joints); axis_a [(0, 0, 0)]: limit axis;
angular_damping [0] 1/s >= 0; break_force [inf] N > 0; collide_connected [False].

Raises ArgumentError / ArgumentTypeError naming the keyword; the world is then unchanged.)");
    world.def(
        "destroy_constraint",
        [](WorldBox& box, const Constraint& x) {
            if (x.box.get() != &box)
                raise_argument("constraint", "a constraint of another world");
            sm::destroy_constraint(box.world, live(x));
        },
        py::arg("constraint"));
    world.def_property_readonly(
        "constraints",
        [](const WorldPtr& box) {
            py::list out;
            for (sm::Constraint h : sm::world_constraints(box->world))
                out.append(Constraint{box, h});
            return out;
        },
        "Live constraints in index order.");
}

} // namespace smpy
