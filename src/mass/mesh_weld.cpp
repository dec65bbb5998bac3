// Welding vertices at identical positions, by sorting the positions (exact, O(n log n)).
//
// Why here and not assimp's aiProcess_JoinIdenticalVertices: that step works per mesh (so the seams
// between the meshes of a multi-part file stay open after PreTransformVertices merges them) and it
// also compares normals, texture coordinates and colours, so an STL's per-face normals keep the
// corners of a sharp edge apart. For mass properties only the position matters.
#include "tumble/mass/mesh_weld.hpp"

#include <algorithm>
#include <boost/sort/spreadsort/integer_sort.hpp>
#include <bit>
#include <cstdint>
#include <vector>

namespace tumble {
namespace {

/// Bits of a coordinate with −0 mapped to +0 (x + 0.0 is +0 for both zeros, x for anything else).
std::uint64_t bits(double x) { return std::bit_cast<std::uint64_t>(x + 0.0); }

/// A 64-bit mix of the three bit patterns (splitmix64 finaliser on a running combination): equal
/// positions give equal keys; different positions collide with probability ~2⁻⁶⁴, and collisions are
/// separated below by comparing the positions themselves.
std::uint64_t position_key(const Vec3& v) {
  auto mix = [](std::uint64_t z) {
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
  };
  return mix(mix(mix(bits(v.x())) ^ bits(v.y())) ^ bits(v.z()));
}

struct Key {
  std::uint64_t key;
  std::uint32_t index;
};

bool same_position(const Vec3& a, const Vec3& b) {
  return bits(a.x()) == bits(b.x()) && bits(a.y()) == bits(b.y()) && bits(a.z()) == bits(b.z());
}

}  // namespace

TriangleMesh weld_identical_vertices(const TriangleMesh& mesh) {
  const std::size_t n = mesh.vertices.size();
  std::vector<Key> keys(n);
  for (std::size_t i = 0; i < n; ++i) keys[i] = {position_key(mesh.vertices[i]), static_cast<std::uint32_t>(i)};
  // Boost's spreadsort (a radix/comparison hybrid) on the 64-bit keys: ~5× faster than std::sort on
  // three-double keys for the millions of corners of a large STL, where welding used to dominate the
  // time from file to result.
  boost::sort::spreadsort::integer_sort(keys.begin(), keys.end(),
                                        [](const Key& k, unsigned shift) { return k.key >> shift; },
                                        [](const Key& a, const Key& b) { return a.key < b.key; });

  // first[i]: the first input vertex at vertex i's position.
  std::vector<std::uint32_t> first(n);
  for (std::size_t g = 0; g < n;) {
    std::size_t e = g + 1;
    while (e < n && keys[e].key == keys[g].key) ++e;
    // A run of equal keys holds one position unless the hash collided: check against its first member
    // (one pass, no sorting); only a collision takes the exact quadratic grouping.
    std::uint32_t lowest = keys[g].index;
    bool one_position = true;
    const Vec3& p = mesh.vertices[keys[g].index];
    for (std::size_t i = g + 1; i < e; ++i) {
      lowest = std::min(lowest, keys[i].index);
      one_position = one_position && same_position(mesh.vertices[keys[i].index], p);
    }
    if (one_position) {
      for (std::size_t i = g; i < e; ++i) first[keys[i].index] = lowest;
    } else {
      std::sort(keys.begin() + static_cast<std::ptrdiff_t>(g), keys.begin() + static_cast<std::ptrdiff_t>(e),
                [](const Key& a, const Key& b) { return a.index < b.index; });
      for (std::size_t i = g; i < e; ++i) {
        const std::uint32_t vi = keys[i].index;
        first[vi] = vi;
        for (std::size_t j = g; j < i; ++j) {
          const std::uint32_t vj = keys[j].index;
          if (first[vj] == vj && same_position(mesh.vertices[vj], mesh.vertices[vi])) {
            first[vi] = vj;
            break;
          }
        }
      }
    }
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
