// SPDX-License-Identifier: MIT
// The module's exception classes, defined in Python so they carry attributes (argument, pointer, file).
#include "bindings.h"

#include <pybind11/eval.h>

namespace smpy
{
namespace
{

// The classes live as long as the interpreter; kept as leaked references so no destructor runs after it.
py::object* g_argument = nullptr;
py::object* g_type = nullptr;
py::object* g_scene = nullptr;
py::object* g_state = nullptr;

constexpr const char* k_classes = R"(
class ArgumentError(ValueError):
    """A bad argument value (out of range, NaN or infinite, an unknown name).

    ``argument`` names the argument (or Def field) at fault. The world is unchanged.
    """
    def __init__(self, message, argument=""):
        super().__init__(message)
        self.argument = argument


class ArgumentTypeError(TypeError):
    """An argument of the wrong type, or an unexpected keyword; ``argument`` names it."""
    def __init__(self, message, argument=""):
        super().__init__(message)
        self.argument = argument


class SceneError(ValueError):
    """A scene the loader refused. ``pointer`` is the JSON pointer of the bad value
    ("/bodies/3/shape/radii/0"), ``file`` the scene file ("<dict>" for a dict)."""
    def __init__(self, message, pointer="", file=""):
        super().__init__(message)
        self.pointer = pointer
        self.file = file


class StateError(ValueError):
    """The world refused the call: a destroyed body or constraint, a snapshot of another world."""
)";

[[noreturn]] void raise(const py::object& cls, const py::object& instance)
{
    PyErr_SetObject(cls.ptr(), instance.ptr());
    throw py::error_already_set();
}

} // namespace

void raise_argument(const std::string& argument, const std::string& what)
{
    raise(*g_argument, (*g_argument)(argument + ": " + what, argument));
}

void raise_type(const std::string& argument, const std::string& what)
{
    raise(*g_type, (*g_type)(argument + ": " + what, argument));
}

void raise_scene(const sm::Error& error)
{
    raise(*g_scene, (*g_scene)(error.message(), error.where, error.file));
}

void raise_state(const std::string& what)
{
    raise(*g_state, (*g_state)(what));
}

void check_status(const sm::Status& status, std::initializer_list<std::pair<const char*, const char*>> rename)
{
    if (status)
        return;
    std::string where = status.error().where;
    for (const auto& [engine_name, python_name] : rename)
        if (where == engine_name)
            where = python_name;
    if (where.empty())
        raise_state(status.error().what);
    raise_argument(where, status.error().what);
}

void register_errors(py::module_& m)
{
    py::dict scope;
    scope["__builtins__"] = py::module_::import("builtins");
    scope["__name__"] = "supermodal";
    py::exec(k_classes, scope);
    g_argument = new py::object(scope["ArgumentError"]);
    g_type = new py::object(scope["ArgumentTypeError"]);
    g_scene = new py::object(scope["SceneError"]);
    g_state = new py::object(scope["StateError"]);
    m.attr("ArgumentError") = *g_argument;
    m.attr("ArgumentTypeError") = *g_type;
    m.attr("SceneError") = *g_scene;
    m.attr("StateError") = *g_state;
}

} // namespace smpy
