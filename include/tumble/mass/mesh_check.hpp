#pragma once
// Topology and geometry checks of a triangle mesh: what keeps it from bounding a solid.
#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "tumble/mass/triangle_mesh.hpp"

namespace tumble {

/// One triangle's use of an edge: the triangle runs along it from vertex `from` to vertex `to`.
struct EdgeUse {
  std::uint32_t from = 0;
  std::uint32_t to = 0;
  std::size_t triangle = 0;
};

/// A triangle and its three vertex indices.
struct TriangleRef {
  std::size_t triangle = 0;
  std::array<std::uint32_t, 3> vertices{};
};

/// A vertex and its coordinates.
struct VertexRef {
  std::size_t vertex = 0;
  Vec3 position = Vec3::Zero();
};

/// An edge (v0 < v1) shared by more than two triangles.
struct NonManifoldEdge {
  std::uint32_t v0 = 0;
  std::uint32_t v1 = 0;
  std::vector<std::size_t> triangles;  ///< all triangles on the edge, ascending
};

/// An edge that two triangles traverse in the same direction (their windings disagree).
struct MisorientedEdge {
  std::uint32_t from = 0;
  std::uint32_t to = 0;
  std::size_t first = 0;   ///< the lower triangle index
  std::size_t second = 0;  ///< the higher triangle index
};

/// What check_mesh() found. Each defect has its total count and the first few instances (those with
/// the lowest triangle or vertex index), at most MeshReport::listed of them.
struct MeshReport {
  static constexpr std::size_t listed = 5;

  std::size_t vertex_count = 0;
  std::size_t triangle_count = 0;

  std::size_t non_finite_vertex_count = 0;  ///< NaN or infinite coordinates
  std::vector<VertexRef> non_finite_vertices;
  std::size_t out_of_range_count = 0;  ///< triangles with an index ≥ vertex_count
  std::vector<TriangleRef> out_of_range_triangles;
  std::size_t degenerate_count = 0;  ///< a repeated index, or zero area (see check_mesh)
  std::vector<TriangleRef> degenerate_triangles;
  std::size_t boundary_edge_count = 0;  ///< edges used by one triangle only (holes)
  std::vector<EdgeUse> boundary_edges;
  std::size_t non_manifold_edge_count = 0;  ///< edges used by more than two triangles
  std::vector<NonManifoldEdge> non_manifold_edges;
  std::size_t misoriented_edge_count = 0;  ///< edges two triangles traverse the same way
  std::vector<MisorientedEdge> misoriented_edges;

  double surface_area = 0.0;  ///< Σ triangle areas (m²); 0 if indices or coordinates are invalid
  double diagonal = 0.0;      ///< length of the bounding box diagonal (m), the mesh's scale

  /// Every index refers to a vertex and every coordinate is finite (the mesh can be integrated).
  bool usable() const { return non_finite_vertex_count == 0 && out_of_range_count == 0; }
  /// Bounds a solid: usable, no degenerate triangles, closed, manifold, consistently oriented.
  bool solid() const {
    return usable() && degenerate_count == 0 && boundary_edge_count == 0 && non_manifold_edge_count == 0 &&
           misoriented_edge_count == 0;
  }
};

/// Checks a mesh: finite coordinates, indices in range, degenerate triangles (a repeated index, or an
/// area that is zero to the rounding of the coordinates: |(b−a)×(c−a)| ≤ 16 ε S ℓ, with S the largest
/// coordinate magnitude plus the bounding-box diagonal and ℓ the triangle's longest edge), and the edge
/// table: boundary, non-manifold and misoriented edges. Triangles with a repeated index are left out
/// of the edge table. O(n) time: edges are bucketed by their lower vertex (a counting sort).
[[nodiscard]] MeshReport check_mesh(const TriangleMesh& mesh);

/// Only the checks every integration needs: finite coordinates and indices in range (and the
/// diagonal). Cheap: one pass over vertices and one over indices.
[[nodiscard]] MeshReport check_mesh_indices(const TriangleMesh& mesh);

/// The mesh without its degenerate triangles (as check_mesh judges them; the mesh's indices must be in
/// range), their indices in `dropped`. A zero-area triangle adds nothing to a solid's integrals, so a
/// closed surface left by dropping them bounds the same solid.
[[nodiscard]] TriangleMesh without_degenerate_triangles(const TriangleMesh& mesh,
                                                        std::vector<std::size_t>& dropped);

/// One sentence per defect a solid must not have: what, how many, the first few indices, and how to
/// fix it, joined by "; ". Empty if report.solid().
std::string describe_solid_defects(const MeshReport& report);

}  // namespace tumble
