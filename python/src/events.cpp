// SPDX-License-Identifier: MIT
// The last step's contact events, contacts and fault events as lists of small read-only objects.
#include "bindings.h"

#include <pybind11/stl.h>

namespace smpy
{
namespace
{

struct ContactEvent {
    std::string kind; ///< "begin", "persist", "end".
    Body a, b;
    py::tuple point, normal, impulse_on_a;
    double normal_impulse = 0.0, depth = 0.0;
};

struct Contact {
    Body a, b;
    py::tuple point, normal, force_on_a;
    double depth = 0.0;
    int point_count = 0;
};

struct FaultEvent {
    std::string kind; ///< "body_non_finite", "modal_non_finite".
    Body body;
    std::string stage;
    uint64_t step = 0;
    int substep = 0;
};

const char* event_kind(sm::ContactEventKind kind)
{
    switch (kind) {
    case sm::ContactEventKind::Begin:
        return "begin";
    case sm::ContactEventKind::Persist:
        return "persist";
    case sm::ContactEventKind::End:
        return "end";
    }
    return "begin";
}

py::list contact_events(const WorldPtr& box)
{
    py::list out;
    for (const sm::ContactEvent& e : sm::world_contact_events(box->world))
        out.append(ContactEvent{event_kind(e.kind), Body{box, e.a}, Body{box, e.b}, from_vec3(e.point),
                                from_vec3(e.normal), from_vec3(e.impulse_on_a), e.normal_impulse, e.depth});
    return out;
}

py::list contacts(const WorldPtr& box)
{
    py::list out;
    for (const sm::ContactInfo& c : sm::world_contacts(box->world))
        out.append(Contact{Body{box, c.a}, Body{box, c.b}, from_vec3(c.point), from_vec3(c.normal),
                           from_vec3(c.force_on_a), c.depth, c.point_count});
    return out;
}

py::list fault_events(const WorldPtr& box)
{
    py::list out;
    for (const sm::FaultEvent& f : sm::world_fault_events(box->world))
        out.append(FaultEvent{sm::fault_kind_name(f.kind), Body{box, f.body},
                              std::string(sm::stage_name(f.stage)), f.step, f.substep});
    return out;
}

} // namespace

void register_events(py::module_& m)
{
    py::class_<ContactEvent>(m, "ContactEvent", "One contact event of the last step (read-only).")
        .def_readonly("kind", &ContactEvent::kind, "'begin', 'persist' or 'end'.")
        .def_readonly("a", &ContactEvent::a, "Body of the lower entity index.")
        .def_readonly("b", &ContactEvent::b, "Body of the higher index (or the static one).")
        .def_readonly("point", &ContactEvent::point, "Contact point [m], world.")
        .def_readonly("normal", &ContactEvent::normal, "Unit normal from b towards a.")
        .def_readonly("impulse_on_a", &ContactEvent::impulse_on_a,
                      "Contact impulse on a over the step [N*s].")
        .def_readonly("normal_impulse", &ContactEvent::normal_impulse, "Its normal part [N*s], >= 0.")
        .def_readonly("depth", &ContactEvent::depth, "Deepest penetration in the step [m].")
        .def("__repr__", [](const ContactEvent& e) {
            return "ContactEvent(" + e.kind + ", a=" + std::to_string(e.a.entity.index) +
                   ", b=" + std::to_string(e.b.entity.index) + ")";
        });
    py::class_<Contact>(m, "Contact", "One touching pair after the last step (read-only).")
        .def_readonly("a", &Contact::a)
        .def_readonly("b", &Contact::b)
        .def_readonly("point", &Contact::point, "Force-weighted contact point [m], world.")
        .def_readonly("normal", &Contact::normal, "Unit normal from b towards a.")
        .def_readonly("force_on_a", &Contact::force_on_a, "Total contact force on a [N], world.")
        .def_readonly("depth", &Contact::depth, "Deepest penetration of the pair [m].")
        .def_readonly("point_count", &Contact::point_count);
    py::class_<FaultEvent>(m, "FaultEvent", "A body whose state turned NaN/inf in the last step (read-only).")
        .def_readonly("kind", &FaultEvent::kind, "'body_non_finite' (frozen) or 'modal_non_finite' (reset).")
        .def_readonly("body", &FaultEvent::body)
        .def_readonly("stage", &FaultEvent::stage, "Stage after which it was found ('integrate_positions').")
        .def_readonly("step", &FaultEvent::step)
        .def_readonly("substep", &FaultEvent::substep);

    auto world = py::reinterpret_borrow<py::class_<WorldBox, WorldPtr>>(m.attr("World"));
    world.def("contact_events", &contact_events, "The last step's contact events: a list of ContactEvent.");
    world.def("contacts", &contacts, "The touching pairs after the last step: a list of Contact.");
    world.def("fault_events", &fault_events, "The last step's numerical faults: a list of FaultEvent.");
}

} // namespace smpy
