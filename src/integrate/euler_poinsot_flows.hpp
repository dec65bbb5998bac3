#pragma once
// The closed-form flows behind EulerPoinsot, one per kind of body (internal to the library). They are
// plain values: EulerPoinsot holds one, as a FreeRotation (a std::variant of the three), in a buffer of
// its own, so that constructing, copying and evaluating it never allocates.
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <type_traits>
#include <utility>
#include <variant>

#include "tumble/integrate/euler_poinsot.hpp"
#include "tumble/integrate/jacobi_elliptic.hpp"
#include "tumble/math/quaternion.hpp"

namespace tumble::detail {

inline constexpr double kInf = std::numeric_limits<double>::infinity();

// ---- Equal moments (euler_poinsot_symmetric.cpp) ----

/// Constant ω_b (rest, sphere, spin about a principal axis that stays one): Ṙ = R[ω_b]× = [ω_w]×R with
/// ω_w = R₀ω_b fixed, so R(t) = exp(t[ω_w]×) R₀ = Rot(ω_w, |ω|t) R₀.
class SteadyRotation {
 public:
  SteadyRotation(const Quat& q0, const Vec3& omega_b0)
      : q0_(q0), omega_b0_(omega_b0), omega_w_(q0 * omega_b0) {}
  Vec3 omega_b(double) const { return omega_b0_; }
  Quat q(double t) const { return (quat_exp<double>(t * omega_w_) * q0_).normalized(); }
  EulerPoinsot::State state(double t) const { return {q(t), omega_b0_}; }
  double period_omega() const { return kInf; }
  double flip_interval() const { return kInf; }

 private:
  Quat q0_;
  Vec3 omega_b0_, omega_w_;
};

/// Two equal moments: regular precession about L_w. Transverse moment I_t (twice), symmetry moment I_s
/// about e_s. L_s = I_s ω_s is constant, and
///   ω_b(t) = Rot(e_s, n t) ω_b(0),           n = (I_s − I_t) ω_s / I_t   (body-frame precession),
///   R(t) = Rot(L̂_w, Ω_p t) R₀ Rot(e_s, −n t),  Ω_p = |L| / I_t          (space precession).
class AxisymmetricRotation {
 public:
  /// `axis` is the index (in the caller's axes) of the distinct moment; the equal pair is replaced by
  /// its mean.
  AxisymmetricRotation(const Vec3& Lambda, int axis, const Quat& q0, const Vec3& omega_b0);
  Vec3 omega_b(double t) const;
  Quat q(double t) const;
  EulerPoinsot::State state(double t) const { return {q(t), omega_b(t)}; }
  double period_omega() const { return n_ == 0.0 ? kInf : 2.0 * std::numbers::pi / std::abs(n_); }
  double flip_interval() const { return n_ == 0.0 ? kInf : std::numbers::pi / std::abs(n_); }

