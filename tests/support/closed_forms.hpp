#pragma once
// Closed-form solutions used as references by the dynamics tests.
#include <boost/math/special_functions/ellint_1.hpp>
#include <cmath>

#include "tumble/math/quaternion.hpp"

namespace tumble::test {

/// Torque-free axisymmetric body, transverse moment I_t (axes x, y of {b}) and symmetry moment I_s
/// (axis z of {b}). ω_b cones about e_z at the body-frame rate n = (I_s − I_t) ω_z / I_t, and
/// R(t) = Rot(L̂, Ω_p t) R₀ Rot(e_z, −n t) with Ω_p = |L| / I_t (Landau & Lifshitz §33).
struct AxisymmetricTop {
  double I_t, I_s;
  Mat3 R0;
  Vec3 omega_b0;

  double n() const { return (I_s - I_t) * omega_b0.z() / I_t; }
  Vec3 L_w() const { return R0 * Vec3(I_t * omega_b0.x(), I_t * omega_b0.y(), I_s * omega_b0.z()); }
  Vec3 omega_b(double t) const { return Eigen::AngleAxisd(n() * t, Vec3::UnitZ()) * omega_b0; }
  Mat3 R(double t) const {
    const Vec3 L = L_w();
    return Eigen::AngleAxisd(L.norm() / I_t * t, L.normalized()).toRotationMatrix() * R0 *
           Eigen::AngleAxisd(-n() * t, Vec3::UnitZ()).toRotationMatrix();
  }
};

/// The time between successive flips of a body spinning near its intermediate axis (the zeros of
/// ω₂ ∝ sn(λt)): 2K(m)/λ, in the regime D = L²/2E < I₂ (Landau & Lifshitz §37, with
/// I₁ < I₂ < I₃). The differences 2E I_j − L² = Σ Iᵢ(I_j − Iᵢ)ωᵢ² are formed from the components, which
/// avoids the cancellation of subtracting the large invariants.
inline double intermediate_axis_flip_interval(const Vec3& I, const Vec3& w) {
  auto diff = [&](int j) {  // 2E I_j − L²
    double s = 0;
    for (int i = 0; i < 3; ++i) s += I(i) * (I(j) - I(i)) * w(i) * w(i);
    return s;
  };
  const double a3 = diff(2);   // 2E I₃ − L² > 0
  const double a1 = -diff(0);  // L² − 2E I₁ > 0
  const double lambda = std::sqrt((I(1) - I(0)) * a3 / (I(0) * I(1) * I(2)));
  const double m = (I(2) - I(1)) * a1 / ((I(1) - I(0)) * a3);
  return 2.0 * boost::math::ellint_1(std::sqrt(m)) / lambda;
}

}  // namespace tumble::test
