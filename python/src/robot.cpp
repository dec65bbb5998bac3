// tumble.model_check: the audit of a robot description (include/tumble/robot/audit.hpp), handed to
// Python as the JSON `tumble model check --json` prints (the package parses it into a dict), so that the
// command line and Python give the same report from one writer.
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include "bindings.hpp"
#include "tumble/error.hpp"
#include "tumble/robot/audit.hpp"

namespace py = pybind11;

namespace tumble::python {

void bind_robot(py::module_& m) {
  m.def(
      "_model_check",
      [](const std::filesystem::path& path, const std::vector<std::filesystem::path>& package_paths,
         const std::string& geometry, std::optional<double> density, bool lump_fixed) {
        robot::AuditOptions o;
        o.package_paths = package_paths;
        if (geometry != "collision" && geometry != "visual")
          throw InvalidArgument("geometry='" + geometry + "': choose 'collision' or 'visual'");
        o.geometry = geometry == "visual" ? robot::GeometryChoice::visual : robot::GeometryChoice::collision;
        o.density = density;
        o.lump_fixed = lump_fixed;
        return robot::audit_json(robot::audit_model(path, o));
      },
      py::arg("path"), py::arg("package_paths"), py::arg("geometry"), py::arg("density"),
      py::arg("lump_fixed"));
}

}  // namespace tumble::python
