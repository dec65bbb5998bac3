#pragma once
// The closed-form flows behind EulerPoinsot, one per kind of body (internal to the library). They are
// plain values: EulerPoinsot holds one, as a FreeRotation (a std::variant of the three), in a buffer of
// its own, so that constructing, copying and evaluating it never allocates.
#include <cmath>
#include <limits>
#include <numbers>
#include <optional>
#include <type_traits>
#include <utility>
#include <variant>

#include "tumble/integrate/euler_poinsot.hpp"
#include "tumble/integrate/jacobi_elliptic.hpp"
#include "tumble/math/quaternion.hpp"

namespace tumble::detail {

inline constexpr double kInf = std::numeric_limits<double>::infinity();

/// Rz(φ) Rx(θ) Rz(ψ) as a unit quaternion (z-x-z Euler angles), with θ and ψ given by the cosines and
/// sines of their halves. The three factors are multiplied rather than combined into angles (φ ± ψ)/2:
/// φ grows with t, and rounding φ + ψ would perturb the body part Rx(θ)Rz(ψ) (and so L_w) by ε|φ| —
/// 1e-9 rad at t = 1e6 s. Kept apart, the rounding of φ only rotates about the fixed L_w.
inline Quat quat_zxz(double phi, double cos_half_theta, double sin_half_theta, double cos_half_psi,
                     double sin_half_psi) {
  const Quat qz_phi(std::cos(0.5 * phi), 0.0, 0.0, std::sin(0.5 * phi));
  const Quat qx_theta(cos_half_theta, sin_half_theta, 0.0, 0.0);
  const Quat qz_psi(cos_half_psi, 0.0, 0.0, sin_half_psi);
  return qz_phi * (qx_theta * qz_psi);
}

// ---- Equal moments (euler_poinsot_symmetric.cpp; shared/research/numerics.md §2) ----

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

// ---- Three distinct moments (euler_poinsot_triaxial.cpp; numerics.md §1) ----

/// The body in sorted principal axes: I₁ < I₂ < I₃ (all three distinct), ω_s = P ω_b with P a signed
/// permutation (det P = +1). I and ω_s may be scaled by powers of two (exactly): I by any factor, ω_s
/// by 1/omega_scale, so the physical angular velocity is omega_scale · w.
struct SortedBody {
  Vec3 I;
  Vec3 w;
  Mat3 P;
  double omega_scale = 1.0;
};

/// Three distinct moments: the elliptic-function solution (both regimes and the separatrix).
/// Everything is written in the sorted frame {s} (ω_s = P ω_b); the derivation is at the top of
/// euler_poinsot_triaxial.cpp.
class TriaxialRotation {
 public:
  using Regime = EulerPoinsot::Regime;

  /// Requires w not along the intermediate axis (w₁ or w₃ non-zero). Sets `regime`.
  TriaxialRotation(const SortedBody& b, const Quat& q0, Regime& regime);
  Vec3 omega_b(double t) const { return P_.transpose() * omega_s(jacobi_(lambda_ * t + u0_)); }
  Quat q(double t) const { return q(t, jacobi_(lambda_ * t + u0_)); }
  /// Both from one evaluation of sn, cn, dn (the same u = λt + u₀ as each alone: the same bits).
  EulerPoinsot::State state(double t) const {
    const JacobiValues v = jacobi_(lambda_ * t + u0_);
    return {q(t, v), P_.transpose() * omega_s(v)};
  }
  double period_omega() const { return 4.0 * jacobi_.K() / lambda_; }
  double flip_interval() const { return 2.0 * jacobi_.K() / lambda_; }

