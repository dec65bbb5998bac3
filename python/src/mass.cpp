// Mass properties in Python: tumble.MassProperties, the primitive shapes, meshes from files or arrays.
#include <pybind11/eigen.h>
#include <pybind11/functional.h>
#include <pybind11/numpy.h>
#include <pybind11/operators.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <optional>

#include "bindings.hpp"
#include "tumble/error.hpp"
#include "tumble/mass/density.hpp"
#include "tumble/mass/mass_properties.hpp"
#include "tumble/mass/mesh_io.hpp"
#include "tumble/mass/mesh_mass.hpp"
#include "tumble/mass/shapes.hpp"

namespace py = pybind11;

namespace tumble::python {
namespace {

/// density (a number) or mass (exactly one, or neither: unit density).
MassSpec spec_of(const py::object& density, std::optional<double> mass) {
  if (!density.is_none() && mass) throw InvalidArgument("give density or mass, not both");
  if (mass) return MassSpec::mass(*mass);
  return MassSpec::density(density.is_none() ? 1.0 : density.cast<double>());
}

/// A density given as a Python function of points, called once with every quadrature point as an
/// (n, 3) array (not once per point). The rule's points are fixed by the shape or mesh and the degree,
/// so the integration runs twice: first recording the points (with ρ = 1), then with the values the
/// function gave for them, in the same order.
DensityResult integrate_python_density(const py::function& rho,
                                       const std::function<DensityResult(const DensityField&)>& integrate) {
  std::vector<Vec3> points;
  integrate([&](const Vec3& x) {
    points.push_back(x);
    return 1.0;
  });
  py::array_t<double> X({static_cast<py::ssize_t>(points.size()), py::ssize_t{3}});
  auto P = X.mutable_unchecked<2>();
  for (size_t i = 0; i < points.size(); ++i) {
    for (int k = 0; k < 3; ++k) P(static_cast<py::ssize_t>(i), k) = points[i](k);
  }
  const auto values = py::array_t<double, py::array::c_style | py::array::forcecast>(rho(X));
  if (values.ndim() != 1 || values.shape(0) != static_cast<py::ssize_t>(points.size())) {
    throw InvalidArgument(py::str("the density function returned shape {} for {} points: return one density "
                                  "(kg/m^3) per point, shape (n,)")
                              .format(py::getattr(values, "shape"), points.size())
                              .cast<std::string>());
  }
  const double* v = values.data();
  size_t next = 0;
  return integrate([&](const Vec3&) { return next < points.size() ? v[next++] : v[points.size() - 1]; });
}

/// The degree of the density rule (density.hpp): exact for polynomial densities of degree ≤ d − 2.
constexpr int kDensityDegree = 10;

MassProperties of_shape(const Shape& shape, const py::object& density, std::optional<double> mass,
                        std::optional<double> thickness) {
  if (py::isinstance<py::function>(density)) {
    if (mass || thickness) throw InvalidArgument("a density function is for solids given by density alone");
    return integrate_python_density(density.cast<py::function>(),
                                    [&](const DensityField& rho) {
                                      return integrate_density(shape, rho, kDensityDegree);
                                    })
        .properties;
  }
  const MassSpec spec = spec_of(density, mass);
  return thickness ? shell_mass_properties(shape, *thickness, spec) : solid_mass_properties(shape, spec);
}

/// A mesh's properties with its warnings (mesh reading and integration).
struct MeshResult {
  MassProperties properties;
  double surface_area;
  std::vector<std::string> warnings;
};

MeshResult of_mesh(const TriangleMesh& mesh, const py::object& density, std::optional<double> mass,
                   std::optional<double> thickness, const std::string& name) {
  if (py::isinstance<py::function>(density)) {
    if (mass || thickness) throw InvalidArgument("a density function is for solids given by density alone");
    const DensityResult r =
        integrate_python_density(density.cast<py::function>(), [&](const DensityField& rho) {
          return integrate_density(mesh, rho, kDensityDegree, name);
        });
    return {r.properties, solid_mass_properties(mesh, MassSpec::density(1.0), name).surface_area, r.warnings};
  }
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
      "with surface density density*thickness. density may also be a function of points: called once "
      "with every quadrature point as an (n, 3) array (m, the shape's frame), it returns the densities "
      "(n,) in kg/m^3 (exact for polynomial densities of degree <= 8).";
  m.def(
      "box",
      [](const Vec3& size, py::object density, std::optional<double> mass, std::optional<double> thickness) {
        return of_shape(Box{size}, density, mass, thickness);
      },
      py::arg("size"), py::kw_only(), py::arg("density") = py::none(), py::arg("mass") = py::none(),
      py::arg("thickness") = py::none(),
      (std::string("A box of edge lengths size = (a, b, c) (m) along x, y, z, centred at the origin.") +
       material)
          .c_str());
  m.def(
      "sphere",
      [](double radius, py::object density, std::optional<double> mass, std::optional<double> thickness) {
        return of_shape(Sphere{radius}, density, mass, thickness);
      },
      py::arg("radius"), py::kw_only(), py::arg("density") = py::none(), py::arg("mass") = py::none(),
      py::arg("thickness") = py::none(),
      (std::string("A sphere of radius r (m) at the origin.") + material).c_str());
  m.def(
      "cylinder",
      [](double radius, double length, py::object density, std::optional<double> mass,
         std::optional<double> thickness) {
        return of_shape(Cylinder{radius, length}, density, mass, thickness);
      },
      py::arg("radius"), py::arg("length"), py::kw_only(), py::arg("density") = py::none(),
      py::arg("mass") = py::none(), py::arg("thickness") = py::none(),
      (std::string("A cylinder of radius r and length l (m) along z, centred at the origin.") + material)
          .c_str());
  m.def(
      "capsule",
      [](double radius, double length, py::object density, std::optional<double> mass,
         std::optional<double> thickness) {
        return of_shape(Capsule{radius, length}, density, mass, thickness);
      },
      py::arg("radius"), py::arg("length"), py::kw_only(), py::arg("density") = py::none(),
      py::arg("mass") = py::none(), py::arg("thickness") = py::none(),
      (std::string(
           "A capsule: a cylinder of radius r and length l (m) along z with hemispherical ends, centred "
           "at the origin.") +
       material)
          .c_str());
  m.def(
      "cone",
      [](double radius, double height, py::object density, std::optional<double> mass,
         std::optional<double> thickness) {
        return of_shape(Cone{radius, height}, density, mass, thickness);
      },
      py::arg("radius"), py::arg("height"), py::kw_only(), py::arg("density") = py::none(),
      py::arg("mass") = py::none(), py::arg("thickness") = py::none(),
      (std::string("A cone of base radius r (m) at z = 0 and apex at z = height.") + material).c_str());
  m.def(
      "torus",
      [](double major_radius, double minor_radius, py::object density, std::optional<double> mass,
         std::optional<double> thickness) {
        return of_shape(Torus{major_radius, minor_radius}, density, mass, thickness);
      },
      py::arg("major_radius"), py::arg("minor_radius"), py::kw_only(), py::arg("density") = py::none(),
      py::arg("mass") = py::none(), py::arg("thickness") = py::none(),
      (std::string("A torus about the z axis: tube radius r at distance R from the axis (m).") + material)
          .c_str());
  m.def(
      "ellipsoid",
      [](const Vec3& semi_axes, py::object density, std::optional<double> mass) {
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
      [](const std::filesystem::path& path, py::object density, std::optional<double> mass, double scale,
         std::size_t part, std::optional<double> thickness) {
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
         const Eigen::Matrix<std::int64_t, Eigen::Dynamic, 3, Eigen::RowMajor>& F, py::object density,
         std::optional<double> mass, std::optional<double> thickness) {
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
