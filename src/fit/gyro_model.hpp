#pragma once
// The model's angular velocity at the samples, written once as a template on the number type: on
// double it predicts the gyro's samples, on Dual<double, N> (math/dual.hpp) it gives them together with
// their derivatives with respect to the N unknowns — the Jacobian of the discrete map RK4 actually
// computes, with no hand-derived tangent equations and no finite differences.
//
// State: the total angular momentum in sensor axes, L = J ω + h. Since the world momentum changes only
// by the applied torque, in body-fixed axes
//     L̇ = L × ω + τ,   ω = J⁻¹ (L − h),
// which is Euler's equation J ω̇ = (J ω + h) × ω + τ − ḣ with ḣ carried inside L: the wheel momentum h
// is needed at the stage times only, never its derivative (between samples τ and h are interpolated
// linearly, i.e. the wheel torque −ḣ is constant within an interval).
#include <cmath>
#include <vector>

#include "tumble/fit/gyro_fit.hpp"
#include "tumble/math/dual.hpp"
#include "tumble/math/quaternion.hpp"

namespace tumble::fit {

/// The classic RK4 tableau: c = (0, ½, ½, 1), weights b/6 with b = (1, 2, 2, 1). The same numbers as
/// rk4::c and rk4::b in src/integrate/rk4_steps.hpp, which is private to the integrate layer and tied to
/// its batched engine (it includes engine.hpp), so a later layer cannot include it.
inline constexpr double kRk4c[4] = {0.0, 0.5, 0.5, 1.0};
inline constexpr double kRk4b[4] = {1.0, 2.0, 2.0, 1.0};

/// How the unknowns are laid out in the parameter vector p.
///   absolute (a torque or wheel momentum is known): p = (Jxx, Jyy, Jzz, Jxy, Jxz, Jyz, ω₀, [b]);
///   trace one (neither: J's scale is unobservable):  p = (Jxx, Jyy, Jxy, Jxz, Jyz, ω₀, [b]) with
///   Jzz = 1 − Jxx − Jyy, so trace J = 1 holds exactly and the scale is not a free direction.
struct Layout {
  bool absolute = false;
  bool bias = false;
  int inertia_size() const { return absolute ? 6 : 5; }
  int omega0_index() const { return inertia_size(); }
  int bias_index() const { return inertia_size() + 3; }
  int size() const { return inertia_size() + 3 + (bias ? 3 : 0); }
};

/// J from p (see Layout).
template <class S>
Mat3T<S> inertia_of(const Layout& layout, const S* p) {
  const S Jxx = p[0], Jyy = p[1];
  const S Jzz = layout.absolute ? p[2] : S(1.0) - Jxx - Jyy;
  const int o = layout.absolute ? 3 : 2;
  const S Jxy = p[o], Jxz = p[o + 1], Jyz = p[o + 2];
  Mat3T<S> J;
  J << Jxx, Jxy, Jxz,  //
      Jxy, Jyy, Jyz,   //
      Jxz, Jyz, Jzz;
  return J;
}

inline double value_of(double x) { return x; }
template <int N>
double value_of(const Dual<double, N>& x) {
  return x.v;
}

/// J⁻¹ = adj(J)/det J of the symmetric J, or false when J is not positive definite (Sylvester: the
/// leading minors Jxx, Jxx Jyy − Jxy², det J all > 0); the model is undefined there.
template <class S>
bool inverse_if_positive_definite(const Mat3T<S>& J, Mat3T<S>& Jinv) {
  const S c00 = J(1, 1) * J(2, 2) - J(1, 2) * J(1, 2);
  const S c01 = J(0, 2) * J(1, 2) - J(0, 1) * J(2, 2);
  const S c02 = J(0, 1) * J(1, 2) - J(0, 2) * J(1, 1);
  const S c11 = J(0, 0) * J(2, 2) - J(0, 2) * J(0, 2);
  const S c12 = J(0, 1) * J(0, 2) - J(0, 0) * J(1, 2);
  const S c22 = J(0, 0) * J(1, 1) - J(0, 1) * J(0, 1);
  const S det = J(0, 0) * c00 + J(0, 1) * c01 + J(0, 2) * c02;
  if (!(value_of(J(0, 0)) > 0.0 && value_of(c22) > 0.0 && value_of(det) > 0.0)) return false;
  const S inv = S(1.0) / det;
  Jinv << c00 * inv, c01 * inv, c02 * inv,  //
      c01 * inv, c11 * inv, c12 * inv,      //
      c02 * inv, c12 * inv, c22 * inv;
  return true;
}

/// The steps between samples: interval k (t_k → t_{k+1}) is crossed in per_interval[k] equal steps.
struct Steps {
  std::vector<int> per_interval;
  double longest = 0.0;  ///< the longest step (s)
};
/// Equal steps of at most h_max in every interval.
inline Steps steps_of_at_most(const Telemetry& d, double h_max) {
  Steps s;
  for (std::size_t k = 0; k + 1 < d.t.size(); ++k) {
    const double dt = d.t[k + 1] - d.t[k];
    const int n = std::max(1, static_cast<int>(std::ceil(dt / h_max * (1.0 - 1e-12))));
    s.per_interval.push_back(n);
    s.longest = std::max(s.longest, dt / n);
  }
  return s;
}

/// L̇ = L × ω + τ with ω = J⁻¹ (L − h): Euler's equation for the total momentum in sensor axes.
template <class S>
Vec3T<S> momentum_rate(const Mat3T<S>& Jinv, const Vec3T<S>& L, const Vec3& h, const Vec3& tau) {
  const Vec3T<S> omega = Jinv * (L - h.cast<S>());
  return L.cross(omega) + tau.cast<S>();
}

/// v[k], or zero when v is empty (no torque, no wheel).
inline Vec3 sample_or_zero(const std::vector<Vec3>& v, std::size_t k) {
  return v.empty() ? Vec3(Vec3::Zero()) : v[k];
}

/// ŷ_k = ω(t_k) + b at every sample, from the unknowns p (Layout), into y_hat (one per sample). False
/// when J is not positive definite or the motion is not finite.
template <class S>
bool predict(const Telemetry& d, const Steps& steps, const Layout& layout, const S* p, Vec3T<S>* y_hat) {
  Mat3T<S> Jinv;
  const Mat3T<S> J = inertia_of(layout, p);
  if (!inverse_if_positive_definite(J, Jinv)) return false;
  const Vec3T<S> omega0(p[layout.omega0_index()], p[layout.omega0_index() + 1], p[layout.omega0_index() + 2]);
  const Vec3T<S> b =
      layout.bias ? Vec3T<S>(p[layout.bias_index()], p[layout.bias_index() + 1], p[layout.bias_index() + 2])
                  : Vec3T<S>(S(0.0), S(0.0), S(0.0));
  const bool has_h = !d.h.empty(), has_tau = !d.tau.empty();

  Vec3T<S> L = J * omega0 + sample_or_zero(d.h, 0).cast<S>();  // L(t₀) = J ω₀ + h(t₀)
  y_hat[0] = omega0 + b;
  for (std::size_t k = 0; k + 1 < d.t.size(); ++k) {
    const double Dt = d.t[k + 1] - d.t[k];
    const int n = steps.per_interval[k];
    const double dt = Dt / n;
    const Vec3 h0 = sample_or_zero(d.h, k), dh = has_h ? Vec3(d.h[k + 1] - d.h[k]) : Vec3(Vec3::Zero());
    const Vec3 tau0 = sample_or_zero(d.tau, k),
               dtau = has_tau ? Vec3(d.tau[k + 1] - d.tau[k]) : Vec3(Vec3::Zero());
    for (int i = 0; i < n; ++i) {
      // Classic RK4: k_s = f(t + c_s dt, L + c_s dt k_{s−1}), L ← L + dt/6 Σ b_s k_s.
      Vec3T<S> A = Vec3T<S>::Zero(), Y = L;
      for (int s = 0; s < 4; ++s) {
        const double alpha = (i + kRk4c[s]) / n;  // where the stage is in the interval, 0 … 1
        const Vec3T<S> K = momentum_rate<S>(Jinv, Y, h0 + alpha * dh, tau0 + alpha * dtau);
        A += S(kRk4b[s]) * K;
        if (s < 3) Y = L + S(kRk4c[s + 1] * dt) * K;
      }
      L += S(dt / 6.0) * A;
    }
    y_hat[k + 1] = Jinv * (L - sample_or_zero(d.h, k + 1).cast<S>()) + b;
    if (!std::isfinite(value_of(L.x())) || !std::isfinite(value_of(L.y())) || !std::isfinite(value_of(L.z())))
      return false;
  }
  return true;
}

}  // namespace tumble::fit
