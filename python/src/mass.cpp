// Mass properties in Python: tumble.MassProperties, the primitive shapes, meshes from files or arrays.
#include <pybind11/eigen.h>
#include <pybind11/operators.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <optional>

#include "bindings.hpp"
#include "tumble/error.hpp"
#include "tumble/mass/mass_properties.hpp"
#include "tumble/mass/mesh_io.hpp"
#include "tumble/mass/mesh_mass.hpp"
#include "tumble/mass/shapes.hpp"

namespace py = pybind11;

namespace tumble::python {
namespace {

/// density or mass (exactly one, or neither: unit density).
MassSpec spec_of(std::optional<double> density, std::optional<double> mass) {
  if (density && mass) throw InvalidArgument("give density or mass, not both");
  if (mass) return MassSpec::mass(*mass);
  return MassSpec::density(density.value_or(1.0));
}

MassProperties of_shape(const Shape& shape, std::optional<double> density, std::optional<double> mass,
                        std::optional<double> thickness) {
  const MassSpec spec = spec_of(density, mass);
  return thickness ? shell_mass_properties(shape, *thickness, spec) : solid_mass_properties(shape, spec);
}

/// A mesh's properties with its warnings (mesh reading and integration).
struct MeshResult {
  MassProperties properties;
  double surface_area;
  std::vector<std::string> warnings;
};

MeshResult of_mesh(const TriangleMesh& mesh, std::optional<double> density, std::optional<double> mass,
                   std::optional<double> thickness, const std::string& name) {
  const MassSpec spec = spec_of(density, mass);
  const MeshMassResult r = thickness ? shell_mass_properties(mesh, *thickness, spec, name)
                                     : solid_mass_properties(mesh, spec, name);
  return {r.properties, r.surface_area, r.warnings};
}

}  // namespace

void bind_mass(py::module_& m) {
  py::class_<MassProperties>(
      m, "MassProperties",
      "Mass m (kg), centre of mass c (m) and inertia tensor I about c (kg m^2), in the "
      "reference frame the shape or mesh was given in.")
      .def(py::init([](double mass, const Vec3& center_of_mass, const Mat3& inertia) {
             MassProperties mp = MassProperties::from_inertia(mass, center_of_mass, inertia);
             mp.validate();
             return mp;
           }),
           py::arg("mass"), py::arg("center_of_mass"), py::arg("inertia"),
           "From data-sheet values: inertia about the centre of mass; validated (positive definite, "
           "triangle inequality).")
      .def_readonly("mass", &MassProperties::mass, "m (kg)")
      .def_readonly("volume", &MassProperties::volume, "volume of material (m^3); 0 where unknown")
      .def_readonly("center_of_mass", &MassProperties::center_of_mass, "c (m), reference frame, shape (3,)")
      .def_readonly("inertia", &MassProperties::inertia, "I about c, reference axes (kg m^2), shape (3, 3)")
      .def_property_readonly(
          "principal_moments", [](const MassProperties& mp) { return Vec3(mp.principal_axes().Lambda); },
          "Lambda: principal moments, ascending (kg m^2)")
      .def_property_readonly(
          "principal_axes", [](const MassProperties& mp) { return Mat3(mp.principal_axes().U); },
          "U: a proper rotation whose columns are the principal axes, I = U diag(Lambda) U^T")
      .def("inertia_about", &MassProperties::inertia_about, py::arg("point"),
           "the inertia tensor about another point (parallel-axis theorem), reference axes")
      .def(
          "moment_about_axis",
          [](const MassProperties& mp, const Vec3& axis, std::optional<Vec3> point) {
            return mp.moment_about_axis(axis, point.value_or(mp.center_of_mass));
          },
          py::arg("axis"), py::arg("point") = py::none(),
          "b^T I_p b: the moment about the line through `point` (default: c) along `axis`")
      .def(
          "transformed",
          [](const MassProperties& mp, std::optional<Mat3> R, std::optional<Vec3> t) {
            return mp.transformed(R.value_or(Mat3::Identity()), t.value_or(Vec3::Zero()));
          },
          py::arg("R") = py::none(), py::arg("t") = py::none(),
          "the body placed in a parent frame, x_parent = R x + t: c' = R c + t, I' = R I R^T")
      .def("expressed_in", &MassProperties::expressed_in, py::arg("R"),
           "the same body in a frame rotated by R (columns: its axes): I' = R^T I R, c' = R^T c")
      .def(py::self + py::self, "two parts combined (same reference frame)")
      .def(py::self - py::self, "a hole removed")
      .def(
          "validate", [](const MassProperties& mp) { mp.validate(); },
          "raises ValueError unless a body can have these (positive mass, I positive definite, triangle "
          "inequality)")
      .def("__repr__", [](const MassProperties& mp) {
        return py::str("MassProperties(mass={}, center_of_mass={}, principal_moments={})")
            .format(mp.mass, py::cast(mp.center_of_mass), py::cast(Vec3(mp.principal_axes().Lambda)));
      });

  const char* material =
      " Give density (kg/m^3) or mass (kg) (default: unit density); thickness (m) makes it a thin shell "
      "with surface density density*thickness.";
  m.def(
      "box",
      [](const Vec3& size, std::optional<double> density, std::optional<double> mass,
         std::optional<double> thickness) { return of_shape(Box{size}, density, mass, thickness); },
      py::arg("size"), py::kw_only(), py::arg("density") = py::none(), py::arg("mass") = py::none(),
      py::arg("thickness") = py::none(),
      (std::string("A box of edge lengths size = (a, b, c) (m) along x, y, z, centred at the origin.") +
       material)
          .c_str());
  m.def(
      "sphere",
      [](double radius, std::optional<double> density, std::optional<double> mass,
         std::optional<double> thickness) { return of_shape(Sphere{radius}, density, mass, thickness); },
      py::arg("radius"), py::kw_only(), py::arg("density") = py::none(), py::arg("mass") = py::none(),
      py::arg("thickness") = py::none(),
      (std::string("A sphere of radius r (m) at the origin.") + material).c_str());
  m.def(
      "cylinder",
      [](double radius, double length, std::optional<double> density, std::optional<double> mass,
         std::optional<double> thickness) {
        return of_shape(Cylinder{radius, length}, density, mass, thickness);
      },
      py::arg("radius"), py::arg("length"), py::kw_only(), py::arg("density") = py::none(),
      py::arg("mass") = py::none(), py::arg("thickness") = py::none(),
      (std::string("A cylinder of radius r and length l (m) along z, centred at the origin.") + material)
          .c_str());
  m.def(
      "ellipsoid",
      [](const Vec3& semi_axes, std::optional<double> density, std::optional<double> mass) {
        return of_shape(Ellipsoid{semi_axes}, density, mass, std::nullopt);
      },
      py::arg("semi_axes"), py::kw_only(), py::arg("density") = py::none(), py::arg("mass") = py::none(),
      "A solid ellipsoid of semi-axes (a, b, c) (m) along x, y, z. Give density or mass.");

  py::class_<MeshResult>(m, "MeshMassProperties")
      .def_readonly("properties", &MeshResult::properties)
      .def_readonly("surface_area", &MeshResult::surface_area, "m^2")
      .def_readonly("warnings", &MeshResult::warnings);
  m.def(
      "_mesh_file",
      [](const std::filesystem::path& path, std::optional<double> density, std::optional<double> mass,
         double scale, std::size_t part, std::optional<double> thickness) {
        LoadedMesh loaded = load_mesh(path, MeshLoadOptions{.scale = scale, .part = part});
        MeshResult r = of_mesh(loaded.mesh, density, mass, thickness, path.string());
        r.warnings.insert(r.warnings.begin(), loaded.warnings.begin(), loaded.warnings.end());
        return r;
      },
      py::arg("path"), py::arg("density"), py::arg("mass"), py::arg("scale"), py::arg("part"),
      py::arg("thickness"));
  m.def(
      "_mesh_arrays",
      [](const Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>& V,
         const Eigen::Matrix<std::int64_t, Eigen::Dynamic, 3, Eigen::RowMajor>& F,
         std::optional<double> density, std::optional<double> mass, std::optional<double> thickness) {
        TriangleMesh mesh;
        mesh.vertices.reserve(static_cast<std::size_t>(V.rows()));
        for (Eigen::Index i = 0; i < V.rows(); ++i) mesh.vertices.emplace_back(V.row(i).transpose());
        for (Eigen::Index i = 0; i < F.rows(); ++i) {
          std::array<std::uint32_t, 3> f{};
          for (int k = 0; k < 3; ++k) {
            const std::int64_t v = F(i, k);
            if (v < 0 || v >= V.rows()) {
              throw InvalidArgument(py::str("faces[{}, {}] = {} is not a vertex index (0 to {})")
                                        .format(i, k, v, V.rows() - 1)
                                        .cast<std::string>());
            }
            f[static_cast<std::size_t>(k)] = static_cast<std::uint32_t>(v);
          }
          mesh.triangles.push_back(f);
        }
        return of_mesh(mesh, density, mass, thickness, "mesh");
      },
      py::arg("vertices"), py::arg("faces"), py::arg("density"), py::arg("mass"), py::arg("thickness"));
}

}  // namespace tumble::python
