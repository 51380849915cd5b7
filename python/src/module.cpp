// SPDX-License-Identifier: MIT
// The Python module `supermodal` (docs/python.md).
#include "bindings.h"

#include <supermodal/version.h>

PYBIND11_MODULE(supermodal, m)
{
    m.doc() = "supermodal physics engine: superquadric bodies, modal deformation, contact (docs/python.md).";
    m.attr("__version__") = SM_VERSION_STRING;
    smpy::register_errors(m);
    smpy::register_world(m);
    smpy::register_bodies(m);
    smpy::register_deformed(m);
    smpy::register_constraints(m);
    smpy::register_arrays(m);
    smpy::register_events(m);
    smpy::register_scene(m);
    smpy::register_assets(m);
    // Pure Python (python/_supermodal_sweep.py, installed beside this module): runs on Dask workers,
    // which import it by name.
    m.attr("sweep") = pybind11::module_::import("_supermodal_sweep").attr("sweep");
}
