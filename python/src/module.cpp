// tumble._tumble: the compiled half of the Python package (python/tumble/__init__.py is the other).
#include "bindings.hpp"

#include "tumble/error.hpp"

PYBIND11_MODULE(_tumble, m) {
  m.doc() = "tumble's C++ core; use the package `tumble`, which re-exports it with documentation.";
  // tumble's errors are Python ValueError (bad input: a scene, a mesh, a value) or OSError (a file),
  // with tumble's one-line message.
  pybind11::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const tumble::FileError& e) {
      PyErr_SetString(PyExc_OSError, e.what());
    } catch (const tumble::Error& e) {
      PyErr_SetString(PyExc_ValueError, e.what());
    }
  });
  tumble::python::bind_mass(m);
  tumble::python::bind_scene(m);
  tumble::python::bind_euler_poinsot(m);
  tumble::python::bind_arrays(m);
  tumble::python::bind_ensemble(m);
  tumble::python::bind_robot(m);
  tumble::python::bind_fit(m);
}
