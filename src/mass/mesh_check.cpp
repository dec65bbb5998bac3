// Mesh checks for solids: coordinates, indices, degenerate triangles and the edge table.
//
// The edge table groups the 3n directed edges of the triangles by their undirected edge {lo, hi}. A
// closed, manifold, consistently oriented mesh uses every edge exactly twice, once in each direction.
// Grouping is a counting sort by the lower vertex index (one pass to count, one to scatter), then a
// sort of each small bucket by (hi, triangle): O(n) for bounded vertex valence, and the buckets of a
// mesh with coherent vertex order are visited in memory order. That beats a comparison sort of 3n
// 64-bit keys (and hashing) for millions of triangles.
#include "tumble/mass/mesh_check.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <limits>

#include "pairwise_sum.hpp"
#include "tumble/error.hpp"

namespace tumble {
namespace {

/// Keeps the `MeshReport::listed` items with the smallest keys offered so far, in key order.
template <class T, class Key>
class FirstFew {
 public:
  explicit FirstFew(std::vector<T>& out) : out_(out) {}
  void offer(const Key& key, T item) {
    if (keys_.size() == MeshReport::listed && !(key < keys_.back())) return;
    const auto at = std::upper_bound(keys_.begin(), keys_.end(), key) - keys_.begin();
    keys_.insert(keys_.begin() + at, key);
    out_.insert(out_.begin() + at, std::move(item));
    if (keys_.size() > MeshReport::listed) {
      keys_.pop_back();
      out_.pop_back();
    }
  }

 private:
  std::vector<T>& out_;
  std::vector<Key> keys_;
};

bool repeated_index(const std::array<std::uint32_t, 3>& f) {
  return f[0] == f[1] || f[1] == f[2] || f[2] == f[0];
}

void check_vertices(const TriangleMesh& mesh, MeshReport& r, double& max_abs) {
  Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity());
  Vec3 hi = -lo;
  max_abs = 0.0;
  for (std::size_t i = 0; i < mesh.vertices.size(); ++i) {
    const Vec3& v = mesh.vertices[i];
    if (!v.allFinite()) {
      if (r.non_finite_vertex_count++ < MeshReport::listed) r.non_finite_vertices.push_back({i, v});
      continue;
    }
    lo = lo.cwiseMin(v);
    hi = hi.cwiseMax(v);
    max_abs = std::max(max_abs, v.cwiseAbs().maxCoeff());
  }
  if (lo.x() <= hi.x()) r.diagonal = (hi - lo).norm();
}

void check_indices(const TriangleMesh& mesh, MeshReport& r) {
  const std::size_t nv = mesh.vertices.size();
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    const auto& f = mesh.triangles[t];
    if (f[0] >= nv || f[1] >= nv || f[2] >= nv) {
      if (r.out_of_range_count++ < MeshReport::listed) r.out_of_range_triangles.push_back({t, f});
    }
  }
}

/// Degenerate triangles and the surface area. A triangle whose corners are collinear in exact
/// arithmetic still gets a cross product of the size of the coordinates' rounding, about
/// ε·S·ℓ (S the coordinate magnitude, ℓ the edge length); 16 ε S ℓ covers the few roundings of
/// two subtractions and a cross product.
/// Whether triangle f is degenerate at tolerance `tol` (check_triangles); adds twice its area to `area2`.
bool degenerate_triangle(const TriangleMesh& mesh, const std::array<std::uint32_t, 3>& f, double tol,
                         double& area2) {
  if (repeated_index(f)) return true;
  const Vec3& a = mesh.vertices[f[0]];
  const Vec3& b = mesh.vertices[f[1]];
  const Vec3& c = mesh.vertices[f[2]];
  const Vec3 n = (b - a).cross(c - a);
  const double n2 = n.squaredNorm();
  const double l2 = std::max({(b - a).squaredNorm(), (c - a).squaredNorm(), (c - b).squaredNorm()});
  area2 += std::sqrt(n2);
  return n2 <= tol * tol * l2;
}

double degenerate_tolerance(const MeshReport& r, double max_abs) {
  return 16.0 * std::numeric_limits<double>::epsilon() * (max_abs + r.diagonal);
}

void check_triangles(const TriangleMesh& mesh, MeshReport& r, double max_abs) {
  const double tol = degenerate_tolerance(r, max_abs);
  detail::PairwiseSum<1> area;
  double block = 0.0;  // twice the area of the current block of 256 triangles
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    const auto& f = mesh.triangles[t];
    const bool degenerate = degenerate_triangle(mesh, f, tol, block);
    if (degenerate && r.degenerate_count++ < MeshReport::listed) {
      r.degenerate_triangles.push_back({t, f});
    }
    if ((t + 1) % 256 == 0) {
      area.add({block});
      block = 0.0;
    }
  }
  area.add({block});
  r.surface_area = 0.5 * area.total()[0];
}

