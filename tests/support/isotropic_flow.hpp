#pragma once
// The free isotropic body's flow differentiated in closed form, in the tangent space of
// dynamics/tangent.hpp: ω stays ω₀, R(t) = exp([ω₀]× t) R₀, p(t) = p₀ + v₀ t (centre of mass at the
// reference origin), so
//   ∂p/∂p₀ = I, ∂p/∂v₀ = t I, ∂v/∂v₀ = I, ∂ω/∂ω₀ = I,
//   ∂θ/∂θ₀ = exp([ω₀]× t) (a turn before the flow is the same turn carried along by it),
//   ∂θ/∂ω₀ = t J_l(ω₀ t), J_l(φ) = I + (1 − cos|φ|)/|φ|² [φ]× + (|φ| − sin|φ|)/|φ|³ [φ]×²,
// and zero elsewhere. The reference both ways of computing the state transition matrix are checked with.
#include <cmath>

#include <Eigen/Geometry>

#include "tumble/forces/model.hpp"
#include "tumble/math/types.hpp"

namespace tumble::test {

/// The free isotropic body both are checked on: a ball (Λ = 0.4 kg·m² each) spinning at kBallOmega0
/// while it drifts, its centre of mass at its reference origin.
inline const Vec3 kBallOmega0(0.7, -1.1, 0.5);
inline Model ball_model() {
  Model model;
  model.add_body(RigidBody::from_principal_moments(2.0, Vec3(0.4, 0.4, 0.4), "ball"));
  return model;
}
inline SystemState ball_state() {
  SystemState s0;
  s0.bodies.push_back(BodyState{Vec3(0.1, 0.2, 0.3), Quat(Eigen::AngleAxisd(0.4, Vec3(1, 2, 2).normalized())),
                                Vec3(1.0, -0.5, 0.2), kBallOmega0});
  return s0;
}

inline Eigen::Matrix<double, 12, 12> isotropic_flow_stm(const Vec3& omega0, double t) {
  Eigen::Matrix<double, 12, 12> M = Eigen::Matrix<double, 12, 12>::Identity();
  M.block<3, 3>(0, 6) = t * Mat3::Identity();
  const Vec3 phi = omega0 * t;
  const double a = phi.norm();
  const Mat3 K = skew(phi);
  M.block<3, 3>(3, 3) = Eigen::AngleAxisd(a, phi / a).toRotationMatrix();
  M.block<3, 3>(3, 9) =
      t * (Mat3::Identity() + (1 - std::cos(a)) / (a * a) * K + (a - std::sin(a)) / (a * a * a) * K * K);
  return M;
}

}  // namespace tumble::test
