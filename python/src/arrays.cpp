// SPDX-License-Identifier: MIT
// Whole-world state as numpy arrays, one row per body in World.bodies order. The public API reads a
// body at a time (there is no contiguous pose array to view), so each is a fresh copy, marked read-only
// so that writing to it is not mistaken for moving the bodies.
#include "bindings.h"

#include <pybind11/numpy.h>

namespace smpy
{
namespace
{

template <int N, class Read> py::array_t<double> rows(const WorldBox& box, Read read)
{
    const std::vector<sm::Entity> bodies = sm::world_bodies(box.world);
    py::array_t<double> out({static_cast<py::ssize_t>(bodies.size()), static_cast<py::ssize_t>(N)});
    double* p = out.mutable_data();
    for (sm::Entity e : bodies) {
        read(box.world, e, p);
        p += N;
    }
    py::detail::array_proxy(out.ptr())->flags &= ~py::detail::npy_api::NPY_ARRAY_WRITEABLE_;
    return out;
}

void put(double* p, const sm::Vec3& v)
{
    p[0] = v.x;
    p[1] = v.y;
    p[2] = v.z;
}

void put(double* p, const sm::Quat& q)
{
    p[0] = q.w;
    p[1] = q.x;
    p[2] = q.y;
    p[3] = q.z;
}

} // namespace

void register_arrays(py::module_& m)
{
    auto world = py::reinterpret_borrow<py::class_<WorldBox, WorldPtr>>(m.attr("World"));
    world.def(
        "positions",
        [](const WorldBox& b, bool interpolated) {
            return rows<3>(b, [interpolated](const sm::World& w, sm::Entity e, double* p) {
                put(p, interpolated ? sm::body_interpolated_position(w, e) : sm::body_position(w, e));
            });
        },
        py::arg("interpolated") = false,
        "(n, 3) float64, read-only copy: each body's shape origin [m], world frame, in World.bodies order; "
        "interpolated=True blends the last two steps by interpolation_alpha.");
    world.def(
        "orientations",
        [](const WorldBox& b, bool interpolated) {
            return rows<4>(b, [interpolated](const sm::World& w, sm::Entity e, double* p) {
                put(p, interpolated ? sm::body_interpolated_orientation(w, e) : sm::body_orientation(w, e));
            });
        },
        py::arg("interpolated") = false, "(n, 4) float64, read-only copy: unit quaternions (w, x, y, z).");
    world.def(
        "linear_velocities",
        [](const WorldBox& b) {
            return rows<3>(b, [](const sm::World& w, sm::Entity e, double* p) {
                put(p, sm::body_linear_velocity(w, e));
            });
        },
        "(n, 3) float64, read-only copy: centre-of-mass velocities [m/s], world frame.");
    world.def(
        "angular_velocities",
        [](const WorldBox& b) {
            return rows<3>(b, [](const sm::World& w, sm::Entity e, double* p) {
                put(p, sm::body_angular_velocity(w, e));
            });
        },
        "(n, 3) float64, read-only copy: angular velocities [rad/s], world frame.");
}

} // namespace smpy
