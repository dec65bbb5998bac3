#pragma once
// Welding: one vertex per position.
#include <cstdint>
#include <vector>

#include "tumble/mass/triangle_mesh.hpp"

namespace tumble {

/// The same mesh with vertices at bit-identical positions merged into one (+0 and −0 count as equal,
/// nothing else is rounded: welding is exact and never closes a real gap). Triangles are renumbered;
/// the vertices keep the order in which they first occur; unreferenced vertices are kept.
TriangleMesh weld_identical_vertices(const TriangleMesh& mesh);

/// Welding one position at a time, for a reader that meets corners one by one (a binary STL's): add()
/// gives each position's index among the distinct ones so far, a new one the next. The same rule and
/// order as weld_identical_vertices, which is this applied to every vertex in turn.
class VertexWelder {
 public:
  /// Room for about `expected` distinct positions before the table grows.
  explicit VertexWelder(std::size_t expected = 0);
  std::uint32_t add(const Vec3& position);
  /// The distinct positions, in the order they were first added.
  const std::vector<Vec3>& vertices() const { return vertices_; }
  std::vector<Vec3> take_vertices() { return std::move(vertices_); }

 private:
  struct Slot {
    std::uint64_t key;
    std::uint32_t index;  // into vertices_; kEmpty: free
  };
  void grow();
  std::vector<Slot> table_;
  std::vector<Vec3> vertices_;
};

}  // namespace tumble
