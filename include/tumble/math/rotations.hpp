#pragma once
#include <optional>
// Other descriptions of a rotation R (a unit quaternion q, w first, in tumble): Euler angles in two
// named conventions, axis–angle and modified Rodrigues parameters. Used for output columns and for orientations given in scenes.
//
//  - ZYX (yaw–pitch–roll, aerospace): R = Rz(yaw) Ry(pitch) Rx(roll), angles (yaw, pitch, roll) with
//    yaw, roll ∈ (−π, π] and pitch ∈ [−π/2, π/2]. At pitch = ±π/2 (gimbal lock) only yaw ∓ roll is
//    defined: roll is set to 0. Just short of the lock the angles still rebuild R to rounding.
//  - ZXZ (3-1-3, classical mechanics and orbits): R = Rz(φ) Rx(θ) Rz(ψ), angles (φ, θ, ψ) with
//    φ, ψ ∈ (−π, π] and θ ∈ [0, π]. At θ = 0 or π only φ ± ψ is defined: ψ is set to 0. Just short of
//    it, as of ZYX's lock, the angles still rebuild R to rounding.
//  - Axis–angle: R = exp(angle [axis]×), angle ∈ [0, π], |axis| = 1; at angle = 0 the axis is
//    arbitrary and given as (1, 0, 0).
//  - Modified Rodrigues parameters (spacecraft attitude): σ = tan(angle/4) axis, |σ| ≤ 1 (mrp()).
//  - Classical Rodrigues parameters: g = tan(angle/2) axis, infinite at a half turn (crp()).
// Rotations are active and map the rotated frame's coordinates to the fixed frame's: x_w = R x.
#include <algorithm>
#include <cmath>

#include "tumble/math/types.hpp"

