// Closed-form torque-free motion of bodies with two equal moments (Landau & Lifshitz, Mechanics, §33);
// the classes and the formulas are in euler_poinsot_flows.hpp (SteadyRotation is all there).
#include <cmath>

#include "euler_poinsot_flows.hpp"
#include "tumble/math/quaternion.hpp"

namespace tumble::detail {

AxisymmetricRotation::AxisymmetricRotation(const Vec3& Lambda, int axis, const Quat& q0, const Vec3& omega_b0)
    : q0_(q0), omega_b0_(omega_b0), e_s_(Vec3::Unit(axis)) {
  const double I_s = Lambda(axis);
  const double I_t = 0.5 * (Lambda((axis + 1) % 3) + Lambda((axis + 2) % 3));
  Vec3 Lambda_eff = Vec3::Constant(I_t);
  Lambda_eff(axis) = I_s;
  n_ = (I_s - I_t) * omega_b0(axis) / I_t;
  precession_w_ = (q0 * Vec3(Lambda_eff.cwiseProduct(omega_b0))) / I_t;  // Ω_p L̂_w = L_w / I_t
}

Vec3 AxisymmetricRotation::omega_b(double t) const { return quat_exp<double>(n_ * t * e_s_) * omega_b0_; }

Quat AxisymmetricRotation::q(double t) const {
  return (quat_exp<double>(t * precession_w_) * q0_ * quat_exp<double>(-n_ * t * e_s_)).normalized();
}

}  // namespace tumble::detail