void check_edges(const TriangleMesh& mesh, MeshReport& r) {
  const std::size_t nv = mesh.vertices.size();
  const std::size_t nt = mesh.triangles.size();
  if (nt >= (std::size_t{1} << 31)) {
    throw MeshError(
        fmt::format("the mesh has {} triangles; the edge check handles fewer than 2^31: split the mesh", nt));
  }
  // Entry: hi << 32 | triangle << 1 | (1 if the triangle runs hi → lo). Sorting a bucket by it orders
  // by the other vertex, then by triangle.
  std::vector<std::size_t> end(nv + 1, 0);
  for (const auto& f : mesh.triangles) {
    if (repeated_index(f)) continue;
    for (int e = 0; e < 3; ++e) ++end[std::min(f[e], f[(e + 1) % 3]) + 1];
  }
  for (std::size_t v = 0; v < nv; ++v) end[v + 1] += end[v];  // end[v] = start of bucket v
  std::vector<std::uint64_t> entries(end[nv]);
  for (std::size_t t = 0; t < nt; ++t) {
    const auto& f = mesh.triangles[t];
    if (repeated_index(f)) continue;
    for (int e = 0; e < 3; ++e) {
      const std::uint32_t from = f[e], to = f[(e + 1) % 3];
      const std::uint32_t lo = std::min(from, to), hi = std::max(from, to);
      entries[end[lo]++] = std::uint64_t{hi} << 32 | std::uint64_t{t} << 1 | (from > to ? 1U : 0U);
    }
  }
  // Now end[v] is the end of bucket v, and bucket v starts where bucket v − 1 ends.

  // Listed first: the defects of the lowest-numbered triangles.
  FirstFew<EdgeUse, std::pair<std::size_t, std::uint32_t>> boundary(r.boundary_edges);
  FirstFew<NonManifoldEdge, std::size_t> non_manifold(r.non_manifold_edges);
  FirstFew<MisorientedEdge, std::size_t> misoriented(r.misoriented_edges);
  auto triangle_of = [](std::uint64_t x) { return static_cast<std::size_t>((x & 0xffffffffU) >> 1); };
  auto reversed = [](std::uint64_t x) { return (x & 1U) != 0U; };

  std::size_t begin = 0;
  for (std::size_t lo = 0; lo < nv; begin = end[lo], ++lo) {
    const auto first = entries.begin() + static_cast<std::ptrdiff_t>(begin);
    const auto last = entries.begin() + static_cast<std::ptrdiff_t>(end[lo]);
    std::sort(first, last);
    for (auto g = first; g != last;) {
      const std::uint64_t hi64 = *g >> 32;
      auto g_end = g;
      while (g_end != last && (*g_end >> 32) == hi64) ++g_end;
      const auto hi = static_cast<std::uint32_t>(hi64);
      const auto v0 = static_cast<std::uint32_t>(lo);
      const auto uses = g_end - g;
      if (uses == 1) {
        ++r.boundary_edge_count;
        const EdgeUse e = reversed(*g) ? EdgeUse{hi, v0, triangle_of(*g)} : EdgeUse{v0, hi, triangle_of(*g)};
        boundary.offer({e.triangle, e.from}, e);
      } else if (uses == 2) {
        if (reversed(g[0]) == reversed(g[1])) {
          ++r.misoriented_edge_count;
          const bool rev = reversed(g[0]);
          misoriented.offer(triangle_of(g[0]), MisorientedEdge{rev ? hi : v0, rev ? v0 : hi,
                                                               triangle_of(g[0]), triangle_of(g[1])});
        }
      } else {
        ++r.non_manifold_edge_count;
        NonManifoldEdge e{v0, hi, {}};
        for (auto x = g; x != g_end; ++x) e.triangles.push_back(triangle_of(*x));
        non_manifold.offer(triangle_of(*g), std::move(e));
      }
      g = g_end;
    }
  }
}

/// ", ..." when more exist than are listed.
std::string more(std::size_t count) { return count > MeshReport::listed ? ", ..." : ""; }

std::string plural(std::size_t n, const char* one, const char* many) {
  return fmt::format("{} {}", n, n == 1 ? one : many);
}

std::string triangle_list(const std::vector<TriangleRef>& list, std::size_t count) {
  std::string s;
  for (const TriangleRef& t : list) {
    s += fmt::format("{}triangle {} (vertices {}, {}, {})", s.empty() ? "" : ", ", t.triangle, t.vertices[0],
                     t.vertices[1], t.vertices[2]);
  }
  return s + more(count);
}

}  // namespace

MeshReport check_mesh_indices(const TriangleMesh& mesh) {
  MeshReport r;
  r.vertex_count = mesh.vertices.size();
  r.triangle_count = mesh.triangles.size();
  double max_abs = 0.0;
  check_vertices(mesh, r, max_abs);
  check_indices(mesh, r);
  return r;
}

