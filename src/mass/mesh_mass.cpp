// Mass properties of meshes for users: checks, orientation, scaling to a density or a mass.
#include "tumble/mass/mesh_mass.hpp"

#include <cmath>
#include <fmt/format.h>
#include <limits>

#include "mesh_components.hpp"
#include "mesh_integrals.hpp"
#include "tumble/error.hpp"
#include "tumble/mass/mesh_check.hpp"

namespace tumble {
namespace {

/// The integrals of coordinates up to x grow like x^5 (inertia of a solid) and overflow double beyond
/// about 1e61 m (the products on the way, earlier): found by fuzzing (fuzz/fuzz_mass.cpp), a mesh of
/// finite but huge coordinates gave an infinite or NaN inertia without a word.
void require_finite_integrals(const MassProperties& unit, double diagonal, const std::string& name) {
  if (std::isfinite(unit.mass) && unit.center_of_mass.allFinite() && unit.inertia.allFinite()) return;
  throw MeshError(fmt::format(
      "{}: the mesh's integrals overflow double (volume or area {:.6g}, bounding-box diagonal {:.6g} m): "
      "its coordinates are too large; give them in metres, or scale the mesh down",
      name, unit.mass, diagonal));
}

}  // namespace

MeshMassResult solid_mass_properties(const TriangleMesh& mesh, const MassSpec& spec,
                                     const std::string& name) {
  MeshMassResult result = solid_unit_properties(mesh, name);
  result.properties = spec.apply(result.properties);
  return result;
}

MeshMassResult solid_unit_properties(const TriangleMesh& mesh, const std::string& name) {
  if (mesh.triangles.empty()) {
    throw MeshError(fmt::format("{}: the mesh has no triangles, so it bounds no solid", name));
  }
  MeshReport report = check_mesh(mesh);
  MeshMassResult result;
  if (!report.solid() && report.usable() && report.degenerate_count > 0) {
    // Zero-area triangles (CAD exports leave slivers) add nothing to the integrals: if the surface
    // without them is closed, it bounds the same solid.
    std::vector<std::size_t> dropped;
    TriangleMesh kept = without_degenerate_triangles(mesh, dropped);
    MeshReport kept_report = check_mesh(kept);
    if (kept_report.solid()) {
      std::string list;
      for (std::size_t k = 0; k < std::min<std::size_t>(dropped.size(), MeshReport::listed); ++k)
        list += fmt::format("{}{}", k > 0 ? ", " : "", dropped[k]);
      if (dropped.size() > MeshReport::listed) list += ", ...";
      result.warnings.push_back(fmt::format(
          "{}: left out {} degenerate (zero-area) triangle{} ({}), which add nothing to the solid: the "
          "surface without {} is closed. Remove {} in a mesh editor to silence this notice",
          name, dropped.size(), dropped.size() == 1 ? "" : "s", list, dropped.size() == 1 ? "it" : "them",
          dropped.size() == 1 ? "it" : "them"));
      MeshMassResult rest = solid_unit_properties(kept, name);
      rest.warnings.insert(rest.warnings.begin(), result.warnings.begin(), result.warnings.end());
      return rest;
    }
  }
  if (!report.solid()) {
    const std::string what =
        fmt::format("{}: cannot compute solid mass properties: {}", name, describe_solid_defects(report));
    if (report.boundary_edge_count > 0) throw NotASolidError(what);  // a shell would do
    throw MeshError(what);
  }
  result.surface_area = report.surface_area;
  MassProperties unit = integrate_solid_mesh(mesh);
  require_finite_integrals(unit, report.diagonal, name);
  // A closed mesh can still enclose nothing (two triangles back to back, a folded sheet). The
  // rounding of the signed volume is a few ε of Σ|tetrahedra| ≲ area·diagonal/3, far below 1e-12 L³
  // for any mesh with fewer than ~10⁹ triangles of ordinary proportions.
  const double L = report.diagonal;
  if (!(std::abs(unit.mass) > 1e-12 * L * L * L)) {
    throw NotASolidError(fmt::format(
        "{}: the closed mesh encloses zero volume ({:.3g} m^3 for a bounding-box diagonal of {:.6g} "
        "m): it is flat or folded onto itself; treat a sheet as a thin-walled part (shell mass "
        "properties)",
        name, unit.mass, L));
  }
  detail::check_surfaces_bound_material_once(mesh, unit.mass < 0.0 ? -1.0 : 1.0, name);
  if (unit.mass < 0.0) {
    // Inside-out: every triangle winds clockwise seen from outside. Flipping them all negates each
    // tetrahedron, so volume and inertia change sign while the centre of mass stays.
    result.flipped = true;
    result.warnings.push_back(fmt::format(
        "{}: the mesh is inside-out (signed volume {:.6g} m^3: its triangles wind clockwise seen "
        "from outside); it was integrated with the orientation flipped. Flip the normals in a mesh "
        "editor to silence this warning",
        name, unit.mass));
    unit.mass = -unit.mass;
    unit.inertia = -unit.inertia;
  }
  unit.volume = unit.mass;
  result.properties = unit;
  return result;
}

MeshMassResult shell_mass_properties(const TriangleMesh& mesh, double thickness, const MassSpec& spec,
                                     const std::string& name) {
  if (!std::isfinite(thickness) || !(thickness > 0.0)) {
    throw InvalidArgument(fmt::format(
        "{}: shell thickness {} m is invalid: give a positive, finite wall thickness", name, thickness));
  }
  if (mesh.triangles.empty()) {
    throw MeshError(fmt::format("{}: the mesh has no triangles, so it has no surface", name));
  }
  // Open meshes, shared edges and any winding are fine for a shell; only the data must be valid.
  const MeshReport report = check_mesh_indices(mesh);
  if (!report.usable()) {
    throw MeshError(
        fmt::format("{}: cannot compute shell mass properties: {}", name, describe_solid_defects(report)));
  }
  MeshMassResult result;
  MassProperties unit = detail::unit_properties(detail::surface_moments(mesh));
  require_finite_integrals(unit, report.diagonal, name);
  if (!(unit.mass > 0.0)) {
    throw MeshError(fmt::format(
        "{}: the surface has zero area (every triangle is degenerate), so it cannot carry mass", name));
  }
  result.surface_area = unit.mass;
  // The thin-wall model needs the wall thin against every feature of the surface; the shortest edge is
  // the finest feature the mesh can tell, so a wall as thick as that is past what the model represents.
  double shortest = std::numeric_limits<double>::infinity();
  std::size_t shortest_triangle = 0;
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    const auto& f = mesh.triangles[t];
    for (int e = 0; e < 3; ++e) {
      const double length = (mesh.vertices[f[(e + 1) % 3]] - mesh.vertices[f[e]]).norm();
      if (length > 0 && length < shortest) {
        shortest = length;
        shortest_triangle = t;
      }
    }
  }
  if (thickness >= shortest) {
    result.warnings.push_back(fmt::format(
        "{}: shell thickness {} m is at least the mesh's shortest edge, {:.6g} m (triangle {}): the "
        "thin-wall "
        "model needs the wall thin against every feature of the surface; for a thick wall subtract an "
        "inner solid as a hole",
        name, thickness, shortest, shortest_triangle));
  }
  unit.volume = unit.mass * thickness;  // thin-wall limit: material volume = area · t
  if (!std::isfinite(unit.volume)) {    // found by fuzz/fuzz_mass.cpp: a volume of inf m^3 was returned
    throw InvalidArgument(fmt::format(
        "{}: shell thickness {} m times the surface area {:.6g} m^2 overflows double: give the wall "
        "thickness in metres",
        name, thickness, unit.mass));
  }
  result.properties = spec.apply(unit, thickness);
  return result;
}

}  // namespace tumble
