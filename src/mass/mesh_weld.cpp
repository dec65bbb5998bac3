// Welding vertices at identical positions, by sorting the positions (exact, O(n log n)).
//
// Why here and not assimp's aiProcess_JoinIdenticalVertices: that step works per mesh (so the seams
// between the meshes of a multi-part file stay open after PreTransformVertices merges them) and it
// also compares normals, texture coordinates and colours, so an STL's per-face normals keep the
// corners of a sharp edge apart. For mass properties only the position matters.
#include "tumble/mass/mesh_weld.hpp"

#include <algorithm>
#include <bit>
#include <cstdint>
#include <vector>

namespace tumble {
namespace {

struct Key {
  std::uint64_t x, y, z;  // bit patterns of the coordinates
  std::uint32_t index;    // position in the input; ties keep the first occurrence first

  friend bool operator<(const Key& a, const Key& b) {
    if (a.x != b.x) return a.x < b.x;
    if (a.y != b.y) return a.y < b.y;
    if (a.z != b.z) return a.z < b.z;
    return a.index < b.index;
  }
  bool same_position(const Key& o) const { return x == o.x && y == o.y && z == o.z; }
};

/// Bits of a coordinate with −0 mapped to +0 (x + 0.0 is +0 for both zeros, x for anything else).
std::uint64_t bits(double x) { return std::bit_cast<std::uint64_t>(x + 0.0); }

}  // namespace

TriangleMesh weld_identical_vertices(const TriangleMesh& mesh) {
  const std::size_t n = mesh.vertices.size();
  std::vector<Key> keys(n);
  for (std::size_t i = 0; i < n; ++i) {
    const Vec3& v = mesh.vertices[i];
    keys[i] = {bits(v.x()), bits(v.y()), bits(v.z()), static_cast<std::uint32_t>(i)};
  }
  std::sort(keys.begin(), keys.end());

  // first[i]: the first input vertex at vertex i's position.
  std::vector<std::uint32_t> first(n);
  for (std::size_t g = 0; g < n;) {
    std::size_t e = g;
    while (e < n && keys[e].same_position(keys[g])) first[keys[e++].index] = keys[g].index;
    g = e;
  }
  // New numbering in order of first occurrence.
  TriangleMesh out;
  std::vector<std::uint32_t> renumber(n);
  for (std::size_t i = 0; i < n; ++i) {
    if (first[i] == i) {
      renumber[i] = static_cast<std::uint32_t>(out.vertices.size());
      out.vertices.push_back(mesh.vertices[i]);
    } else {
      renumber[i] = renumber[first[i]];
    }
  }
  out.triangles.reserve(mesh.triangles.size());
  for (const auto& f : mesh.triangles) {
    auto map = [&](std::uint32_t v) { return v < n ? renumber[v] : v; };  // keep invalid as is
    out.triangles.push_back({map(f[0]), map(f[1]), map(f[2])});
  }
  return out;
}

}  // namespace tumble