MeshReport check_mesh(const TriangleMesh& mesh) {
  MeshReport r;
  r.vertex_count = mesh.vertices.size();
  r.triangle_count = mesh.triangles.size();
  double max_abs = 0.0;
  check_vertices(mesh, r, max_abs);
  check_indices(mesh, r);
  if (!r.usable()) return r;  // nothing below can be computed
  check_triangles(mesh, r, max_abs);
  check_edges(mesh, r);
  return r;
}

TriangleMesh without_degenerate_triangles(const TriangleMesh& mesh, std::vector<std::size_t>& dropped) {
  MeshReport r;
  double max_abs = 0.0;
  check_vertices(mesh, r, max_abs);
  const double tol = degenerate_tolerance(r, max_abs);
  TriangleMesh kept;
  kept.vertices = mesh.vertices;
  kept.triangles.reserve(mesh.triangles.size());
  dropped.clear();
  double area2 = 0.0;
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    if (degenerate_triangle(mesh, mesh.triangles[t], tol, area2)) {
      dropped.push_back(t);
    } else {
      kept.triangles.push_back(mesh.triangles[t]);
    }
  }
  return kept;
}

std::string describe_solid_defects(const MeshReport& r) {
  std::vector<std::string> out;
  if (r.non_finite_vertex_count > 0) {
    std::string list;
    for (const VertexRef& v : r.non_finite_vertices) {
      list += fmt::format("{}vertex {} ({}, {}, {})", list.empty() ? "" : ", ", v.vertex, v.position.x(),
                          v.position.y(), v.position.z());
    }
    out.push_back(
        fmt::format("{} non-finite coordinates (NaN or infinity), first: {}{}; fix or remove them in the "
                    "source data",
                    plural(r.non_finite_vertex_count, "vertex has", "vertices have"), list,
                    more(r.non_finite_vertex_count)));
  }
  if (r.out_of_range_count > 0) {
    out.push_back(fmt::format(
        "{} to vertices that do not exist (the mesh has {} vertices, valid indices 0..{}), first: "
        "{}; the triangle list is corrupt: re-export the mesh",
        plural(r.out_of_range_count, "triangle refers", "triangles refer"), r.vertex_count,
        r.vertex_count == 0 ? 0 : r.vertex_count - 1,
        triangle_list(r.out_of_range_triangles, r.out_of_range_count)));
  }
  if (r.degenerate_count > 0) {
    out.push_back(
        fmt::format("the mesh has {} (a repeated vertex or zero area), first: {}; remove them (e.g. MeshLab: "
                    "Remove Duplicate Faces / Remove Zero Area Faces) or re-export the mesh",
                    plural(r.degenerate_count, "degenerate triangle", "degenerate triangles"),
                    triangle_list(r.degenerate_triangles, r.degenerate_count)));
  }
  if (r.boundary_edge_count > 0) {
    std::string list;
    for (const EdgeUse& e : r.boundary_edges) {
      list +=
          fmt::format("{}edge ({},{}) of triangle {}", list.empty() ? "" : ", ", e.from, e.to, e.triangle);
    }
    out.push_back(fmt::format(
        "the mesh has {} (an open surface), first: {}{}; close the holes in a mesh editor, or "
        "treat it as a thin-walled part (shell mass properties)",
        plural(r.boundary_edge_count, "boundary edge", "boundary edges"), list, more(r.boundary_edge_count)));
  }
  if (r.non_manifold_edge_count > 0) {
    std::string list;
    for (const NonManifoldEdge& e : r.non_manifold_edges) {
      list += fmt::format("{}edge ({},{}) of triangles {{{}}}", list.empty() ? "" : ", ", e.v0, e.v1,
                          fmt::join(e.triangles, ", "));
    }
    out.push_back(fmt::format(
        "the mesh has {} (shared by more than two triangles), first: {}{}; separate the bodies "
        "that touch along these edges or repair the mesh (e.g. MeshLab: Repair Non Manifold Edges)",
        plural(r.non_manifold_edge_count, "non-manifold edge", "non-manifold edges"), list,
        more(r.non_manifold_edge_count)));
  }
  if (r.misoriented_edge_count > 0) {
    std::string list;
    for (const MisorientedEdge& e : r.misoriented_edges) {
      list += fmt::format("{}edge ({},{}) in triangles {} and {}", list.empty() ? "" : ", ", e.from, e.to,
                          e.first, e.second);
    }
    out.push_back(fmt::format(
        "the mesh is inconsistently oriented: {} traversed in the same direction by both of "
        "their triangles, first: {}{}; flip one triangle of each pair so that all wind "
        "counter-clockwise seen from outside (e.g. MeshLab: Re-Orient all faces coherently)",
        plural(r.misoriented_edge_count, "edge is", "edges are"), list, more(r.misoriented_edge_count)));
  }
  std::string joined;
  for (const std::string& s : out) joined += (joined.empty() ? "" : "; ") + s;
  return joined;
}

}  // namespace tumble
