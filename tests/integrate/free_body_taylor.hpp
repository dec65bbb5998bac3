#pragma once
// An independent reference for the torque-free body: the Taylor-series method in long double.
//
// Euler's equations and the kinematics are quadratic, so the Taylor coefficients follow from Cauchy
// products (no derivatives to code by hand):
//   ω̇₁ = a₁ ω₂ω₃ (cyclic), aᵢ = (I_j − I_k)/Iᵢ  ⇒  ω₁[n+1] = a₁/(n+1) Σ_{k≤n} ω₂[k] ω₃[n−k],
//   q̇ = ½ q ⊗ (0, ω_b)                       ⇒  q[n+1] = 1/(2(n+1)) Σ_{k≤n} q[k] ⊗ (0, ω[n−k]).
// With order 30 and steps well inside the radius of convergence the truncation error is far below
// the rounding of long double (64-bit mantissa, ε = 1.1e-19), so the reference is ~1e-16 accurate over
// 1e4 steps; the tests check that by halving the step.
#include <algorithm>
#include <array>
#include <vector>

#include "tumble/math/types.hpp"

namespace tumble::test {

struct FreeBodyStateLd {
  std::array<long double, 3> w;  ///< ω_b
  std::array<long double, 4> q;  ///< (w, x, y, z), body → world
};

class FreeBodyTaylor {
 public:
  static constexpr int kMaxOrder = 40;

  FreeBodyTaylor(const Vec3& I, int order = 30) : order_(std::min(order, kMaxOrder)) {
    using LD = long double;
    const LD I1 = LD(I(0)), I2 = LD(I(1)), I3 = LD(I(2));
    a_ = {(I2 - I3) / I1, (I3 - I1) / I2, (I1 - I2) / I3};
  }

  /// One step of size h.
  FreeBodyStateLd step(const FreeBodyStateLd& s, long double h) const {
    const int P = order_;
    std::array<std::array<long double, 3>, kMaxOrder + 1> w;
    std::array<std::array<long double, 4>, kMaxOrder + 1> q;
    w[0] = s.w;
    q[0] = s.q;
    for (int n = 0; n < P; ++n) {
      std::array<long double, 3> cw{0, 0, 0};
      std::array<long double, 4> cq{0, 0, 0, 0};
      for (int k = 0; k <= n; ++k) {
        const auto& x = w[k];
        const auto& y = w[n - k];
        cw[0] += x[1] * y[2];
        cw[1] += x[2] * y[0];
        cw[2] += x[0] * y[1];
        // q[k] ⊗ (0, ω[n−k]): (−v·ω, q₀ω + v × ω)
        const auto& p = q[k];
        cq[0] += -(p[1] * y[0] + p[2] * y[1] + p[3] * y[2]);
        cq[1] += p[0] * y[0] + p[2] * y[2] - p[3] * y[1];
        cq[2] += p[0] * y[1] + p[3] * y[0] - p[1] * y[2];
        cq[3] += p[0] * y[2] + p[1] * y[1] - p[2] * y[0];
      }
      for (int i = 0; i < 3; ++i) w[n + 1][i] = a_[i] * cw[i] / (n + 1);
      for (int i = 0; i < 4; ++i) q[n + 1][i] = cq[i] / (2.0L * (n + 1));
    }
    FreeBodyStateLd out{{0, 0, 0}, {0, 0, 0, 0}};
    for (int n = P; n >= 0; --n) {  // Horner
      for (int i = 0; i < 3; ++i) out.w[i] = out.w[i] * h + w[n][i];
      for (int i = 0; i < 4; ++i) out.q[i] = out.q[i] * h + q[n][i];
    }
    return out;
  }

  /// States at t = 0, h, 2h, …, n h.
  std::vector<FreeBodyStateLd> run(const FreeBodyStateLd& s0, long double h, int n) const {
    std::vector<FreeBodyStateLd> out{s0};
    for (int i = 0; i < n; ++i) out.push_back(step(out.back(), h));
    return out;
  }

 private:
  int order_;
  std::array<long double, 3> a_;
};

inline FreeBodyStateLd to_ld(const Quat& q, const Vec3& w) {
  using LD = long double;
  return {{LD(w(0)), LD(w(1)), LD(w(2))}, {LD(q.w()), LD(q.x()), LD(q.y()), LD(q.z())}};
}
inline Vec3 omega_of(const FreeBodyStateLd& s) {
  return Vec3(static_cast<double>(s.w[0]), static_cast<double>(s.w[1]), static_cast<double>(s.w[2]));
}
inline Quat quat_of(const FreeBodyStateLd& s) {
  return Quat(static_cast<double>(s.q[0]), static_cast<double>(s.q[1]), static_cast<double>(s.q[2]),
              static_cast<double>(s.q[3]))
      .normalized();
}

}  // namespace tumble::test