 private:
  /// q(t) given v = sn, cn, dn, … at u = λt + u₀.
  Quat q(double t, const JacobiValues& v) const;
  // ω_s from sn, cn, dn (pole 3: ω₁ ∝ cn, ω₃ ∝ dn; pole 1: ω₁ ∝ dn, ω₃ ∝ cn).
  Vec3 omega_s(const JacobiValues& v) const {
    return pole_ == 3 ? Vec3(A_(0) * v.cn, A_(1) * v.sn, A_(2) * v.dn)
                      : Vec3(A_(0) * v.dn, A_(1) * v.sn, A_(2) * v.cn);
  }
  /// Π(−N; am u | m), continued beyond |am u| ≤ π/2 by Π(n; φ + jπ) = Π(n; φ) + 2jΠ(n).
  double Pi(double u, const JacobiValues& v) const {
    if (separatrix_) {
      // m = 1: Π(−N; am u | 1) = ∫₀ᵘ du′/(1 + N tanh²u′) = (u + √N atan(√N tanh u))/(1 + N).
      const double rN = std::sqrt(N_);
      return (u + rN * std::atan(rN * v.sn)) / (1.0 + N_);
    }
    return (*Pi_)(v);
  }
  /// The unit quaternion of Rz(φ) Rx(θ) Rz(ψ) for given φ: θ and ψ are the z-x-z angles of μ.
  Quat body_part(double phi, const JacobiValues& v) const {
    // Transverse part of μ up to the factor ρ (it is ρ·(h₁ cn, h₂ sn) for pole 3, ρ·(h₁ sn, h₂ cn) for
    // pole 1), so ψ stays defined when ρ = 0 (spin exactly about the pole).
    const double T1 = pole_ == 3 ? h_(0) * v.cn : h_(0) * v.sn;
    const double T2 = pole_ == 3 ? h_(1) * v.sn : h_(1) * v.cn;
    const double T = std::hypot(T1, T2);  // > 0: sn² + cn² = 1
    // ψ = atan2(T₁, T₂) ∈ [−π, π] and θ = atan2(ρ|T|, c dn) ∈ [0, π/2) (c dn > 0), taken by their half
    // angles without evaluating them: for an angle α with (sin α, cos α) = (y, x)/r,
    //   cos(α/2) = √((r + x)/(2r)),  sin(α/2) = y/√(2r(r + x))                  (x ≥ 0),
    //   sin(α/2) = ±√((r − x)/(2r)), cos(α/2) = |y|/√(2r(r − x)), ± the sign of y  (x < 0),
    // each a sum of non-negative terms (no cancellation); cos(α/2) ≥ 0 and the sign of sin(α/2) is
    // that of y, as with the angle from atan2 (its branch cut included).
    double c_psi, s_psi;
    if (T2 >= 0.0) {
      const double w = std::sqrt(2.0 * T * (T + T2));
      c_psi = (T + T2) / w;
      s_psi = T1 / w;
    } else {
      const double w = std::sqrt(2.0 * T * (T - T2));
      s_psi = std::copysign((T - T2) / w, T1);
      c_psi = std::abs(T1) / w;
    }
    const double y = rho_ * T, x = c_ * v.dn, r = std::hypot(y, x);
    const double w = std::sqrt(2.0 * r * (r + x));
    return quat_zxz(phi, (r + x) / w, y / w, c_psi, s_psi);
  }

  int pole_ = 3;
  bool separatrix_ = false;
  JacobiElliptic jacobi_{1.0, 0.0};  // set in the constructor (m = 1 costs nothing to set up)
  double lambda_ = 0.0, u0_ = 0.0;   // u = λt + u₀ (λ in rad/s)
  Vec3 A_;                           // signed amplitudes σ·A (rad/s)
  Vec3 h_;                           // shape of the transverse momentum (first two entries used)
  double rho_ = 0.0, c_ = 0.0;       // |μ_transverse| = ρ |T|, μ₃ = c dn
  double N_ = 0.0, kappa_ = 0.0, rate_ = 0.0, Pi0_ = 0.0;
  std::optional<EllipticPi> Pi_;  // Π(−N; am u | m) off the separatrix
  Mat3 P_;
  Quat G_, CP_;
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

 private:
  std::variant<SteadyRotation, AxisymmetricRotation, TriaxialRotation> flow_;
};

}  // namespace tumble::detail
