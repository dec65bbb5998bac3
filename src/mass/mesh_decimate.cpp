#include "tumble/mass/mesh_decimate.hpp"

#include <algorithm>
#include <cmath>
#include <unordered_map>

#include "tumble/mass/shapes.hpp"
#include "tumble/mass/tessellate.hpp"

namespace tumble {
namespace {

TriangleMesh cluster(const TriangleMesh& mesh, int cells, const Vec3& lo, const Vec3& size) {
  TriangleMesh out;
  std::unordered_map<std::uint64_t, std::uint32_t> cell_vertex;  // cell → its vertex in `out`
  std::vector<int> count;
  std::vector<std::uint32_t> vertex_of(mesh.vertices.size());
  for (size_t i = 0; i < mesh.vertices.size(); ++i) {
    std::uint64_t key = 0;
    for (int k = 0; k < 3; ++k) {
      const double u = size(k) > 0 ? (mesh.vertices[i](k) - lo(k)) / size(k) : 0.0;
      key = key * 2048 + static_cast<std::uint64_t>(std::clamp(static_cast<int>(u * cells), 0, cells - 1));
    }
    const auto [it, fresh] = cell_vertex.try_emplace(key, static_cast<std::uint32_t>(out.vertices.size()));
    if (fresh) {
      out.vertices.push_back(Vec3::Zero());
      count.push_back(0);
    }
    out.vertices[it->second] += mesh.vertices[i];
    ++count[it->second];
    vertex_of[i] = it->second;
  }
  for (size_t v = 0; v < out.vertices.size(); ++v) out.vertices[v] /= count[v];  // the cell's mean
  for (const auto& t : mesh.triangles) {
    const std::array<std::uint32_t, 3> c{vertex_of[t[0]], vertex_of[t[1]], vertex_of[t[2]]};
    if (c[0] != c[1] && c[1] != c[2] && c[0] != c[2]) out.triangles.push_back(c);
  }
  return out;
}

}  // namespace

TriangleMesh decimate(const TriangleMesh& mesh, std::size_t max_triangles) {
  if (mesh.triangles.size() <= max_triangles || mesh.vertices.empty()) return mesh;
  Vec3 lo = mesh.vertices.front(), hi = lo;
  for (const Vec3& v : mesh.vertices) {
    lo = lo.cwiseMin(v);
    hi = hi.cwiseMax(v);
  }
  for (int cells = 1024; cells >= 2; cells /= 2) {
    TriangleMesh out = cluster(mesh, cells, lo, hi - lo);
    if (out.triangles.size() <= max_triangles) return out;
  }
  return cluster(mesh, 1, lo, hi - lo);  // one cell: nothing left to draw
}

Vec3 inertia_box_edges(double m, const Vec3& Lambda) {
  Vec3 edges;
  for (int i = 0; i < 3; ++i) {
    const double a2 = 6.0 * (Lambda((i + 1) % 3) + Lambda((i + 2) % 3) - Lambda(i)) / m;
    edges(i) = std::sqrt(std::max(a2, 0.0));
  }
  // A flat body (a triangle inequality met with equality) has a zero edge: draw it thin, not invisible.
  return edges.cwiseMax(1e-3 * edges.maxCoeff());
}

TriangleMesh inertia_box(double m, const Vec3& Lambda) {
  return tessellate(Box{inertia_box_edges(m, Lambda)}, 4);
}

}  // namespace tumble
