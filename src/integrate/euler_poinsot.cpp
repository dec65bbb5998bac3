// EulerPoinsot: validates the data, sorts the principal axes, decides the regime and picks the
// closed-form flow (euler_poinsot_symmetric.cpp, euler_poinsot_triaxial.cpp).
#include "tumble/integrate/euler_poinsot.hpp"

#include <array>
#include <cmath>
#include <new>
#include <sstream>
#include <type_traits>
#include <utility>

#include "euler_poinsot_flows.hpp"
#include "tumble/debug_assert.hpp"
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

}  // namespace

namespace detail {

namespace {
/// 2^−⌊log₂ x⌋: multiplying by it is exact and brings x into [1, 2).
double power_of_two_scale(double x) { return std::ldexp(1.0, -std::ilogb(x)); }
}  // namespace

AxesSort sort_axes(const Vec3& Lambda, const Vec3& omega_b0) {
  AxesSort s;
  // The axis indices in ascending order of Lambda, equal moments kept in their given order (what
  // std::stable_sort gives, without its temporary buffer on the heap): an element moves left only past
  // strictly larger ones.
  s.order = {0, 1, 2};
  for (int i = 1; i < 3; ++i) {
    for (int k = i; k > 0 && Lambda(s.order[k]) < Lambda(s.order[k - 1]); --k)
      std::swap(s.order[k], s.order[k - 1]);
  }
  s.P.setZero();
  for (int k = 0; k < 3; ++k) s.P(k, s.order[k]) = 1.0;
  if (s.P.determinant() < 0) s.P.row(1) *= -1.0;
  s.I_scale = power_of_two_scale(Lambda.maxCoeff());
  s.omega_scale = 1.0 / power_of_two_scale(omega_b0.cwiseAbs().maxCoeff());
  return s;
}

}  // namespace detail

const detail::FreeRotation& EulerPoinsot::flow() const {
  // The flow lives in flow_ (no heap): it must fit, and since ~EulerPoinsot() is trivial, need no
  // destructor.
  static_assert(sizeof(detail::FreeRotation) <= kFlowBytes,
                "EulerPoinsot::kFlowBytes is too small for detail::FreeRotation: raise it");
  static_assert(alignof(detail::FreeRotation) <= alignof(Quat),
                "EulerPoinsot::flow_ is not aligned enough for detail::FreeRotation");
  static_assert(std::is_trivially_destructible_v<detail::FreeRotation>,
                "~EulerPoinsot() = default would not destroy detail::FreeRotation");
  return *std::launder(reinterpret_cast<const detail::FreeRotation*>(flow_));
}
detail::FreeRotation& EulerPoinsot::flow() {
  return *std::launder(reinterpret_cast<detail::FreeRotation*>(flow_));
}

EulerPoinsot::EulerPoinsot(const EulerPoinsot& other)
    : Lambda_(other.Lambda_), R0_(other.R0_), omega_b0_(other.omega_b0_), regime_(other.regime_) {
  ::new (static_cast<void*>(flow_)) detail::FreeRotation(other.flow());
}

EulerPoinsot& EulerPoinsot::operator=(const EulerPoinsot& other) {
  Lambda_ = other.Lambda_;
  R0_ = other.R0_;
  omega_b0_ = other.omega_b0_;
  regime_ = other.regime_;
  flow() = other.flow();
  return *this;
}

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
    throw InvalidArgument("EulerPoinsot: the initial angular velocity " +
                          vec_text(omega_b0.homogeneous(), 3) + " must be finite (rad/s)");
  }
  const Quat q0 = q0_in.normalized();
  R0_ = q0.toRotationMatrix();

  // Builds the flow of kind Flow in flow_, once, as the last step of construction.
  const auto build = [this]<class Flow>(std::in_place_type_t<Flow> kind, auto&&... args) {
    ::new (static_cast<void*>(flow_)) detail::FreeRotation(kind, std::forward<decltype(args)>(args)...);
  };
  using detail::AxisymmetricRotation, detail::SteadyRotation, detail::TriaxialRotation;

  if (omega_b0.isZero(0.0)) {
    regime_ = Regime::rest;
    build(std::in_place_type<SteadyRotation>, q0, omega_b0);
    return;
  }

  // Sort the axes: ω_s = P ω_b with P a signed permutation of determinant +1. Exact power-of-two
  // scalings keep the moments' differences exact and keep the squares of ω away from overflow and
  // underflow; λ and the amplitudes are scaled back by omega_scale.
  const detail::AxesSort sort = detail::sort_axes(Lambda, omega_b0);
  const std::array<int, 3>& order = sort.order;
  detail::SortedBody body;
  body.P = sort.P;
  body.I = sort.I_scale * (body.P.cwiseAbs() * Lambda);
  body.omega_scale = sort.omega_scale;
  body.w = (body.P * omega_b0) / body.omega_scale;

  const double tol = kEqualMomentsTolerance * body.I(2);
  const bool low_pair = body.I(1) - body.I(0) <= tol, high_pair = body.I(2) - body.I(1) <= tol;
  if (low_pair && high_pair) {
    regime_ = Regime::sphere;
    build(std::in_place_type<SteadyRotation>, q0, omega_b0);
  } else if (low_pair || high_pair) {
    regime_ = Regime::axisymmetric;
    const int axis = low_pair ? order[2] : order[0];
    build(std::in_place_type<AxisymmetricRotation>, Lambda, axis, q0, omega_b0);
  } else if (body.w(0) == 0.0 && body.w(2) == 0.0) {
    regime_ = Regime::separatrix;  // steady spin about the intermediate axis (unstable, but exact)
    build(std::in_place_type<SteadyRotation>, q0, omega_b0);
  } else {
    build(std::in_place_type<TriaxialRotation>, body, q0, regime_);  // sets regime_
  }
}

Vec3 EulerPoinsot::omega_b(double t) const { return flow().omega_b(t); }
Vec3 EulerPoinsot::omega_w(double t) const {
  const State s = flow().state(t);
  return s.q * s.omega_b;
}
Quat EulerPoinsot::q(double t) const {
  const Quat q = flow().q(t);
  // The closed form composes unit quaternions: unit to a few ε whatever t.
  TUMBLE_DEBUG_ASSERT(std::abs(q.squaredNorm() - 1.0) < 1e-13,
                      "the exact flow's attitude is a unit quaternion");
  return q;
}
EulerPoinsot::State EulerPoinsot::state(double t) const {
  const State s = flow().state(t);
  TUMBLE_DEBUG_ASSERT(std::abs(s.q.squaredNorm() - 1.0) < 1e-13,
                      "the exact flow's attitude is a unit quaternion");
  return s;
}
double EulerPoinsot::period_omega() const { return flow().period_omega(); }
double EulerPoinsot::flip_interval() const { return flow().flip_interval(); }

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