namespace tumble {

/// Rotations about one axis: Rx(a), Ry(a), Rz(a).
inline Mat3 rotation_x(double a) { return Eigen::AngleAxisd(a, Vec3::UnitX()).toRotationMatrix(); }
inline Mat3 rotation_y(double a) { return Eigen::AngleAxisd(a, Vec3::UnitY()).toRotationMatrix(); }
inline Mat3 rotation_z(double a) { return Eigen::AngleAxisd(a, Vec3::UnitZ()).toRotationMatrix(); }

/// (yaw, pitch, roll) with R = Rz(yaw) Ry(pitch) Rx(roll).
[[nodiscard]] inline Vec3 euler_zyx(const Mat3& R) {
  // Third row: (−sin pitch, cos pitch sin roll, cos pitch cos roll). pitch from atan2 keeps its accuracy
  // near ±π/2, where asin(−R(2,0)) would lose half the digits.
  const double c = std::hypot(R(2, 1), R(2, 2));
  const double pitch = std::atan2(-R(2, 0), c);
  // Near the lock roll comes from entries of size cos pitch, each off by ~ε, so roll alone is off by
  // ~ε / cos pitch. Yaw is therefore taken from entries of size 1 *given* that roll, so that yaw ∓ roll,
  // on which alone the rotation depends there, is right to rounding:
  //   sin r R(0,2) − cos r R(0,1) = sin yaw,   cos r R(1,1) − sin r R(1,2) = cos yaw.
  // At the lock itself (c = 0) only yaw ∓ roll is defined: roll is set to 0.
  const double roll = c == 0.0 ? 0.0 : std::atan2(R(2, 1), R(2, 2));
  const double sr = std::sin(roll), cr = std::cos(roll);
  const double yaw = std::atan2(sr * R(0, 2) - cr * R(0, 1), cr * R(1, 1) - sr * R(1, 2));
  return {yaw, pitch, roll};
}

[[nodiscard]] inline Mat3 from_euler_zyx(const Vec3& yaw_pitch_roll) {
  return rotation_z(yaw_pitch_roll.x()) * rotation_y(yaw_pitch_roll.y()) * rotation_x(yaw_pitch_roll.z());
}

/// (φ, θ, ψ) with R = Rz(φ) Rx(θ) Rz(ψ).
[[nodiscard]] inline Vec3 euler_zxz(const Mat3& R) {
  // Third row (sin θ sin ψ, sin θ cos ψ, cos θ). As in euler_zyx, ψ comes from entries of size sin θ
  // and φ from entries of size 1 given ψ, so that near θ = 0 or π the rotation is rebuilt to rounding:
  //   cos ψ R(1,0) − sin ψ R(1,1) = sin φ,   cos ψ R(0,0) − sin ψ R(0,1) = cos φ.
  // At θ = 0 or π exactly (s = 0) only φ ± ψ is defined: ψ is set to 0.
  const double s = std::hypot(R(2, 0), R(2, 1));
  const double theta = std::atan2(s, R(2, 2));
  const double psi = s == 0.0 ? 0.0 : std::atan2(R(2, 0), R(2, 1));
  const double sp = std::sin(psi), cp = std::cos(psi);
  const double phi = std::atan2(cp * R(1, 0) - sp * R(1, 1), cp * R(0, 0) - sp * R(0, 1));
  return {phi, theta, psi};
}

[[nodiscard]] inline Mat3 from_euler_zxz(const Vec3& phi_theta_psi) {
  return rotation_z(phi_theta_psi.x()) * rotation_x(phi_theta_psi.y()) * rotation_z(phi_theta_psi.z());
}

/// Unit axis and angle ∈ [0, π] of the rotation q (either sign of q).
struct AxisAngle {
  Vec3 axis = Vec3::UnitX();
  double angle = 0.0;  ///< rad
};

[[nodiscard]] inline AxisAngle axis_angle(const Quat& q) {
  // q = ±(cos(angle/2), sin(angle/2) axis): the sign with w ≥ 0 gives angle ≤ π; atan2 of the vector
  // part's norm and w keeps small angles accurate (acos(w) would not).
  const double sign = q.w() < 0 ? -1.0 : 1.0;
  const Vec3 u = sign * q.vec();
  const double s = u.norm();
  if (s == 0.0) return {};
  return {u / s, 2.0 * std::atan2(s, sign * q.w())};
}

/// Modified Rodrigues parameters σ = q_v / (1 + q_w) = tan(angle/4) axis, of the sign of q with
/// q_w ≥ 0: the principal set, |σ| ≤ 1 (= 1 at angle π). As a rotation turns through π its σ jumps
/// from the unit sphere to the antipode: it switches to the shadow set σˢ = −σ/|σ|² (the same rotation,
/// of −q) where |σ| would exceed 1 (Schaub & Junkins, Analytical Mechanics of Space Systems, §3.8).
/// 1 + |q_w| ≥ 1: no cancellation anywhere.
[[nodiscard]] inline Vec3 mrp(const Quat& q) {
  const double sign = q.w() < 0 ? -1.0 : 1.0;
  return sign * q.vec() / (1.0 + sign * q.w());
}

/// Classical Rodrigues parameters (Gibbs vector) g = q_v / q_w = tan(angle/2) axis: the same for q and
/// −q, infinite at a half turn (q_w = 0), where nullopt. Near it they grow without bound, which is why
/// spacecraft software prefers the MRPs above.
[[nodiscard]] inline std::optional<Vec3> crp(const Quat& q) {
  if (q.w() == 0.0) return std::nullopt;
  return Vec3(q.vec() / q.w());
}

/// The rotation σ describes, for any σ (a set and its shadow give the same rotation):
/// q = ((1 − |σ|²), 2σ) / (1 + |σ|²), unit by construction.
[[nodiscard]] inline Quat from_mrp(const Vec3& sigma) {
  const double s2 = sigma.squaredNorm(), d = 1.0 + s2;
  const Vec3 v = 2.0 * sigma / d;
  return Quat((1.0 - s2) / d, v.x(), v.y(), v.z());
}

}  // namespace tumble
