// SPDX-License-Identifier: MIT
// supermodal.World: making a world, its settings (the speed/accuracy knobs), the clock, hash and
// snapshots. Every call that can be refused checks before it changes anything.
#include "bindings.h"

#include <cmath>
#include <pybind11/stl.h>

namespace smpy
{
namespace
{

// The WorldDef keywords, read over `def` (the defaults, or the world's current settings).
void read_world_def(Kwargs& kw, sm::WorldDef& def)
{
    def.dt = kw.number("dt", def.dt);
    def.substep_count = kw.integer("substep_count", def.substep_count);
    def.gravity = kw.vec3("gravity", def.gravity);
    def.max_steps_per_advance = kw.integer("max_steps_per_advance", def.max_steps_per_advance);
    def.constraint_iterations = kw.integer("constraint_iterations", def.constraint_iterations);
    def.thread_count = kw.integer("thread_count", def.thread_count);
    def.split_islands = kw.flag("split_islands", def.split_islands);
    sm::ContactDef& c = def.contact;
    c.enabled = kw.flag("contact_enabled", c.enabled);
    c.solver = kw.choice("contact_solver", c.solver,
                         {{"penalty", sm::ContactSolver::Penalty}, {"soft", sm::ContactSolver::Soft}});
    c.soft.iterations = kw.integer("contact_iterations", c.soft.iterations);
    c.soft.relax_iterations = kw.integer("relax_iterations", c.soft.relax_iterations);
    c.soft.substeps = kw.integer("solver_substeps", c.soft.substeps);
    c.soft.frequency_hz = kw.number("soft_frequency_hz", c.soft.frequency_hz);
    c.soft.damping_ratio = kw.number("soft_damping_ratio", c.soft.damping_ratio);
    c.path = kw.choice("contact_path", c.path,
                       {{"auto", sm::ContactPath::Auto},
                        {"sampling", sm::ContactPath::Sampling},
                        {"support_map", sm::ContactPath::SupportMap}});
    c.stiffness = kw.choice(
        "contact_stiffness", c.stiffness,
        {{"frequency", sm::ContactStiffness::Frequency}, {"material", sm::ContactStiffness::Material}});
    c.frequency_hz = kw.number("contact_frequency_hz", c.frequency_hz);
    c.damping_ratio = kw.number("contact_damping_ratio", c.damping_ratio);
    c.sample_spacing = kw.number("sample_spacing", c.sample_spacing);
    c.deformed_inside_test = kw.flag("deformed_inside_test", c.deformed_inside_test);
    def.sleep.enabled = kw.flag("sleep_enabled", def.sleep.enabled);
    kw.finish();
}

// The ContactDef fields that the WorldDef validation does not cover, checked here so a refused value
// never reaches the step.
void check_contact(const sm::ContactDef& c)
{
    if (c.frequency_hz < 0.0)
        raise_argument("contact_frequency_hz", "expected a frequency >= 0 Hz (0: the stability cap)");
    if (c.sample_spacing < 0.0)
        raise_argument("sample_spacing", "expected a spacing >= 0 m (0: automatic)");
}

// Engine field names (Error::where) → the keyword that sets them.
constexpr std::initializer_list<std::pair<const char*, const char*>> k_world_fields = {
    {"contact.soft.iterations", "contact_iterations"},
    {"contact.soft.relax_iterations", "relax_iterations"},
    {"contact.soft.substeps", "solver_substeps"},
    {"contact.soft.frequency_hz", "soft_frequency_hz"},
    {"contact.soft.damping_ratio", "soft_damping_ratio"},
};

void check_world_def(const sm::WorldDef& def)
{
    check_status(sm::validate(def), k_world_fields);
    check_contact(def.contact);
}

WorldPtr make_world(const py::kwargs& kwargs)
{
    sm::WorldDef def = sm::default_world_def();
    Kwargs kw("World", kwargs);
    read_world_def(kw, def);
    check_world_def(def);
    return std::make_shared<WorldBox>(sm::World(def));
}

void configure(WorldBox& box, const py::kwargs& kwargs)
{
    sm::WorldDef def = box.world.settings();
    Kwargs kw("configure", kwargs);
    read_world_def(kw, def);
    check_world_def(def);
    check_status(box.world.set_settings(def));
}

py::dict settings(const WorldBox& box)
{
    const sm::WorldDef& d = box.world.settings();
    py::dict out;
    out["dt"] = d.dt;
    out["substep_count"] = d.substep_count;
    out["gravity"] = from_vec3(d.gravity);
    out["max_steps_per_advance"] = d.max_steps_per_advance;
    out["constraint_iterations"] = d.constraint_iterations;
    out["thread_count"] = d.thread_count;
    out["split_islands"] = d.split_islands;
    out["contact_enabled"] = d.contact.enabled;
    out["contact_solver"] = solver_name(d.contact.solver);
    out["contact_iterations"] = d.contact.soft.iterations;
    out["relax_iterations"] = d.contact.soft.relax_iterations;
    out["solver_substeps"] = d.contact.soft.substeps;
    out["soft_frequency_hz"] = d.contact.soft.frequency_hz;
    out["soft_damping_ratio"] = d.contact.soft.damping_ratio;
    const char* paths[] = {"auto", "sampling", "support_map"};
    out["contact_path"] = paths[static_cast<int>(d.contact.path)];
    out["contact_stiffness"] =
        d.contact.stiffness == sm::ContactStiffness::Material ? "material" : "frequency";
    out["contact_frequency_hz"] = d.contact.frequency_hz;
    out["contact_damping_ratio"] = d.contact.damping_ratio;
    out["sample_spacing"] = d.contact.sample_spacing;
    out["deformed_inside_test"] = d.contact.deformed_inside_test;
    out["sleep_enabled"] = d.sleep.enabled;
    return out;
}

void step(WorldBox& box, const py::handle& count_arg)
{
    const int count = to_int(count_arg, "count");
    if (count < 0)
        raise_argument("count", "expected a step count >= 0, got " + std::to_string(count));
    for (int i = 0; i < count; ++i)
        box.world.step();
}

int advance(WorldBox& box, const py::handle& seconds_arg)
{
    const double seconds = to_number(seconds_arg, "seconds");
    if (seconds < 0.0)
        raise_argument("seconds", "expected a time >= 0 s");
    return box.world.advance(seconds);
}

py::bytes snapshot(const WorldBox& box)
{
    const sm::Snapshot s = box.world.snapshot();
    return py::bytes(reinterpret_cast<const char*>(s.bytes().data()), s.bytes().size());
}

void restore(WorldBox& box, const py::handle& data)
{
    if (!PyBytes_Check(data.ptr()) && !PyByteArray_Check(data.ptr()) && !PyMemoryView_Check(data.ptr()))
        raise_type("snapshot", "expected bytes from World.snapshot()");
    const py::buffer_info info = py::reinterpret_borrow<py::buffer>(data).request();
    const auto* first = static_cast<const std::byte*>(info.ptr);
    const sm::Snapshot s = sm::Snapshot::from_bytes(
        std::span<const std::byte>(first, static_cast<size_t>(info.size * info.itemsize)));
    if (sm::Status status = box.world.restore(s); !status)
        raise_state("snapshot refused: " + status.error().message());
}

// A read/write property over one settings keyword.
template <class T> void knob(py::class_<WorldBox, WorldPtr>& c, const char* name, const char* doc)
{
    c.def_property(
        name, [name](const WorldBox& box) { return settings(box)[name].template cast<T>(); },
        [name](WorldBox& box, py::object value) {
            py::kwargs kw;
            kw[name] = value;
            configure(box, kw);
        },
        doc);
}

} // namespace

void register_world(py::module_& m)
{
    py::class_<WorldBox, WorldPtr> c(m, "World",
                                     R"(A physics world: bodies, settings and the fixed-step clock.

World(**settings) makes an empty world; supermodal.load_scene() makes one from a scene. The keywords
mirror WorldDef and ContactDef (defaults in brackets):

  dt [0.002] s, > 0: the fixed step (changeable only before the first step).
  substep_count [1], in [1, 1000]: substeps per step.
  gravity [(0, -9.81, 0)] m/s^2, world frame (Y up).
  max_steps_per_advance [64], >= 1: advance() runs at most this many steps per call.
  constraint_iterations [4], in [1, 100]: Gauss-Seidel passes over the joints per substep.
  thread_count [1], in [1, 64]: threads of the step (fixed at creation; results are identical for any).
  split_islands [False]: solve islands of 1024 rows or more in slabs the threads share (identical for
      any thread_count, not to a run without it; costs up to ~10% of the solve on one thread).
  contact_enabled [True].
  contact_solver ['soft']: 'soft' (implicit, stable at any step) or 'penalty' (the paper's explicit
      springs, want small steps).
  contact_iterations [10], in [1, 100]: the soft solver's passes per substep.
  relax_iterations [0], in [0, 100]: the soft solver's relax passes per substep (0: as many as
      contact_iterations); fewer are cheaper (docs/contact.md).
  solver_substeps [0], in [0, 64]: the soft solver's substeps per narrowphase (0: as many as keep each
      at most 1/240 s, so 4 at a 1/60 s step, which holds tall stacks).
  soft_frequency_hz [0] Hz, >= 0: the soft contact spring (0: min(1/(2 dt), 60 Hz)).
  soft_damping_ratio [5], >= 0.
  contact_path ['auto']: 'auto', 'sampling' or 'support_map'.
  contact_stiffness ['frequency']: 'frequency' or 'material' (Hertz, from the bodies' Young's moduli).
  contact_frequency_hz [0] Hz, >= 0: penalty spring (0: the stability cap 1/(10 h)).
  contact_damping_ratio [-1]: penalty damping (< 0: from the pair's restitution).
  sample_spacing [0] m, >= 0: contact sample spacing (0: a quarter of each body's smallest radius).
  deformed_inside_test [False]: sampled points tested against a modal body meet its deformed shape
      (through its inverse deformation), so both bodies' dents count; False: its rest shape.
  sleep_enabled [True]: bodies at rest stop being stepped.

A refused value raises ArgumentError naming the keyword and leaves the world unchanged.)");
    c.def(py::init(&make_world));
    c.def("configure", &configure,
          "Changes settings between steps (the same keywords as World()). All or nothing: a refused value "
          "raises ArgumentError and changes none. dt and thread_count cannot change after the first step.");
    c.def("settings", &settings, "Every setting as a dict of the World() keywords.");
    knob<double>(c, "dt", "The fixed step [s] (set before the first step only).");
    knob<int>(c, "substep_count", "Substeps per step [-], in [1, 1000].");
    knob<std::string>(c, "contact_solver", "'penalty' or 'soft'.");
    knob<int>(c, "contact_iterations", "The soft contact solver's passes per substep [-], in [1, 100].");
    knob<int>(c, "constraint_iterations", "Joint solver passes per substep [-], in [1, 100].");
    c.def("step", &step, py::arg("count") = 1,
          "Runs `count` fixed steps of dt, >= 0. The GIL stays held: another Python thread cannot reach the "
          "world while it steps (the engine refuses changes during a step).");
    c.def("advance", &advance, py::arg("seconds"),
          "Adds `seconds` [s], >= 0, of real time to the accumulator and runs the whole steps it holds (at "
          "most max_steps_per_advance). Returns the number of steps run.");
    c.def_property_readonly(
        "interpolation_alpha", [](const WorldBox& b) { return b.world.interpolation_alpha(); },
        "Fraction of a step left in the accumulator [-], in [0, 1): blend the previous and current poses.");
    c.def_property_readonly(
        "time", [](const WorldBox& b) { return b.world.time(); }, "Simulated time [s].");
    c.def_property_readonly(
        "step_count", [](const WorldBox& b) { return b.world.step_count(); }, "Steps run since creation.");
    c.def(
        "state_hash", [](const WorldBox& b) { return b.world.state_hash(); },
        "FNV-1a hash of the dynamic state (an int): the same scene, steps and engine build give the same "
        "hash in Python, C++ and `supermodal run` (which prints it in hex).");
    c.def("snapshot", &snapshot, "The world's dynamic state as bytes, for restore().");
    c.def("restore", &restore, py::arg("snapshot"),
          "Restores bytes from snapshot() of this world. Raises StateError, changing nothing, when they "
          "come from another layout version, are damaged, or bodies or constraints changed since.");
    c.def_property_readonly(
        "duration", [](const WorldBox& b) { return b.duration; },
        "The scene's run length [s] (settings.duration), or None for a world made in code.");
    c.def_property_readonly(
        "source", [](const WorldBox& b) { return b.source; }, "The scene file it was loaded from, or ''.");
    c.def(
        "warnings",
        [](const WorldBox& b) {
            const sm::StepWarnings& w = b.world.warnings();
            py::dict out;
            out["non_finite_bodies"] = w.non_finite_bodies;
            out["gyroscopic_fallbacks"] = w.gyroscopic_fallbacks;
            out["contact_frequency_clamps"] = w.contact_frequency_clamps;
            out["speculative_substeps"] = w.speculative_substeps;
            out["modal_integrator_switches"] = w.modal_integrator_switches;
            out["modal_non_finite"] = w.modal_non_finite;
            return out;
        },
        "Counts of numerical trouble since creation (StepWarnings), as a dict.");
    c.def(
        "last_step_ms", [](const WorldBox& b) { return b.world.profile().total_ms; },
        "Wall time of the last step [ms], as the engine measured it.");
    c.def(
        "max_penetration", [](const WorldBox& b) { return sm::world_max_penetration(b.world); },
        "Deepest contact penetration in the last step [m] (the per-step value `supermodal run` takes the "
        "maximum of).");
}

} // namespace smpy
