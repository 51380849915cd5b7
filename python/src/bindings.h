// SPDX-License-Identifier: MIT
// The Python module's shared pieces: the world box that bodies keep alive, keyword parsing that names
// the argument in every error, and the register_* functions each file adds to the module.
#pragma once

#include <initializer_list>
#include <map>
#include <memory>
#include <optional>
#include <pybind11/pybind11.h>
#include <set>
#include <string>
#include <supermodal/supermodal.hpp>
#include <utility>
#include <vector>

namespace smpy
{

namespace py = pybind11;
namespace sm = supermodal;

/// A world and what a scene said about it; handles keep it alive through a shared_ptr.
struct WorldBox {
    sm::World world;
    std::optional<double> duration; ///< The scene's run length [s]; none for a world made in code.
    std::string source;             ///< The scene's file, "<dict>", "<string>", or empty.
    /// The scene's render meshes (SceneBody::render_mesh) by body; none for a world made in code.
    std::map<sm::Entity, std::shared_ptr<const sm::TriangleMesh>> render_meshes;
    explicit WorldBox(sm::World w) : world(std::move(w)) {}
};
using WorldPtr = std::shared_ptr<WorldBox>;

/// A body of a world (Python's supermodal.Body).
struct Body {
    WorldPtr box;
    sm::Entity entity;
};

/// A constraint of a world (Python's supermodal.Constraint).
struct Constraint {
    WorldPtr box;
    sm::Constraint handle;
};

// ---- errors.cpp ------------------------------------------------------------------------------------
/// ArgumentError (a ValueError): a value out of range, NaN/inf, an unknown name; `argument` names it.
[[noreturn]] void raise_argument(const std::string& argument, const std::string& what);
/// ArgumentTypeError (a TypeError): a value of the wrong type, or an unexpected keyword.
[[noreturn]] void raise_type(const std::string& argument, const std::string& what);
/// SceneError (a ValueError): a scene refused by the loader; carries the JSON pointer and file.
[[noreturn]] void raise_scene(const sm::Error& error);
/// StateError (a ValueError): the world refused the call (a stale handle, a foreign snapshot).
[[noreturn]] void raise_state(const std::string& what);
/// An engine Status naming a field (Error::where): ArgumentError for that field (renamed by `rename`).
void check_status(const sm::Status& status,
                  std::initializer_list<std::pair<const char*, const char*>> rename = {});
void register_errors(py::module_& m);

// ---- args.cpp --------------------------------------------------------------------------------------
/// Strict conversions of one Python value; errors name `argument`.
double to_number(const py::handle& value, const std::string& argument);        ///< int or float, finite.
double to_number_or_inf(const py::handle& value, const std::string& argument); ///< +inf allowed.
int to_int(const py::handle& value, const std::string& argument);
bool to_bool(const py::handle& value, const std::string& argument);
std::string to_text(const py::handle& value, const std::string& argument);
sm::Vec3 to_vec3(const py::handle& value, const std::string& argument);
sm::Quat to_quat(const py::handle& value, const std::string& argument); ///< [w, x, y, z], non-zero.
/// An (n, 3) array-like of real numbers, every row finite: ArgumentTypeError for another type or
/// shape, ArgumentError naming the first non-finite row.
std::vector<sm::Vec3> to_points(const py::object& value, const std::string& argument);
py::tuple from_vec3(const sm::Vec3& v);
py::tuple from_quat(const sm::Quat& q);

/// Keyword arguments of one call: each read names its key, finish() refuses the keys left unread.
class Kwargs
{
  public:
    Kwargs(const char* function, const py::kwargs& kwargs);
    [[nodiscard]] bool has(const char* name) const;
    double number(const char* name, double fallback);
    double number_or_inf(const char* name, double fallback);
    int integer(const char* name, int fallback);
    bool flag(const char* name, bool fallback);
    std::string text(const char* name, const std::string& fallback);
    sm::Vec3 vec3(const char* name, const sm::Vec3& fallback);
    sm::Quat quat(const char* name, const sm::Quat& fallback);
    py::object object(const char* name); ///< The raw value, or None.
    /// One of `names` (Python strings) for an enum.
    template <class E>
    E choice(const char* name, E fallback, std::initializer_list<std::pair<const char*, E>> names)
    {
        if (!has(name))
            return fallback;
        const std::string value = text(name, "");
        std::string allowed;
        for (const auto& [text_name, e] : names) {
            if (value == text_name)
                return e;
            allowed += (allowed.empty() ? "'" : ", '") + std::string(text_name) + "'";
        }
        raise_argument(name, "expected one of " + allowed + ", got '" + value + "'");
    }
    /// Raises for any keyword not read.
    void finish() const;

  private:
    py::handle get(const char* name);
    std::string m_function;
    py::dict m_kwargs;
    std::set<std::string> m_read;
};

/// The enum's Python name ("dynamic"), for reading back.
const char* motion_name(sm::MotionType motion);
const char* solver_name(sm::ContactSolver solver);

// ---- handles ---------------------------------------------------------------------------------------
/// The body's entity, after checking it is alive in its world (StateError otherwise).
sm::Entity live(const Body& body);
sm::Constraint live(const Constraint& constraint);

void register_world(py::module_& m);
void register_bodies(py::module_& m);
void register_deformed(py::module_& m); ///< After register_bodies: it adds to Body.
void register_constraints(py::module_& m);
void register_arrays(py::module_& m);
void register_events(py::module_& m);
void register_scene(py::module_& m);
void register_assets(py::module_& m);

} // namespace smpy