 private:
  Quat q0_;
  Vec3 omega_b0_, e_s_, precession_w_;
  double n_;
};

// ---- Three distinct moments (euler_poinsot_triaxial.cpp) ----

/// The body in sorted principal axes: I₁ < I₂ < I₃ (all three distinct), ω_s = P ω_b with P a signed
/// permutation (det P = +1). I and ω_s may be scaled by powers of two (exactly): I by any factor, ω_s
/// by 1/omega_scale, so the physical angular velocity is omega_scale · w. On double, or on dual numbers
/// for the flow's derivatives (triaxial_setup.hpp).
template <class T>
struct SortedBodyT {
  Vec3T<T> I;
  Vec3T<T> w;
  Mat3 P;
  double omega_scale = 1.0;
};
using SortedBody = SortedBodyT<double>;

/// How a body is put in sorted axes: ω_s = P ω_b with the moments ascending (equal ones in their given
/// order) and det P = +1; the moments are scaled by I_scale and ω by 1/omega_scale, exact powers of two.
struct AxesSort {
  std::array<int, 3> order;  ///< the axes' indices, ascending moments
  Mat3 P;
  double I_scale = 1.0, omega_scale = 1.0;
};
AxesSort sort_axes(const Vec3& Lambda, const Vec3& omega_b0);

/// The constants of a triaxial flow off the separatrix: everything its evaluation at a time t needs.
/// One lane per body for a pack (the batched splitting drift keeps them as columns).
template <class T>
struct TriaxialConstants {
  JacobiConstants<T> jacobi;                // sn, cn, dn of parameter m
  PiConstants<T> pi;                        // Π(−N; am u | m)
  T lambda = T(0), u0 = T(0);               // u = λt + u₀ (λ in rad/s)
  T pole = T(3);                            // the axis the polhode circles: 3 or 1
  Vec3T<T> A;                               // signed amplitudes σ·A (rad/s)
  T h1 = T(0), h2 = T(0);                   // shape of the transverse momentum
  T rho = T(0), c = T(0);                   // |μ_transverse| = ρ |T|, μ₃ = c dn
  T kappa = T(0), rate = T(0), Pi0 = T(0);  // φ(t) = rate·t + κ (Π(u) − Π₀)
  Mat3T<T> P;                               // ω_s = P ω_b
  QuatT<T> G, CP;                           // R = G · Rz(φ) Rx(θ) Rz(ψ) · C P
};

/// Calls f(value) on every constant of k in one fixed order, with the first `ratios` Landen ratios last
/// (those beyond a flow's own AGM steps must be zero): how columns of flows are written and loaded.
template <class T, class F>
void visit_constants(TriaxialConstants<T>& k, int ratios, F&& f) {
  JacobiConstants<T>& J = k.jacobi;
  PiConstants<T>& P = k.pi;
  for (T* x : {&J.K,     &J.inv_2K,   &J.a_N,      &J.m1,     &J.k1,    &P.n,     &P.n_reflected, &P.c_linear,
               &P.c_Pi,  &P.complete, &P.rj_steps, &k.lambda, &k.u0,    &k.pole,  &k.h1,          &k.h2,
               &k.rho,   &k.c,        &k.kappa,    &k.rate,   &k.Pi0,   &k.G.w(), &k.G.x(),       &k.G.y(),
               &k.G.z(), &k.CP.w(),   &k.CP.x(),   &k.CP.y(), &k.CP.z()}) {
    f(*x);
  }
  for (int r = 0; r < 3; ++r) f(k.A(r));
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) f(k.P(r, c));
  }
  for (int r = 0; r < ratios; ++r) f(J.ratio[r]);
}

/// q(t) and ω_b(t) of a flow of one body (double) or of one body per lane (packs).
template <class T>
struct FlowState {
  QuatT<T> q;
  Vec3T<T> omega_b;
};

/// ω_b = Pᵀ ω_s from sn, cn, dn (pole 3: ω₁ ∝ cn, ω₃ ∝ dn; pole 1: ω₁ ∝ dn, ω₃ ∝ cn). P is a signed
/// permutation: each component is one product, exact.
template <class T>
TUMBLE_INLINE Vec3T<T> triaxial_omega_b(const TriaxialConstants<T>& k, const SnCnDn<T>& f) {
  const auto pole3 = k.pole == T(3);
  const T w1 = k.A(0) * select(pole3, f.cn, f.dn), w2 = k.A(1) * f.sn,
          w3 = k.A(2) * select(pole3, f.dn, f.cn);
  return {k.P(0, 0) * w1 + k.P(1, 0) * w2 + k.P(2, 0) * w3, k.P(0, 1) * w1 + k.P(1, 1) * w2 + k.P(2, 1) * w3,
          k.P(0, 2) * w1 + k.P(1, 2) * w2 + k.P(2, 2) * w3};
}

