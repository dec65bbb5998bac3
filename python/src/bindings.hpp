#pragma once
// The parts of the Python module `tumble._tumble`, each bound by its own file.
#include <pybind11/pybind11.h>

namespace tumble::python {

void bind_mass(pybind11::module_& m);           // mass.cpp: MassProperties, shapes, meshes
void bind_scene(pybind11::module_& m);          // scene.cpp: Scene, load_scene, simulate
void bind_euler_poinsot(pybind11::module_& m);  // euler_poinsot.cpp: the analytic free motion
void bind_arrays(pybind11::module_& m);         // arrays.cpp: N bodies from NumPy arrays
void bind_ensemble(pybind11::module_& m);       // ensemble.cpp: Monte Carlo studies
void bind_robot(pybind11::module_& m);          // robot.cpp: robot descriptions' inertials audited
void bind_fit(pybind11::module_& m);            // fit.cpp: inertia from gyro telemetry

}  // namespace tumble::python
