// The torque-free flow on dual numbers: closed form where it is differentiable, Taylor series elsewhere
// (free_flow_tangent.hpp says which and why).
#include "free_flow_tangent.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "free_body_taylor.hpp"
#include "triaxial_setup.hpp"

namespace tumble {
namespace detail {

using T = TangentScalar;

// The special functions of triaxial_setup.hpp on dual numbers. Their values agree with the double ones
// to rounding (the flow's values are EulerPoinsot's in the end); what matters is their derivatives.

void elliptic_constants(const T& m, const T& m1, const T& n, JacobiConstants<T>& J, PiConstants<T>& P) {
  // The AGM of 1 and k′ as JacobiElliptic runs it (the same number of steps), and K = π/(2 a_N), its
  // limit, which carries K's derivative with respect to m.
  J = JacobiConstants<T>{};
  T a(1.0), b = sqrt(m1), c = sqrt(m);
  const double eps = std::numeric_limits<double>::epsilon();
  while (c.v > eps * a.v && J.steps < kMaxLandenSteps) {
    const T a_next = T(0.5) * (a + b);
    c = c * c / (T(4.0) * a_next);
    b = sqrt(a * b);
    a = a_next;
    J.ratio[J.steps++] = c / a;
  }
  J.a_N = a;
  J.K = T(0.5 * std::numbers::pi) / a;
  J.inv_2K = T(0.5) / J.K;
  J.m1 = m1;
  J.k1 = sqrt(m1);
  // Π(n | m) by Bulirsch's transformation on dual numbers; the rest as EllipticPi forms it.
  P = PiConstants<T>{};
  P.n = n;
  P.complete = bulirsch_Pi_complete<T>(n, m1, T(std::sqrt(eps)));
  P.rj_max_steps = carlson_rj_steps(-n.v, m1.v);
  P.rj_steps = T(P.rj_max_steps);
  const T bm = m - n;
  if (bm.v > 0.0) {
    P.n_reflected = bm / (T(1.0) - n);
    P.c_linear = m / bm;
    P.c_Pi = -n * m1 / (bm * (T(1.0) - n));
  } else {
    P.c_linear = T(1.0);
  }
}

T elliptic_first_kind(const JacobiConstants<T>& J, const T& s, const T& c, const T& d, const T&) {
  // u = F(φ | m) is the u with sn(u | m) = s, cn(u | m) = c. Its value is the accurate double one; its
  // derivative by implicit differentiation (one Newton step on dual numbers): sn's derivative at fixed u
  // is that with respect to m (through J), and d sn/du = cn dn, d cn/du = −sn dn, so
  //   du = (ds − ∂sn) / (cn dn),  or  du = −(dc − ∂cn) / (sn dn),
  // whichever divides by the larger of |cn|, |sn| (dn ≥ k′ > 0). F depends on c through c² (the caller
  // reflects φ beyond π/2): its cn is |c|.
  const double u = elliptic_Pi_incomplete(0.0, s.v, c.v, d.v);
  const SnCnDn<T> f = jacobi_sn_cn_dn<T>(J, landen_point<T>(J, T(u)));
  const bool by_sn = std::abs(c.v) >= std::abs(s.v);
  const T step = by_sn ? (s - f.sn) / (f.cn * f.dn) : (f.cn - abs(c)) / (f.sn * f.dn);
  T r(u);
  for (int j = 0; j < kTangentDirections; ++j) r.d[j] = step.d[j];
  return r;
}

}  // namespace detail

namespace {

using T = TangentScalar;

Vec3 value_vec(const Vec3T<T>& v) { return {v(0).v, v(1).v, v(2).v}; }

/// The Taylor series' steps: |ω| max(1, |a|) per step at most this (a = the coefficients of Euler's
/// equation, ω̇ᵢ = aᵢ ω_j ω_k), and enough terms that the next would be below ε² of the sum.
constexpr double kTaylorStepRatio = 0.125;

detail::FlowState<T> taylor_flow(const Vec3T<T>& Lambda, const QuatT<T>& q0, const Vec3T<T>& omega_b0,
                                 double tau) {
  const FreeBodyTaylorT<T> probe({Lambda(0), Lambda(1), Lambda(2)}, 1);
  double a_max = 1.0;
  for (const T& a : probe.a()) a_max = std::max(a_max, std::abs(a.v));
  const double rate = std::abs(tau) * value_vec(omega_b0).norm() * a_max;
  const long steps = std::max(1L, static_cast<long>(std::ceil(rate / kTaylorStepRatio)));
  const double ratio = rate / static_cast<double>(steps);
  // ratioᴾ ≤ 1e-32 (ε²): P = 32 ln 10 / ln(1/ratio) terms, at least 2.
  const int order = ratio > 0.0
                        ? std::clamp(static_cast<int>(std::ceil(32.0 * std::log(10.0) / -std::log(ratio))), 2,
                                     FreeBodyTaylorT<T>::kMaxOrder)
                        : 1;
  const FreeBodyTaylorT<T> taylor({Lambda(0), Lambda(1), Lambda(2)}, order);
  FreeBodyStateT<T> s{{omega_b0(0), omega_b0(1), omega_b0(2)}, {q0.w(), q0.x(), q0.y(), q0.z()}};
  const T h(tau / static_cast<double>(steps));
  for (long k = 0; k < steps; ++k) s = taylor.step(s, h);
  return {normalized<T>(QuatT<T>(s.q[0], s.q[1], s.q[2], s.q[3])), Vec3T<T>(s.w[0], s.w[1], s.w[2])};
}

}  // namespace

FreeFlowTangent::FreeFlowTangent(const Vec3T<T>& Lambda, const QuatT<T>& q0, const Vec3T<T>& omega_b0,
                                 Method method)
    : values_(value_vec(Lambda), Quat(q0.w().v, q0.x().v, q0.y().v, q0.z().v), value_vec(omega_b0)),
      Lambda_(Lambda),
      omega_b0_(omega_b0),
      q0_(q0) {
  using Regime = EulerPoinsot::Regime;
  const Regime regime = values_.regime();
  if (method == Method::taylor_series) return;
  if (regime != Regime::about_major_axis && regime != Regime::about_minor_axis) return;
  // The body in sorted, scaled axes as EulerPoinsot puts it (exact scalings), on dual numbers.
  const detail::AxesSort sort = detail::sort_axes(value_vec(Lambda), value_vec(omega_b0));
  const Mat3T<T> P = sort.P.cast<T>();
  const detail::SortedBodyT<T> body{T(sort.I_scale) * (sort.P.cwiseAbs().cast<T>() * Lambda),
                                    (P * omega_b0) / T(sort.omega_scale), sort.P, sort.omega_scale};
  detail::TriaxialConstants<T> k;
  const detail::TriaxialParts<T> parts = detail::triaxial_amplitudes<T>(body, k);
  // A spin about the pole (m = 0) or the separatrix (m₁ = 0): square roots at 0, no derivative here.
  if (!(parts.m.v > 0.0 && parts.m1.v > 0.0)) return;
  SnCnDn<T> f0;
  detail::triaxial_phase<T>(parts, k, f0);
  detail::triaxial_frame<T>(parts, q0, f0, k, sort.P);
  k_ = k;
}

detail::FlowState<T> FreeFlowTangent::at(double tau) const {
  detail::FlowState<T> s = k_ ? detail::triaxial_state<T>(*k_, T(tau))
                              : taylor_flow(Lambda_, q0_, omega_b0_, tau);
  set_values(s, values_.state(tau));
  return s;
}

void set_values(detail::FlowState<TangentScalar>& s, const EulerPoinsot::State& v) {
  // q and −q are one attitude; the Taylor series follows q continuously from q₀, where the closed form
  // may give −q: the derivatives are taken along the sign of the values.
  double dot = 0.0;
  for (int k = 0; k < 4; ++k) dot += s.q.coeffs()(k).v * v.q.coeffs()(k);
  if (dot < 0.0) s.q.coeffs() = -s.q.coeffs();
  for (int k = 0; k < 4; ++k) s.q.coeffs()(k).v = v.q.coeffs()(k);
  for (int k = 0; k < 3; ++k) s.omega_b(k).v = v.omega_b(k);
}

}  // namespace tumble
