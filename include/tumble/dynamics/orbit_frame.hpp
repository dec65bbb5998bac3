#pragma once
// The orbit frame of spacecraft attitude, LVLH (local vertical, local horizontal), from a body's
// position r and velocity v relative to the central body it orbits:
//   ẑ = −r/|r|                 (nadir: toward the central body),
//   ŷ = −(r × v)/|r × v|       (opposite the orbit normal),
//   x̂ = ŷ × ẑ                  (along v on a circular orbit; completes the right-handed triad).
// Its angular velocity: the axes turn with r̂ about the orbit normal, and the orbit plane itself turns
// when a force acts across it (a = r̈): Ω = (r × v)/|r|² + (|r| (a · n̂)/|r × v|) r̂, n̂ = (r × v)/|r × v|
// (d r̂/dt = Ω × r̂ gives the first term; d n̂/dt = (r × a)_⊥/|r × v| the second). Under central gravity
// alone a ∥ r and Ω = (r × v)/|r|²: what lvlh_angular_velocity() gives (the output fields take no
// acceleration).
#include <cmath>
#include <optional>

#include "tumble/math/quaternion.hpp"

namespace tumble {

/// The rotation LVLH → world (columns x̂, ŷ, ẑ in world axes) at r, v relative to the central body;
/// nullopt where r × v = 0 (no orbit plane: at the centre, at rest, or moving along the radius).
[[nodiscard]] inline std::optional<Quat> lvlh_orientation(const Vec3& r, const Vec3& v) {
  const Vec3 h = r.cross(v);
  const double r_norm = r.norm(), h_norm = h.norm();
  if (!(h_norm > 0.0) || !(r_norm > 0.0) || !std::isfinite(h_norm)) return std::nullopt;
  Mat3 axes;
  axes.col(2) = -r / r_norm;
  axes.col(1) = -h / h_norm;
  axes.col(0) = axes.col(1).cross(axes.col(2));
  return Quat(axes).normalized();
}

/// The LVLH frame's angular velocity in world axes, (r × v)/|r|²: exact while no force acts across the
/// orbit plane (central gravity alone); r ≠ 0.
[[nodiscard]] inline Vec3 lvlh_angular_velocity(const Vec3& r, const Vec3& v) {
  return r.cross(v) / r.squaredNorm();
}

}  // namespace tumble
