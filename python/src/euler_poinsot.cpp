// The analytic torque-free motion (Euler–Poinsot) in Python, evaluated at an array of times.
#include <pybind11/eigen.h>
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include "bindings.hpp"
#include "tumble/integrate/euler_poinsot.hpp"

namespace py = pybind11;

namespace tumble::python {

void bind_euler_poinsot(py::module_& m) {
  m.def(
      "_euler_poinsot",
      [](const Vec3& Lambda, const Vec3& omega_b0, const Eigen::Vector4d& q0_wxyz,
         const py::array_t<double>& times) {
        const EulerPoinsot flow(Lambda, Quat(q0_wxyz(0), q0_wxyz(1), q0_wxyz(2), q0_wxyz(3)), omega_b0);
        const auto t = times.unchecked<1>();
        const py::ssize_t n = t.shape(0);
        py::array_t<double> q({n, py::ssize_t{4}}), wb({n, py::ssize_t{3}}), ww({n, py::ssize_t{3}});
        auto Q = q.mutable_unchecked<2>();
        auto WB = wb.mutable_unchecked<2>();
        auto WW = ww.mutable_unchecked<2>();
        {
          py::gil_scoped_release free_python;
          for (py::ssize_t i = 0; i < n; ++i) {
            const EulerPoinsot::State s = flow.state(t(i));
            const Vec3 w = s.q * s.omega_b;  // ω_w = R ω_b
            Q(i, 0) = s.q.w(), Q(i, 1) = s.q.x(), Q(i, 2) = s.q.y(), Q(i, 3) = s.q.z();
            for (int k = 0; k < 3; ++k) WB(i, k) = s.omega_b(k), WW(i, k) = w(k);
          }
        }
        py::dict out;
        out["quaternion"] = q;
        out["omega_body"] = wb;
        out["omega_world"] = ww;
        out["regime"] = regime_name(flow.regime());
        out["flip_interval"] = flow.flip_interval();
        out["period_omega"] = flow.period_omega();
        out["energy"] = flow.energy();
        out["angular_momentum"] = Vec3(flow.angular_momentum_w());
        return out;
      },
      py::arg("moments"), py::arg("omega_b0"), py::arg("q0"), py::arg("t"));
}

}  // namespace tumble::python
