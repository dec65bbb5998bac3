// The closed surfaces of a solid mesh bound its material once (mesh_components.hpp).
#include "mesh_components.hpp"

#include <fmt/format.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <numeric>
#include <vector>

#include "tumble/error.hpp"
#include "tumble/mass/winding_number.hpp"

namespace tumble::detail {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

/// A closed surface of the mesh: its triangles, signed volume and bounding box.
struct Surface {
  std::vector<std::size_t> triangles;
  double volume = 0.0;  // Σ v₀·(v₁ × v₂)/6: positive when it faces outward
  Vec3 lo = Vec3::Constant(kInf), hi = Vec3::Constant(-kInf);
};

/// The mesh's connected surfaces (triangles sharing a vertex), in the order of their first triangle.
std::vector<Surface> surfaces_of(const TriangleMesh& mesh) {
  std::vector<std::uint32_t> parent(mesh.vertices.size());
  std::iota(parent.begin(), parent.end(), 0u);
  const auto root = [&](std::uint32_t v) {
    while (parent[v] != v) v = parent[v] = parent[parent[v]];
    return v;
  };
  for (const auto& f : mesh.triangles) {
    parent[root(f[1])] = root(f[0]);
    parent[root(f[2])] = root(f[0]);
  }
  std::vector<Surface> out;
  std::vector<std::size_t> index_of(mesh.vertices.size(), SIZE_MAX);
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    const auto& f = mesh.triangles[t];
    std::size_t& k = index_of[root(f[0])];
    if (k == SIZE_MAX) k = out.size(), out.emplace_back();
    Surface& s = out[k];
    s.triangles.push_back(t);
    const Vec3 &a = mesh.vertices[f[0]], &b = mesh.vertices[f[1]], &c = mesh.vertices[f[2]];
    s.volume += a.dot(b.cross(c)) / 6.0;
    s.lo = s.lo.cwiseMin(a).cwiseMin(b).cwiseMin(c);
    s.hi = s.hi.cwiseMax(a).cwiseMax(b).cwiseMax(c);
  }
  return out;
}

/// The winding number of one closed surface of the mesh about p (not on it), winding_number.hpp's.
double winding_number(const TriangleMesh& mesh, const Surface& s, const Vec3& p) {
  double omega = 0.0;
  for (const std::size_t t : s.triangles) {
    const auto& f = mesh.triangles[t];
    omega += triangle_solid_angle(mesh.vertices[f[0]] - p, mesh.vertices[f[1]] - p, mesh.vertices[f[2]] - p);
  }
  return omega / (4.0 * std::numbers::pi);
}

}  // namespace

void check_surfaces_bound_material_once(const TriangleMesh& mesh, double outward, const std::string& name) {
  const std::vector<Surface> surfaces = surfaces_of(mesh);
  if (surfaces.size() < 2) return;
  for (std::size_t i = 0; i < surfaces.size(); ++i) {
    const Surface& s = surfaces[i];
    // How often the other surfaces enclose s (at one of its vertices: surfaces of a valid solid do not
    // cross), counted with their orientation as integrated.
    const Vec3& p = mesh.vertices[mesh.triangles[s.triangles.front()][0]];
    double depth = 0.0;
    std::size_t encloser = i;
    for (std::size_t j = 0; j < surfaces.size(); ++j) {
      const Surface& o = surfaces[j];
      if (j == i || (p.array() < o.lo.array()).any() || (p.array() > o.hi.array()).any()) continue;
      const double w = outward * winding_number(mesh, o, p);
      if (std::abs(w) > 0.5 && (encloser == i || o.volume * outward > 0)) encloser = j;
      depth += w;
    }
    // Surfaces that touch or cross leave p on another surface, where the count is not a whole number:
    // nothing is said of those.
    const double count = std::round(depth);
    if (std::abs(depth - count) > 0.25) continue;
    const bool faces_out = s.volume * outward > 0;
    const auto first = [&](const Surface& x) {
      return fmt::format("the closed surface of triangle {} ({} triangles)", x.triangles.front(),
                         x.triangles.size());
    };
    if (faces_out && count >= 1) {
      throw MeshError(fmt::format(
          "{}: {} lies inside {}, and both face outward: the material between them would be counted "
          "twice; if the inner surface bounds a cavity, reverse its triangles (its normals must point "
          "into the cavity); if it is a part of its own, give it as another part or body",
          name, first(s), first(surfaces[encloser])));
    }
    if (!faces_out && count != 1) {
      throw MeshError(fmt::format(
          "{}: {} faces inward (a cavity's surface) but lies {} material: it would subtract a volume "
          "that is not there; reverse its triangles if it is a solid of its own",
          name, first(s), count == 0 ? "in no" : "in doubly counted"));
    }
  }
}

}  // namespace tumble::detail
