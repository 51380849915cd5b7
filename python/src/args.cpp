// SPDX-License-Identifier: MIT
// Strict argument conversion: numbers are ints or floats (never bools or strings) and finite unless a
// field documents ∞; vectors are sequences of exactly 3 (or 4) numbers. Every error names the argument.
#include "bindings.h"

#include <cmath>

namespace smpy
{
namespace
{

std::string type_name(const py::handle& value)
{
    return py::str(py::type::handle_of(value).attr("__name__"));
}

// A real number of any numeric type (int, float, numpy scalars), without range checks.
double raw_number(const py::handle& value, const std::string& argument)
{
    if (PyBool_Check(value.ptr()) || PyUnicode_Check(value.ptr()) || PyBytes_Check(value.ptr()) ||
        !(PyFloat_Check(value.ptr()) || PyLong_Check(value.ptr()) || PyIndex_Check(value.ptr()) ||
          py::hasattr(value, "__float__")))
        raise_type(argument, "expected a number, got " + type_name(value));
    const double d = PyFloat_AsDouble(value.ptr());
    if (d == -1.0 && PyErr_Occurred()) {
        PyErr_Clear();
        raise_type(argument, "expected a number, got " + type_name(value));
    }
    return d;
}

std::string show(double d)
{
    return py::str(py::float_(d));
}

} // namespace

double to_number(const py::handle& value, const std::string& argument)
{
    const double d = raw_number(value, argument);
    if (!std::isfinite(d))
        raise_argument(argument, "expected a finite number, got " + show(d));
    return d;
}

double to_number_or_inf(const py::handle& value, const std::string& argument)
{
    const double d = raw_number(value, argument);
    if (std::isnan(d) || d == -INFINITY)
        raise_argument(argument, "expected a number or +inf, got " + show(d));
    return d;
}

int to_int(const py::handle& value, const std::string& argument)
{
    if (PyBool_Check(value.ptr()) || !PyIndex_Check(value.ptr()))
        raise_type(argument, "expected an integer, got " + type_name(value));
    const long long i =
        PyLong_AsLongLong(py::reinterpret_steal<py::object>(PyNumber_Index(value.ptr())).ptr());
    if ((i == -1 && PyErr_Occurred()) || i < -2147483648LL || i > 2147483647LL) {
        PyErr_Clear();
        raise_argument(argument, "integer out of range");
    }
    return static_cast<int>(i);
}

bool to_bool(const py::handle& value, const std::string& argument)
{
    if (!PyBool_Check(value.ptr()))
        raise_type(argument, "expected True or False, got " + type_name(value));
    return value.ptr() == Py_True;
}

std::string to_text(const py::handle& value, const std::string& argument)
{
    if (!PyUnicode_Check(value.ptr()))
        raise_type(argument, "expected a str, got " + type_name(value));
    return value.cast<std::string>();
}

namespace
{

py::sequence sequence_of(const py::handle& value, const std::string& argument, size_t n)
{
    if (PyUnicode_Check(value.ptr()) || !PySequence_Check(value.ptr()))
        raise_type(argument,
                   "expected a sequence of " + std::to_string(n) + " numbers, got " + type_name(value));
    py::sequence s = py::reinterpret_borrow<py::sequence>(value);
    if (s.size() != n)
        raise_argument(argument,
                       "expected " + std::to_string(n) + " numbers, got " + std::to_string(s.size()));
    return s;
}

} // namespace

sm::Vec3 to_vec3(const py::handle& value, const std::string& argument)
{
    py::sequence s = sequence_of(value, argument, 3);
    sm::Vec3 v;
    for (int i = 0; i < 3; ++i)
        v[i] = to_number(s[static_cast<size_t>(i)], argument + "[" + std::to_string(i) + "]");
    return v;
}

sm::Quat to_quat(const py::handle& value, const std::string& argument)
{
    py::sequence s = sequence_of(value, argument, 4);
    double c[4];
    for (int i = 0; i < 4; ++i)
        c[i] = to_number(s[static_cast<size_t>(i)], argument + "[" + std::to_string(i) + "]");
    const sm::Quat q{c[0], c[1], c[2], c[3]};
    if (!(sm::norm(q) > 0.0))
        raise_argument(argument, "expected a non-zero quaternion [w, x, y, z]");
    return q;
}

py::tuple from_vec3(const sm::Vec3& v)
{
    return py::make_tuple(v.x, v.y, v.z);
}

py::tuple from_quat(const sm::Quat& q)
{
    return py::make_tuple(q.w, q.x, q.y, q.z);
}

Kwargs::Kwargs(const char* function, const py::kwargs& kwargs) : m_function(function), m_kwargs(kwargs) {}

bool Kwargs::has(const char* name) const
{
    return m_kwargs.contains(name);
}

py::handle Kwargs::get(const char* name)
{
    m_read.insert(name);
    return m_kwargs[name];
}

double Kwargs::number(const char* name, double fallback)
{
    return has(name) ? to_number(get(name), name) : fallback;
}

double Kwargs::number_or_inf(const char* name, double fallback)
{
    return has(name) ? to_number_or_inf(get(name), name) : fallback;
}

int Kwargs::integer(const char* name, int fallback)
{
    return has(name) ? to_int(get(name), name) : fallback;
}

bool Kwargs::flag(const char* name, bool fallback)
{
    return has(name) ? to_bool(get(name), name) : fallback;
}

std::string Kwargs::text(const char* name, const std::string& fallback)
{
    return has(name) ? to_text(get(name), name) : fallback;
}

sm::Vec3 Kwargs::vec3(const char* name, const sm::Vec3& fallback)
{
    return has(name) ? to_vec3(get(name), name) : fallback;
}

sm::Quat Kwargs::quat(const char* name, const sm::Quat& fallback)
{
    return has(name) ? to_quat(get(name), name) : fallback;
}

py::object Kwargs::object(const char* name)
{
    return has(name) ? py::reinterpret_borrow<py::object>(get(name)) : py::none();
}

void Kwargs::finish() const
{
    for (const auto& item : m_kwargs) {
        const std::string key = py::str(item.first);
        if (!m_read.contains(key))
            raise_type(key, "unexpected keyword argument of " + m_function + "()");
    }
}

const char* motion_name(sm::MotionType motion)
{
    switch (motion) {
    case sm::MotionType::Static:
        return "static";
    case sm::MotionType::Kinematic:
        return "kinematic";
    case sm::MotionType::Dynamic:
        return "dynamic";
    }
    return "dynamic";
}

const char* solver_name(sm::ContactSolver solver)
{
    return solver == sm::ContactSolver::Soft ? "soft" : "penalty";
}

} // namespace smpy
