#pragma once
// The closed surfaces of a solid mesh, and whether they bound its material once (internal).
#include <string>

#include "tumble/mass/triangle_mesh.hpp"

namespace tumble::detail {

/// A solid mesh's material is what its closed surfaces enclose, each counted with the sign of its
/// orientation (integrate_solid_mesh sums signed tetrahedra). That is the material once only when
/// every outward surface lies in no material and every inward one (a cavity's) lies in material
/// exactly once. Two nested surfaces that both face outward count the material between them twice,
/// a lone inward one subtracts a volume that was never there; either is a modelling error the
/// integrals cannot see. Throws MeshError naming the surfaces (by their first triangle) and the fix.
/// `outward` is the sign the mesh as a whole is integrated with (+1, or −1 when it is inside-out and
/// flipped). Requires a closed, consistently oriented mesh (check_mesh's solid()).
void check_surfaces_bound_material_once(const TriangleMesh& mesh, double outward, const std::string& name);

}  // namespace tumble::detail
