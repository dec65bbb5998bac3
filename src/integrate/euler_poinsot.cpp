// EulerPoinsot: validates the data, sorts the principal axes, decides the regime and picks the
// closed-form flow (euler_poinsot_symmetric.cpp, euler_poinsot_triaxial.cpp).
#include "tumble/integrate/euler_poinsot.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>
#include <sstream>

#include "euler_poinsot_flows.hpp"
#include "tumble/error.hpp"

namespace tumble {
namespace {

std::string vec_text(const Eigen::Vector4d& v, int n) {
  std::ostringstream s;
  s.precision(17);
  s << "(";
  for (int i = 0; i < n; ++i) s << (i ? ", " : "") << v(i);
  s << ")";
  return s.str();
}

/// 2^−⌊log₂ x⌋: multiplying by it is exact and brings x into [1, 2).
double power_of_two_scale(double x) { return std::ldexp(1.0, -std::ilogb(x)); }

}  // namespace

EulerPoinsot::EulerPoinsot(const Vec3& Lambda, const Mat3& R0, const Vec3& omega_b0)
    : EulerPoinsot(Lambda, Quat(R0), omega_b0) {}

EulerPoinsot::EulerPoinsot(const Vec3& Lambda, const Quat& q0_in, const Vec3& omega_b0)
    : Lambda_(Lambda), omega_b0_(omega_b0) {
  if (!(Lambda.allFinite() && Lambda.minCoeff() > 0.0)) {
    throw InvalidArgument("EulerPoinsot: the principal moments " + vec_text(Lambda.homogeneous(), 3) +
                          " must be finite and positive (kg m^2)");
  }
  const double qn = q0_in.norm();
  if (!(std::isfinite(qn) && qn > 0.0)) {
    throw InvalidArgument("EulerPoinsot: the initial orientation (w, x, y, z) = " +
                          vec_text(Eigen::Vector4d(q0_in.w(), q0_in.x(), q0_in.y(), q0_in.z()), 4) +
                          " must be a finite, non-zero quaternion");
  }
  if (!omega_b0.allFinite()) {
    throw InvalidArgument("EulerPoinsot: the initial angular velocity " + vec_text(omega_b0.homogeneous(), 3) +
                          " must be finite (rad/s)");
  }
  const Quat q0 = q0_in.normalized();
  R0_ = q0.toRotationMatrix();

  if (omega_b0.isZero(0.0)) {
    regime_ = Regime::rest;
    flow_ = detail::make_steady_rotation(q0, omega_b0);
    return;
  }

  // Sort the axes: ω_s = P ω_b with P a signed permutation of determinant +1.
  std::array<int, 3> order{0, 1, 2};
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return Lambda(a) < Lambda(b); });
  detail::SortedBody body;
  body.P.setZero();
  for (int k = 0; k < 3; ++k) body.P(k, order[k]) = 1.0;
  if (body.P.determinant() < 0) body.P.row(1) *= -1.0;
  // Exact power-of-two scalings keep the moments' differences exact and keep the squares of ω away
  // from overflow and underflow; λ and the amplitudes are scaled back by omega_scale.
  body.I = power_of_two_scale(Lambda.maxCoeff()) * (body.P.cwiseAbs() * Lambda);
  body.omega_scale = 1.0 / power_of_two_scale(omega_b0.cwiseAbs().maxCoeff());
  body.w = (body.P * omega_b0) / body.omega_scale;

  const double tol = kEqualMomentsTolerance * body.I(2);
  const bool low_pair = body.I(1) - body.I(0) <= tol, high_pair = body.I(2) - body.I(1) <= tol;
  if (low_pair && high_pair) {
    regime_ = Regime::sphere;
    flow_ = detail::make_steady_rotation(q0, omega_b0);
  } else if (low_pair || high_pair) {
    regime_ = Regime::axisymmetric;
    flow_ = detail::make_axisymmetric_rotation(Lambda, low_pair ? order[2] : order[0], q0, omega_b0);
  } else if (body.w(0) == 0.0 && body.w(2) == 0.0) {
    regime_ = Regime::separatrix;  // steady spin about the intermediate axis (unstable, but exact)
    flow_ = detail::make_steady_rotation(q0, omega_b0);
  } else {
    flow_ = detail::make_triaxial_rotation(body, q0, regime_);
  }
}

Vec3 EulerPoinsot::omega_b(double t) const { return flow_->omega_b(t); }
Vec3 EulerPoinsot::omega_w(double t) const { return flow_->q(t) * flow_->omega_b(t); }
Quat EulerPoinsot::q(double t) const { return flow_->q(t); }
double EulerPoinsot::period_omega() const { return flow_->period_omega(); }
double EulerPoinsot::flip_interval() const { return flow_->flip_interval(); }

std::string regime_name(EulerPoinsot::Regime regime) {
  switch (regime) {
    case EulerPoinsot::Regime::rest:
      return "rest";
    case EulerPoinsot::Regime::sphere:
      return "sphere";
    case EulerPoinsot::Regime::axisymmetric:
      return "axisymmetric";
    case EulerPoinsot::Regime::about_minor_axis:
      return "about_minor_axis";
    case EulerPoinsot::Regime::about_major_axis:
      return "about_major_axis";
    case EulerPoinsot::Regime::separatrix:
      return "separatrix";
  }
  return "unknown";
}

}  // namespace tumble
