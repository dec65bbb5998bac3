#pragma once
// Orbits: a state from classical orbital elements, and the orbit frame of spacecraft attitude, LVLH
// (local vertical, local horizontal), from a body's position r and velocity v relative to the central
// body it orbits:
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
#include <utility>

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

/// Classical orbital elements of an ellipse about a central body.
struct OrbitalElements {
  double a = 0.0;     ///< semi-major axis (m), > 0
  double e = 0.0;     ///< eccentricity, 0 ≤ e < 1
  double i = 0.0;     ///< inclination (rad), 0 … π
  double raan = 0.0;  ///< right ascension of the ascending node Ω (rad)
  double argp = 0.0;  ///< argument of periapsis ω (rad)
  double nu = 0.0;    ///< true anomaly ν (rad)
};

/// Position and velocity relative to the central body (μ = GM, m³/s²): in the perifocal frame, with
/// p = a(1 − e²), r = p/(1 + e cos ν) (cos ν, sin ν, 0) and v = √(μ/p) (−sin ν, e + cos ν, 0), turned
/// into the world by Rz(Ω) Rx(i) Rz(ω) (Vallado, Fundamentals of Astrodynamics, algorithm 10).
[[nodiscard]] inline std::pair<Vec3, Vec3> orbit_state(double mu, const OrbitalElements& k) {
  const double p = k.a * (1.0 - k.e * k.e);
  const double c = std::cos(k.nu), s = std::sin(k.nu);
  const Vec3 r_pf = p / (1.0 + k.e * c) * Vec3(c, s, 0.0);
  const Vec3 v_pf = std::sqrt(mu / p) * Vec3(-s, k.e + c, 0.0);
  const Mat3 Q = (Eigen::AngleAxisd(k.raan, Vec3::UnitZ()) * Eigen::AngleAxisd(k.i, Vec3::UnitX()) *
                  Eigen::AngleAxisd(k.argp, Vec3::UnitZ()))
                     .toRotationMatrix();
  return {Q * r_pf, Q * v_pf};
}

}  // namespace tumble