/// Rz(φ) Rx(θ) Rz(ψ) as a unit quaternion (z-x-z Euler angles), with θ and ψ given by the cosines and
/// sines of their halves. The three factors are multiplied rather than combined into angles (φ ± ψ)/2:
/// φ grows with t, and rounding φ + ψ would perturb the body part Rx(θ)Rz(ψ) (and so L_w) by ε|φ| —
/// 1e-9 rad at t = 1e6 s. Kept apart, the rounding of φ only rotates about the fixed L_w.
template <class T>
TUMBLE_INLINE QuatT<T> quat_zxz(T phi, T cos_half_theta, T sin_half_theta, T cos_half_psi, T sin_half_psi) {
  const auto [sin_half_phi, cos_half_phi] = sincos(T(0.5) * phi);
  const QuatT<T> qz_phi(cos_half_phi, T(0), T(0), sin_half_phi);
  const QuatT<T> qx_theta(cos_half_theta, sin_half_theta, T(0), T(0));
  const QuatT<T> qz_psi(cos_half_psi, T(0), T(0), sin_half_psi);
  return quat_mul<T>(qz_phi, quat_mul<T>(qx_theta, qz_psi));
}

/// The unit quaternion of Rz(φ) Rx(θ) Rz(ψ) for given φ: θ and ψ are the z-x-z angles of the unit body
/// momentum μ = (T₁, T₂, c dn) (in the frame C P), from sn, cn, dn.
template <class T>
TUMBLE_INLINE QuatT<T> triaxial_body_part(const TriaxialConstants<T>& k, T phi, const SnCnDn<T>& f) {
  using std::abs, std::copysign, std::hypot, std::sqrt;
  // Transverse part of μ up to the factor ρ (it is ρ·(h₁ cn, h₂ sn) for pole 3, ρ·(h₁ sn, h₂ cn) for
  // pole 1), so ψ stays defined when ρ = 0 (spin exactly about the pole).
  const auto pole3 = k.pole == T(3);
  const T T1 = k.h1 * select(pole3, f.cn, f.sn), T2 = k.h2 * select(pole3, f.sn, f.cn);
  const T Tn = hypot(T1, T2);  // > 0: sn² + cn² = 1
  // ψ = atan2(T₁, T₂) ∈ [−π, π] and θ = atan2(ρ|T|, c dn) ∈ [0, π/2) (c dn > 0), taken by their half
  // angles without evaluating them: for an angle α with (sin α, cos α) = (y, x)/r,
  //   cos(α/2) = √((r + x)/(2r)),  sin(α/2) = y/√(2r(r + x))                  (x ≥ 0),
  //   sin(α/2) = ±√((r − x)/(2r)), cos(α/2) = |y|/√(2r(r − x)), ± the sign of y  (x < 0),
  // each a sum of non-negative terms (no cancellation); cos(α/2) ≥ 0 and the sign of sin(α/2) is
  // that of y, as with the angle from atan2 (its branch cut included). For ψ the two forms share
  // r ± x = Tn + |T₂| (> 0), so one square root serves and the numerators are chosen per lane. Each
  // angle takes one division (1/w): the flow on packs is bound by the divider.
  const auto upper = T2 >= T(0);
  const T Tn_plus = Tn + abs(T2);  // Tn + T₂ where upper, Tn − T₂ where not
  const T inv_w_psi = T(1) / sqrt(T(2) * Tn * Tn_plus);
  const T c_psi = select(upper, Tn_plus, abs(T1)) * inv_w_psi;
  const T s_psi = select(upper, T1, copysign(Tn_plus, T1)) * inv_w_psi;
  const T y = k.rho * Tn, x = k.c * f.dn, r = hypot(y, x);
  const T inv_w = T(1) / sqrt(T(2) * r * (r + x));
  return quat_zxz<T>(phi, (r + x) * inv_w, y * inv_w, c_psi, s_psi);
}

/// q(t) from sn, cn, dn and Π(−N; am u | m) at u = λt + u₀:
///   φ(t) = |L|t/I_p + κ [Π(−N; am u | m) − Π(−N; am u₀ | m)],  R = G · Rz(φ) Rx(θ) Rz(ψ) · C P.
template <class T>
TUMBLE_INLINE QuatT<T> triaxial_q(const TriaxialConstants<T>& k, T t, const SnCnDn<T>& f, T Pi_u) {
  const T phi = k.rate * t + k.kappa * (Pi_u - k.Pi0);
  return normalized<T>(quat_mul<T>(quat_mul<T>(k.G, triaxial_body_part<T>(k, phi, f)), k.CP));
}

