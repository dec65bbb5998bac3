// Tessellation of the primitive shapes. Everything but the box is a surface of revolution about z: a
// profile polyline in the (ρ, z) half-plane swept through `segments` angles, with points on the axis
// (ρ = 0) becoming single pole vertices. The ellipsoid is the unit sphere's mesh scaled by (a, b, c),
// which keeps every vertex on the ellipsoid.
#include "tumble/mass/tessellate.hpp"

#include <cmath>
#include <fmt/format.h>
#include <numbers>
#include <vector>

#include "tumble/error.hpp"

namespace tumble {
namespace {

using std::numbers::pi;
using Index = std::uint32_t;

template <class... Ts>
struct Overloaded : Ts... {
  using Ts::operator()...;
};
template <class... Ts>
Overloaded(Ts...) -> Overloaded<Ts...>;  // Clang 14 lacks C++20 aggregate deduction

struct ProfilePoint {
  double rho;  ///< distance from the z axis; 0 makes a pole
  double z;
};

/// Sweeps the profile around z. Orientation: with φ increasing counter-clockwise about +z and the
/// profile running so that the surface lies to its left seen from outside (bottom to top along the
/// outside, as for a sphere from south to north pole), the triangles (k,j), (k,j+1), (k+1,j+1) have
/// normal φ̂ × (profile direction) pointing outward; at a sphere's equator that is φ̂ × ẑ = ρ̂.
/// A closed profile (torus) wraps around; an open one must start and end on the axis.
TriangleMesh revolve(const std::vector<ProfilePoint>& profile, int segments, bool closed) {
  TriangleMesh mesh;
  const std::size_t n = static_cast<std::size_t>(segments);
  const std::size_t rings = profile.size();
  std::vector<std::size_t> first(rings);  // index of ring k's first vertex (the pole for ρ = 0)
  for (std::size_t k = 0; k < rings; ++k) {
    first[k] = mesh.vertices.size();
    const ProfilePoint& p = profile[k];
    if (p.rho == 0.0) {
      mesh.vertices.emplace_back(0.0, 0.0, p.z);
      continue;
    }
    for (std::size_t j = 0; j < n; ++j) {
      const double phi = 2.0 * pi * static_cast<double>(j) / static_cast<double>(n);
      mesh.vertices.emplace_back(p.rho * std::cos(phi), p.rho * std::sin(phi), p.z);
    }
  }
  auto vertex = [&](std::size_t k, std::size_t j) {
    return static_cast<Index>(profile[k].rho == 0.0 ? first[k] : first[k] + j % n);
  };
  const std::size_t bands = closed ? rings : rings - 1;
  for (std::size_t k = 0; k < bands; ++k) {
    const std::size_t k1 = (k + 1) % rings;
    for (std::size_t j = 0; j < n; ++j) {
      const Index a = vertex(k, j), b = vertex(k, j + 1), c = vertex(k1, j + 1), d = vertex(k1, j);
      if (profile[k].rho != 0.0) mesh.triangles.push_back({a, b, c});   // none at a lower pole
      if (profile[k1].rho != 0.0) mesh.triangles.push_back({a, c, d});  // none at an upper pole
    }
  }
  return mesh;
}

/// Quarter or half circle of radius r centred at (0, zc): angles from θ0 to θ1 in `steps` steps,
/// ρ = r cos θ, z = zc + r sin θ; points at θ = ±π/2 land exactly on the axis.
void arc(std::vector<ProfilePoint>& out, double r, double zc, double theta0, double theta1, int steps,
         bool include_first) {
  for (int i = include_first ? 0 : 1; i <= steps; ++i) {
    const double theta = theta0 + (theta1 - theta0) * i / steps;
    const bool pole = std::abs(std::abs(theta) - pi / 2) < 1e-12;
    out.push_back(
        {pole ? 0.0 : r * std::cos(theta), zc + (pole ? std::copysign(r, theta) : r * std::sin(theta))});
  }
}

TriangleMesh unit_sphere(int segments) {
  std::vector<ProfilePoint> profile;
  arc(profile, 1.0, 0.0, -pi / 2, pi / 2, std::max(2, segments / 2), true);
  return revolve(profile, segments, false);
}

TriangleMesh box(const Vec3& size) {
  // Corner i has coordinate ±size/2 along axis a as bit a of i is set or not.
  TriangleMesh mesh;
  for (int i = 0; i < 8; ++i) {
    mesh.vertices.emplace_back((i & 1 ? 0.5 : -0.5) * size.x(), (i & 2 ? 0.5 : -0.5) * size.y(),
                               (i & 4 ? 0.5 : -0.5) * size.z());
  }
  for (int a = 0; a < 3; ++a) {
    // Going round (−,−), (+,−), (+,+), (−,+) in the axes b, c = a+1, a+2 (cyclic) turns
    // counter-clockwise about ê_b × ê_c = ê_a: outward on the + face, reversed on the − face.
    const int b = (a + 1) % 3, c = (a + 2) % 3;
    for (int side = 0; side < 2; ++side) {
      const int base = side << a;
      Index q[4] = {static_cast<Index>(base), static_cast<Index>(base | 1 << b),
                    static_cast<Index>(base | 1 << b | 1 << c), static_cast<Index>(base | 1 << c)};
      if (side == 0) std::swap(q[1], q[3]);
      mesh.triangles.push_back({q[0], q[1], q[2]});
      mesh.triangles.push_back({q[0], q[2], q[3]});
    }
  }
  return mesh;
}

}  // namespace

TriangleMesh tessellate(const Shape& shape, int segments) {
  validate_shape(shape);
  if (segments < 3) {
    throw InvalidArgument(fmt::format("cannot tessellate a {} with {} segments: a circle needs at least 3",
                                      shape_name(shape), segments));
  }
  return std::visit(
      Overloaded{
          [&](const Box& s) { return box(s.size); },
          [&](const Sphere& s) {
            TriangleMesh m = unit_sphere(segments);
            for (Vec3& v : m.vertices) v *= s.radius;
            return m;
          },
          [&](const Ellipsoid& s) {
            TriangleMesh m = unit_sphere(segments);
            for (Vec3& v : m.vertices) v = v.cwiseProduct(s.semi_axes);
            return m;
          },
          [&](const Cylinder& s) {
            const double r = s.radius, h = 0.5 * s.length;
            return revolve({{0.0, -h}, {r, -h}, {r, h}, {0.0, h}}, segments, false);
          },
          [&](const Capsule& s) {
            const double r = s.radius, h = 0.5 * s.length;
            const int steps = std::max(1, segments / 4);
            std::vector<ProfilePoint> profile;
            arc(profile, r, -h, -pi / 2, 0.0, steps, true);
            arc(profile, r, h, 0.0, pi / 2, steps, true);
            return revolve(profile, segments, false);
          },
          [&](const Cone& s) {
            return revolve({{0.0, 0.0}, {s.radius, 0.0}, {0.0, s.height}}, segments, false);
          },
          [&](const Torus& s) {
            // The tube's circle, counter-clockwise in the (ρ, z) half-plane from the outer equator:
            // there the profile runs towards +z, as on a sphere's equator, so revolve's winding holds.
            std::vector<ProfilePoint> profile;
            for (int i = 0; i < segments; ++i) {
              const double theta = 2.0 * pi * i / segments;
              profile.push_back(
                  {s.major_radius + s.minor_radius * std::cos(theta), s.minor_radius * std::sin(theta)});
            }
            return revolve(profile, segments, true);
          },
      },
      shape);
}

}  // namespace tumble
