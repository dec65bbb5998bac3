// N bodies given as NumPy arrays, made into a Scene in one pass in C++ (no per-body Python), for the
// batched engine: masses (N,), principal moments (N, 3), and the state as (N, 3) and (N, 4) arrays.
#include <pybind11/eigen.h>
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <cmath>

#include "bindings.hpp"
#include "tumble/dynamics/rigid_body.hpp"
#include "tumble/error.hpp"
#include "tumble/forces/forces.hpp"
#include "tumble/io/scene.hpp"

namespace py = pybind11;

namespace tumble::python {
namespace {

using Rows3 = Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>;
using Rows4 = Eigen::Matrix<double, Eigen::Dynamic, 4, Eigen::RowMajor>;

void require_rows(const char* what, Eigen::Index rows, Eigen::Index n) {
  if (rows != n) {
    throw InvalidArgument(
        py::str("{} has {} rows; mass has {} (one per body)").format(what, rows, n).cast<std::string>());
  }
}

Scene from_arrays(const Eigen::VectorXd& mass, const Rows3& moments, std::optional<Rows3> position,
                  std::optional<Rows4> orientation, std::optional<Rows3> velocity, std::optional<Rows3> omega,
                  const std::string& omega_frame, std::optional<Vec3> gravity, double duration,
                  double timestep, double output_interval, const std::string& integrator) {
  const Eigen::Index n = mass.size();
  if (n == 0) throw InvalidArgument("no bodies: mass is empty");
  require_rows("moments", moments.rows(), n);
  if (position) require_rows("position", position->rows(), n);
  if (orientation) require_rows("orientation", orientation->rows(), n);
  if (velocity) require_rows("velocity", velocity->rows(), n);
  if (omega) require_rows("omega", omega->rows(), n);
  const Frame frame =
      omega_frame == "world"       ? Frame::world
      : omega_frame == "principal" ? Frame::principal
      : omega_frame == "reference"
          ? Frame::reference
          : throw InvalidArgument("omega_frame must be \"world\", \"reference\" or \"principal\", found \"" +
                                  omega_frame + "\"");
  Scene scene;
  scene.path = "arrays";
  scene.settings.duration = duration;
  scene.settings.timestep = timestep;
  scene.settings.output_interval = output_interval;
  scene.settings.integrator = integrator;
  scene.model.bodies.reserve(static_cast<size_t>(n));
  scene.initial.bodies.reserve(static_cast<size_t>(n));
  scene.body_info.reserve(static_cast<size_t>(n));
  const auto source = std::make_shared<const std::string>("arrays");  // one for every body
  for (Eigen::Index i = 0; i < n; ++i) {
    RigidBody body = [&] {
      try {
        return RigidBody::from_principal_moments(mass(i), moments.row(i).transpose(),
                                                 "body_" + std::to_string(i));
      } catch (const InvalidMassProperties& e) {
        throw InvalidArgument(py::str("row {}: {}").format(i, e.what()).cast<std::string>());
      }
    }();
    Quat q = Quat::Identity();
    if (orientation) {
      const Eigen::Vector4d w = orientation->row(i).transpose();
      if (!(std::abs(w.norm() - 1.0) <= 1e-3)) {
        throw InvalidArgument(
            py::str("orientation[{}] has norm {}: give unit quaternions (w, x, y, z), w first")
                .format(i, w.norm())
                .cast<std::string>());
      }
      q = Quat(w(0), w(1), w(2), w(3)).normalized();
    }
    const auto row = [&](const std::optional<Rows3>& a) {
      return a ? Vec3(a->row(i).transpose()) : Vec3::Zero();
    };
    scene.initial.bodies.push_back(
        state_from_reference(body, row(position), q, row(velocity), row(omega), frame));
    scene.body_info.push_back({source, nullptr});
    scene.model.add_body(std::move(body));
  }
  if (gravity && gravity->norm() > 0) {
    scene.model.add_force<UniformGravity>(*gravity);
    scene.conserved = Conservation{true, false, false};  // a potential; momenta change
  }
  validate(scene.settings);
  return scene;
}

}  // namespace

void bind_arrays(py::module_& m) {
  m.def("_scene_from_arrays", &from_arrays, py::arg("mass"), py::arg("moments"), py::arg("position"),
        py::arg("orientation"), py::arg("velocity"), py::arg("omega"), py::arg("omega_frame"),
        py::arg("gravity"), py::arg("duration"), py::arg("timestep"), py::arg("output_interval"),
        py::arg("integrator"));
}

}  // namespace tumble::python