/// The flow at t off the separatrix: one Landen point serves sn, cn, dn and Π.
template <class T>
TUMBLE_INLINE FlowState<T> triaxial_state(const TriaxialConstants<T>& k, T t) {
  const LandenPoint<T> p = landen_point<T>(k.jacobi, k.lambda * t + k.u0);
  const SnCnDn<T> f = jacobi_sn_cn_dn<T>(k.jacobi, p);
  return {triaxial_q<T>(k, t, f, elliptic_pi<T>(k.pi, p)), triaxial_omega_b<T>(k, f)};
}

/// Three distinct moments: the elliptic-function solution (both regimes and the separatrix).
/// Everything is written in the sorted frame {s} (ω_s = P ω_b); the derivation is at the top of
/// euler_poinsot_triaxial.cpp. Off the separatrix it evaluates the templates above on double.
class TriaxialRotation {
 public:
  using Regime = EulerPoinsot::Regime;

  /// Requires w not along the intermediate axis (w₁ or w₃ non-zero). Sets `regime`.
  TriaxialRotation(const SortedBody& b, const Quat& q0, Regime& regime);
  Vec3 omega_b(double t) const {
    if (separatrix_) return state(t).omega_b;
    const LandenPoint<double> p = landen_point<double>(k_.jacobi, k_.lambda * t + k_.u0);
    return triaxial_omega_b<double>(k_, jacobi_sn_cn_dn<double>(k_.jacobi, p));  // no Π: cheaper than q(t)
  }
  Quat q(double t) const { return state(t).q; }
  EulerPoinsot::State state(double t) const {
    if (!separatrix_) {
      const FlowState<double> s = triaxial_state<double>(k_, t);
      return {s.q, s.omega_b};
    }
    // m = 1: sn = tanh u, cn = dn = sech u, and Π(−N; am u | 1) = ∫₀ᵘ du′/(1 + N tanh²u′)
    // = (u + √N atan(√N tanh u))/(1 + N).
    const double u = k_.lambda * t + k_.u0;
    const SnCnDn<double> f = separatrix_sn_cn_dn(u);
    const double rN = std::sqrt(N_);
    const double Pi_u = (u + rN * std::atan(rN * f.sn)) / (1.0 + N_);
    return {triaxial_q<double>(k_, t, f, Pi_u), triaxial_omega_b<double>(k_, f)};
  }
  double period_omega() const { return 4.0 * k_.jacobi.K / k_.lambda; }
  double flip_interval() const { return 2.0 * k_.jacobi.K / k_.lambda; }
  /// The constants of the flow, off the separatrix (the batched splitting drift evaluates them).
  const TriaxialConstants<double>& constants() const { return k_; }
  bool separatrix() const { return separatrix_; }

 private:
  bool separatrix_ = false;
  double N_ = 0.0;
  TriaxialConstants<double> k_;
};

// ---- The three together ----

/// A torque-free motion given in closed form from t = 0: one of the flows above, held by value.
class FreeRotation {
 public:
  /// Builds the flow of kind `Flow` in place from `args` (its constructor's arguments).
  template <class Flow, class... Args>
  explicit FreeRotation(std::in_place_type_t<Flow> kind, Args&&... args)
      : flow_(kind, std::forward<Args>(args)...) {}

  Vec3 omega_b(double t) const {
    return std::visit([t](const auto& f) { return f.omega_b(t); }, flow_);
  }
  Quat q(double t) const {
    return std::visit([t](const auto& f) { return f.q(t); }, flow_);
  }
  EulerPoinsot::State state(double t) const {
    return std::visit([t](const auto& f) { return f.state(t); }, flow_);
  }
  double period_omega() const {
    return std::visit([](const auto& f) { return f.period_omega(); }, flow_);
  }
  double flip_interval() const {
    return std::visit([](const auto& f) { return f.flip_interval(); }, flow_);
  }
  /// The triaxial flow, if this is one (else nullptr).
  const TriaxialRotation* triaxial() const { return std::get_if<TriaxialRotation>(&flow_); }

 private:
  std::variant<SteadyRotation, AxisymmetricRotation, TriaxialRotation> flow_;
};

}  // namespace tumble::detail
