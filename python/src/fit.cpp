// tumble.fit: a rigid body's inertia from gyro telemetry (include/tumble/fit/gyro_fit.hpp), handed to
// Python as the JSON `tumble fit` prints (the package parses it into a dict), so that the command line
// and Python give the same result from one writer.
#include <pybind11/numpy.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <fmt/format.h>

#include "bindings.hpp"
#include "tumble/error.hpp"
#include "tumble/fit/gyro_fit.hpp"

namespace py = pybind11;

namespace tumble::python {
namespace {

using Array = py::array_t<double, py::array::c_style | py::array::forcecast>;

/// Rows of an (n, 3) array as vectors; `name` in the message when its shape is not that.
std::vector<Vec3> rows_of(const Array& a, std::size_t n, const char* name) {
  if (a.ndim() != 2 || a.shape(0) != static_cast<py::ssize_t>(n) || a.shape(1) != 3) {
    throw InvalidArgument(
        fmt::format("{} has shape ({}): give one row (x, y, z) per time, shape ({}, 3)", name,
                    fmt::join(std::vector<py::ssize_t>(a.shape(), a.shape() + a.ndim()), ", "), n));
  }
  std::vector<Vec3> out(n);
  const double* p = a.data();
  for (std::size_t k = 0; k < n; ++k) out[k] = Vec3(p[3 * k], p[3 * k + 1], p[3 * k + 2]);
  return out;
}

std::string fitted(const fit::Telemetry& d, double sigma, bool bias, std::optional<double> substep,
                   int max_iterations) {
  const fit::FitOptions o{.sigma = sigma, .bias = bias, .substep = substep, .max_iterations = max_iterations};
  py::gil_scoped_release release;  // the fit touches no Python object
  return fit::fit_json(fit::fit_gyro(d, o));
}

}  // namespace

void bind_fit(py::module_& m) {
  m.def(
      "_fit_file",
      [](const std::filesystem::path& path, double sigma, bool bias, std::optional<double> substep,
         int max_iterations) {
        return fitted(fit::read_telemetry(path), sigma, bias, substep, max_iterations);
      },
      py::arg("path"), py::arg("sigma"), py::arg("bias"), py::arg("substep"), py::arg("max_iterations"));
  m.def(
      "_fit_arrays",
      [](const Array& t, const Array& omega, const std::optional<Array>& torque,
         const std::optional<Array>& wheel_momentum, double sigma, bool bias, std::optional<double> substep,
         int max_iterations) {
        if (t.ndim() != 1)
          throw InvalidArgument(fmt::format("t has {} dimensions: give a 1-D array of times", t.ndim()));
        const auto n = static_cast<std::size_t>(t.shape(0));
        fit::Telemetry d;
        d.t.assign(t.data(), t.data() + n);
        d.omega = rows_of(omega, n, "omega");
        if (torque) d.tau = rows_of(*torque, n, "torque");
        if (wheel_momentum) d.h = rows_of(*wheel_momentum, n, "wheel_momentum");
        return fitted(d, sigma, bias, substep, max_iterations);
      },
      py::arg("t"), py::arg("omega"), py::arg("torque"), py::arg("wheel_momentum"), py::arg("sigma"),
      py::arg("bias"), py::arg("substep"), py::arg("max_iterations"));
}

}  // namespace tumble::python
