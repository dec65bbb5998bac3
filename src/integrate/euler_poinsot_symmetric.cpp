// Closed-form torque-free motion of bodies with equal moments (shared/research/numerics.md §2).
#include <cmath>
#include <limits>
#include <numbers>

#include "euler_poinsot_flows.hpp"
#include "tumble/math/quaternion.hpp"

namespace tumble::detail {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

/// Constant ω_b: Ṙ = R[ω_b]× = [ω_w]×R with ω_w = R₀ω_b fixed, so R(t) = exp(t[ω_w]×) R₀.
class SteadyRotation final : public FreeRotation {
 public:
  SteadyRotation(const Quat& q0, const Vec3& omega_b0) : q0_(q0), omega_b0_(omega_b0), omega_w_(q0 * omega_b0) {}
  Vec3 omega_b(double) const override { return omega_b0_; }
  Quat q(double t) const override { return (quat_exp<double>(t * omega_w_) * q0_).normalized(); }
  double period_omega() const override { return kInf; }
  double flip_interval() const override { return kInf; }

 private:
  Quat q0_;
  Vec3 omega_b0_, omega_w_;
};

/// Transverse moment I_t (twice), symmetry moment I_s about e_s. L_s = I_s ω_s is constant, and
///   ω_b(t) = Rot(e_s, n t) ω_b(0),           n = (I_s − I_t) ω_s / I_t   (body-frame precession),
///   R(t) = Rot(L̂_w, Ω_p t) R₀ Rot(e_s, −n t),  Ω_p = |L| / I_t          (space precession).
class AxisymmetricRotation final : public FreeRotation {
 public:
  AxisymmetricRotation(const Vec3& Lambda, int axis, const Quat& q0, const Vec3& omega_b0)
      : q0_(q0), omega_b0_(omega_b0), e_s_(Vec3::Unit(axis)) {
    const double I_s = Lambda(axis);
    const double I_t = 0.5 * (Lambda((axis + 1) % 3) + Lambda((axis + 2) % 3));
    Vec3 Lambda_eff = Vec3::Constant(I_t);
    Lambda_eff(axis) = I_s;
    n_ = (I_s - I_t) * omega_b0(axis) / I_t;
    precession_w_ = (q0 * Vec3(Lambda_eff.cwiseProduct(omega_b0))) / I_t;  // Ω_p L̂_w = L_w / I_t
  }
  Vec3 omega_b(double t) const override { return quat_exp<double>(n_ * t * e_s_) * omega_b0_; }
  Quat q(double t) const override {
    return (quat_exp<double>(t * precession_w_) * q0_ * quat_exp<double>(-n_ * t * e_s_)).normalized();
  }
  double period_omega() const override { return n_ == 0.0 ? kInf : 2.0 * std::numbers::pi / std::abs(n_); }
  double flip_interval() const override { return n_ == 0.0 ? kInf : std::numbers::pi / std::abs(n_); }

 private:
  Quat q0_;
  Vec3 omega_b0_, e_s_, precession_w_;
  double n_;
};

}  // namespace

std::shared_ptr<const FreeRotation> make_steady_rotation(const Quat& q0, const Vec3& omega_b0) {
  return std::make_shared<SteadyRotation>(q0, omega_b0);
}

std::shared_ptr<const FreeRotation> make_axisymmetric_rotation(const Vec3& Lambda, int axis, const Quat& q0,
                                                               const Vec3& omega_b0) {
  return std::make_shared<AxisymmetricRotation>(Lambda, axis, q0, omega_b0);
}

}  // namespace tumble::detail
