// Exact integrals over polyhedra and triangulated surfaces (the tutorial's section IV for meshes).
//
// Solid (divergence theorem, signed tetrahedra; Mirtich 1996, Eberly, Tonon 2004): the solid is the
// signed sum of the tetrahedra (ref, a, b, c) over its triangles, with a, b, c taken relative to ref:
//   6V = a·(b×c),   ∫r dV = V s/4,   ∫r rᵀ dV = V/20 (aaᵀ + bbᵀ + ccᵀ + ssᵀ),   s = a + b + c.
// Surface (a triangle of area A = |(b−a)×(c−a)|/2):
//   ∫r dA = A s/3,   ∫r rᵀ dA = A/12 (aaᵀ + bbᵀ + ccᵀ + ssᵀ).
// Both use aaᵀ + bbᵀ + ccᵀ + ssᵀ = ppᵀ + qqᵀ + uuᵀ with p = a+b, q = b+c, u = c+a (expand ssᵀ): three
// outer products instead of four.
//
// Accuracy: ref is the bounding-box centre, so the terms are of the size of the mesh, not of its
// distance from the origin (a mesh 1e5 m away would otherwise lose ten digits when the parallel-axis
// term is taken off). Triangles are summed in blocks, and the block sums pairwise (PairwiseSum), so
// the rounding error grows like log n, not n, for millions of triangles.
//
// Speed: each block first gathers its vertex coordinates into structure-of-arrays buffers (a scalar
// loop: indexed loads do not vectorise without gather instructions), then one straight loop computes
// the ten per-triangle terms, which GCC and Clang vectorise at -O2/-O3 with baseline SSE2, then four
// independent lane sums (vectorisable without reassociation flags) reduce the block.
#include "mesh_integrals.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <fmt/format.h>

#include "pairwise_sum.hpp"
#include "tumble/error.hpp"
#include "tumble/mass/mesh_mass.hpp"

