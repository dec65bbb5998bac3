// integrate_density() for a solid bounded by a closed triangle mesh: the signed fan of tetrahedra from
// the unit-density centroid c₀, each integrated with a Grundmann–Möller rule.
//
// For a closed, consistently oriented mesh, Σ_triangles sign(T) 1_T(x) = winding number of the mesh
// about x = 1_solid(x) (almost everywhere), where T = (c₀, a, b, c) and sign(T) = sign of
// det(a − c₀, b − c₀, c − c₀). So Σ_T ∫_T f with signed volumes is ∫_solid f for every integrable f —
// and the rule is exact on each T for polynomials of degree ≤ d.
#include <fmt/format.h>

#include "density_moments.hpp"
#include "tet_quadrature.hpp"
#include "tumble/mass/density.hpp"
#include "tumble/mass/mesh_mass.hpp"

namespace tumble {

DensityResult integrate_density(const TriangleMesh& mesh, const DensityField& rho, int degree,
                                const std::string& name) {
  const std::string where = fmt::format("mesh '{}'", name);
  const int d = detail::density_rule_degree(degree, rho, where);
  // Topology checks, orientation and the centroid (an interior point of the convex hull, near the
  // centre of mass for moderate density variation: a good origin for the moments).
  const MeshMassResult checked = solid_mass_properties(mesh, MassSpec::density(1.0), name);
  const Vec3 apex = checked.properties.center_of_mass;

  auto integrate = [&](int rule_degree) {
    const detail::TetRule rule = detail::grundmann_moller_tet(rule_degree);
    detail::MomentAccumulator sum(rho, apex, where);
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
      const auto& tri = mesh.triangles[t];
      // An inside-out mesh is integrated as its mirror orientation: swap two corners.
      const Vec3 a = mesh.vertices[tri[0]] - apex;
      const Vec3 b = mesh.vertices[checked.flipped ? tri[2] : tri[1]] - apex;
      const Vec3 c = mesh.vertices[checked.flipped ? tri[1] : tri[2]] - apex;
      const double volume = a.dot(b.cross(c)) / 6.0;  // signed: negative where the fan folds back
      if (volume == 0.0) continue;                    // apex in the triangle's plane: no volume
      sum.set_element("the fan tetrahedron of triangle", t);
      for (std::size_t k = 0; k < rule.weights.size(); ++k) {
        const Eigen::Vector4d& l = rule.barycentric[k];
        sum.add(apex + l(1) * a + l(2) * b + l(3) * c, volume * rule.weights[k]);
      }
      sum.end_block();
    }
    return sum.finish();
  };
  DensityResult result = detail::integrate_with_estimate(d, integrate);
  result.warnings = checked.warnings;
  return result;
}

}  // namespace tumble
