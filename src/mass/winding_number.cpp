#include "tumble/mass/winding_number.hpp"

#include <cmath>
#include <numbers>

namespace tumble {

double triangle_solid_angle(const Vec3& a, const Vec3& b, const Vec3& c) {
  const double la = a.norm(), lb = b.norm(), lc = c.norm();
  return 2.0 * std::atan2(a.dot(b.cross(c)), la * lb * lc + a.dot(b) * lc + a.dot(c) * lb + b.dot(c) * la);
}

double winding_number(const TriangleMesh& mesh, const Vec3& p) {
  double omega = 0.0;
  for (const auto& f : mesh.triangles)
    omega += triangle_solid_angle(mesh.vertices[f[0]] - p, mesh.vertices[f[1]] - p, mesh.vertices[f[2]] - p);
  return omega / (4.0 * std::numbers::pi);
}

}  // namespace tumble