namespace tumble::detail {
namespace {

static_assert(sizeof(Vec3) == 3 * sizeof(double), "vertices must be three packed doubles");
static_assert(sizeof(std::array<std::uint32_t, 3>) == 3 * sizeof(std::uint32_t),
              "triangles must be three packed indices");

constexpr std::size_t kBlock = 256;  // triangles per block: 19 buffers of 2 KiB stay in L1
constexpr std::size_t kLanes = 4;    // independent partial sums per term in a block
constexpr std::size_t kTerms = 10;   // w, w·s (3), w·(ppᵀ+qqᵀ+uuᵀ) (6: xx yy zz xy yz zx)

enum class Region { solid, surface };

using Terms = std::array<double, kTerms>;

[[noreturn]] void throw_index_out_of_range(const TriangleMesh& mesh, std::size_t t) {
  const auto& f = mesh.triangles[t];
  throw MeshError(fmt::format(
      "triangle {} has vertex indices ({}, {}, {}) but the mesh has only {} vertices (valid indices "
      "are 0..{}); the triangle list is corrupt: re-export the mesh",
      t, f[0], f[1], f[2], mesh.vertices.size(), mesh.vertices.size() - 1));
}

/// Sums of the per-triangle terms over triangles [first, first + n), n ≤ kBlock, coordinates taken
/// relative to ref. For a solid w = a·(b×c) = 6V of the tetrahedron; for a surface w = |(b−a)×(c−a)|
/// = 2A. The terms are w, w·s and w·(ppᵀ + qqᵀ + uuᵀ); the constant factors come at the end.
template <Region kind>
Terms block_sums(const TriangleMesh& mesh, std::size_t first, std::size_t n, const Vec3& ref) {
  const double* xyz = mesh.vertices.data()->data();
  const std::uint32_t* idx = mesh.triangles.data()->data() + 3 * first;
  const std::size_t nv = mesh.vertices.size();

  // Gather: corner coordinates as structure of arrays. The index check keeps the fast path memory
  // safe; its branch is never taken on a valid mesh and costs about one cycle per triangle.
  alignas(64) double g[9][kBlock];
  for (std::size_t k = 0; k < n; ++k) {
    const std::uint32_t i0 = idx[3 * k], i1 = idx[3 * k + 1], i2 = idx[3 * k + 2];
    if (i0 >= nv || i1 >= nv || i2 >= nv) throw_index_out_of_range(mesh, first + k);
    const double* A = xyz + 3 * std::size_t{i0};
    const double* B = xyz + 3 * std::size_t{i1};
    const double* C = xyz + 3 * std::size_t{i2};
    g[0][k] = A[0], g[1][k] = A[1], g[2][k] = A[2];
    g[3][k] = B[0], g[4][k] = B[1], g[5][k] = B[2];
    g[6][k] = C[0], g[7][k] = C[1], g[8][k] = C[2];
  }

  // Terms: a straight, branch-free loop over contiguous arrays (vectorised).
  const double rx = ref.x(), ry = ref.y(), rz = ref.z();
  alignas(64) double t[kTerms][kBlock];
  for (std::size_t k = 0; k < n; ++k) {
    const double ax = g[0][k] - rx, ay = g[1][k] - ry, az = g[2][k] - rz;
    const double bx = g[3][k] - rx, by = g[4][k] - ry, bz = g[5][k] - rz;
    const double cx = g[6][k] - rx, cy = g[7][k] - ry, cz = g[8][k] - rz;
    double w;
    if constexpr (kind == Region::solid) {
      w = ax * (by * cz - bz * cy) + ay * (bz * cx - bx * cz) + az * (bx * cy - by * cx);
    } else {
      const double ux = bx - ax, uy = by - ay, uz = bz - az;
      const double vx = cx - ax, vy = cy - ay, vz = cz - az;
      const double nx = uy * vz - uz * vy, ny = uz * vx - ux * vz, nz = ux * vy - uy * vx;
      w = std::sqrt(nx * nx + ny * ny + nz * nz);
    }
    // p = a+b, q = b+c, u = c+a; s = a + q. Written so that swapping b and c (flipping the triangle)
    // only permutes p and u and leaves every sum bit-identical: a flipped mesh gives exactly −w·(...).
    const double px = ax + bx, py = ay + by, pz = az + bz;
    const double qx = bx + cx, qy = by + cy, qz = bz + cz;
    const double ux = cx + ax, uy = cy + ay, uz = cz + az;
    t[0][k] = w;
    t[1][k] = w * (ax + qx);
    t[2][k] = w * (ay + qy);
    t[3][k] = w * (az + qz);
    t[4][k] = w * ((px * px + ux * ux) + qx * qx);
    t[5][k] = w * ((py * py + uy * uy) + qy * qy);
    t[6][k] = w * ((pz * pz + uz * uz) + qz * qz);
    t[7][k] = w * ((px * py + ux * uy) + qx * qy);
    t[8][k] = w * ((py * pz + uy * uz) + qy * qz);
    t[9][k] = w * ((pz * px + uz * ux) + qz * qx);
  }
  const std::size_t padded = (n + kLanes - 1) / kLanes * kLanes;
  for (std::size_t r = 0; r < kTerms; ++r) {
    for (std::size_t k = n; k < padded; ++k) t[r][k] = 0.0;
  }

  // Reduce: kLanes interleaved running sums per term, then a balanced sum of the lanes.
  Terms sums{};
  for (std::size_t r = 0; r < kTerms; ++r) {
    double lane[kLanes] = {};
    for (std::size_t k = 0; k < padded; k += kLanes) {
      for (std::size_t l = 0; l < kLanes; ++l) lane[l] += t[r][k + l];
    }
    sums[r] = (lane[0] + lane[1]) + (lane[2] + lane[3]);
  }
  return sums;
}

template <Region kind>
RegionMoments moments(const TriangleMesh& mesh) {
  RegionMoments m;
  m.ref = bounding_box_centre(mesh);
  PairwiseSum<kTerms> sum;
  const std::size_t nt = mesh.triangles.size();
  for (std::size_t first = 0; first < nt; first += kBlock) {
    sum.add(block_sums<kind>(mesh, first, std::min(kBlock, nt - first), m.ref));
  }
  const Terms s = sum.total();
  // Solid: V = Σw/6, ∫r = Σw s/24, ∫rrᵀ = Σw(...)/120. Surface: A = Σw/2, ∫r = Σw s/6, ∫rrᵀ = Σw(...)/24.
  constexpr bool solid = kind == Region::solid;
  const double k0 = solid ? 1.0 / 6.0 : 0.5;
  const double k1 = solid ? 1.0 / 24.0 : 1.0 / 6.0;
  const double k2 = solid ? 1.0 / 120.0 : 1.0 / 24.0;
  m.measure = k0 * s[0];
  m.first = k1 * Vec3(s[1], s[2], s[3]);
  m.second << s[4], s[7], s[9],  //
      s[7], s[5], s[8],          //
      s[9], s[8], s[6];
  m.second *= k2;
  return m;
}

}  // namespace

Vec3 bounding_box_centre(const TriangleMesh& mesh) {
  if (mesh.vertices.empty()) return Vec3::Zero();
  Vec3 lo = mesh.vertices.front(), hi = lo;
  for (const Vec3& v : mesh.vertices) {
    lo = lo.cwiseMin(v);
    hi = hi.cwiseMax(v);
  }
  return 0.5 * (lo + hi);
}

RegionMoments solid_moments(const TriangleMesh& mesh) { return moments<Region::solid>(mesh); }

RegionMoments surface_moments(const TriangleMesh& mesh) { return moments<Region::surface>(mesh); }

MassProperties unit_properties(const RegionMoments& m) {
  const Mat3 I_ref = m.second.trace() * Mat3::Identity() - m.second;  // I = tr(C) I₃ − C
  if (m.measure == 0.0) return MassProperties{0.0, m.ref, I_ref, 0.0};
  const Vec3 d = m.first / m.measure;
  return MassProperties{m.measure, m.ref + d, I_ref - parallel_axis_term(m.measure, d), m.measure};
}

}  // namespace tumble::detail

namespace tumble {

MassProperties integrate_solid_mesh(const TriangleMesh& mesh) {
  return detail::unit_properties(detail::solid_moments(mesh));
}

}  // namespace tumble
