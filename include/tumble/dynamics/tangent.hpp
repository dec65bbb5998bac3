#pragma once
// The tangent space of a body's state, in which sensitivities are stated (issue 25; docs/NOTATION.md,
// "Tangent space"): 12 numbers, all in world axes,
//   δp  the position of the reference frame's origin,
//   δθ  the attitude as a rotation vector: R ← exp([δθ]×) R (a turn about world axes),
//   δv  the velocity of the reference frame's origin,
//   δω  the angular velocity,
// so no quaternion's sign or norm shows in a derivative. perturbed() moves a state along a tangent;
// tangent_between() is its inverse (for |δθ| < π).
#include <Eigen/Core>

#include "tumble/dynamics/state.hpp"
#include "tumble/math/dual.hpp"
#include "tumble/math/quaternion.hpp"

namespace tumble {

using Tangent = Eigen::Matrix<double, 12, 1>;

/// Directions carried by one pass of the sensitivities: a body's 12 tangent directions and its three
/// principal moments (or its mass) fit in one pass; a system whose bodies interact (springs) takes
/// passes of 16 of its columns at a time. 16 doubles are two AVX-512 registers (four AVX2 ones): the
/// derivative loops of a dual number vectorise across directions.
inline constexpr int kTangentDirections = 16;
/// The number type of the sensitivities: a value and its derivatives along kTangentDirections.
using TangentScalar = Dual<double, kTangentDirections>;

/// x moved along δ: p + δp, exp([δθ]×) R, v + δv, ω + δω (the other components held fixed in world axes).
[[nodiscard]] inline ReferenceFrameState perturbed(const ReferenceFrameState& x, const Tangent& delta) {
  ReferenceFrameState y;
  y.position = x.position + delta.segment<3>(0);
  y.orientation = (quat_exp<double>(delta.segment<3>(3)) * x.orientation).normalized();
  y.velocity = x.velocity + delta.segment<3>(6);
  y.omega_w = x.omega_w + delta.segment<3>(9);
  return y;
}

/// The tangent that takes a to b: (p_b − p_a, vee(log(R_b R_aᵀ)), v_b − v_a, ω_b − ω_a).
[[nodiscard]] inline Tangent tangent_between(const ReferenceFrameState& a, const ReferenceFrameState& b) {
  Tangent delta;
  delta.segment<3>(0) = b.position - a.position;
  delta.segment<3>(3) = quat_log(b.orientation * a.orientation.conjugate());
  delta.segment<3>(6) = b.velocity - a.velocity;
  delta.segment<3>(9) = b.omega_w - a.omega_w;
  return delta;
}

}  // namespace tumble
