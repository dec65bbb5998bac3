#pragma once
// Exact mass properties of triangle meshes: solids bounded by closed meshes (divergence theorem,
// signed tetrahedra) and thin shells (area-weighted surfaces).
#include <string>
#include <vector>

#include "tumble/mass/mass_spec.hpp"
#include "tumble/mass/triangle_mesh.hpp"

namespace tumble {

/// What the mesh functions found besides the numbers.
struct MeshMassResult {
  MassProperties properties;          ///< mass, centre of mass, inertia about it, volume
  double surface_area = 0.0;          ///< m²
  bool flipped = false;               ///< the closed mesh was inside-out and was integrated flipped
  std::vector<std::string> warnings;  ///< one line each, for the user
};

/// Unit-density integrals of the solid bounded by a closed, consistently oriented mesh: mass = signed
/// volume, centre of mass, inertia about it. No topology checks (the fast path; see
/// solid_mass_properties). Exact up to rounding.
[[nodiscard]] MassProperties integrate_solid_mesh(const TriangleMesh& mesh);

/// Mass properties of the solid bounded by `mesh`. Checks topology first and throws MeshError naming
/// the defect (boundary edges, non-manifold edges, inconsistent orientation, degenerate triangles,
/// indices out of range) with counts and the first few indices. An inside-out mesh is flipped and a
/// warning says so. `name` (e.g. the file) prefixes messages.
[[nodiscard]] MeshMassResult solid_mass_properties(const TriangleMesh& mesh, const MassSpec& spec,
                                                   const std::string& name = "mesh");
/// The same at unit density (mass = volume): solid_mass_properties(mesh, spec, name) is this with
/// spec.apply(properties), bit for bit — for a mesh whose checks and integrals are kept for many
/// densities or masses (an ensemble reads its scene again for every run).
[[nodiscard]] MeshMassResult solid_unit_properties(const TriangleMesh& mesh,
                                                   const std::string& name = "mesh");

/// Thin-shell mass properties: the surface carries mass uniformly, surface density ρ·t (spec density
/// times `thickness`) or the given total mass. Works for open meshes as well as closed ones.
[[nodiscard]] MeshMassResult shell_mass_properties(const TriangleMesh& mesh, double thickness,
                                                   const MassSpec& spec, const std::string& name = "mesh");

}  // namespace tumble
