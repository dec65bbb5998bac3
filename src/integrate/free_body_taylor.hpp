#pragma once
// The torque-free body by its Taylor series in time, on any number type Real: long double or
// __float128 for the tests' independent reference, dual numbers for the derivatives of the exact free
// flow where its closed form has none (free_flow_tangent.cpp: equal moments, the separatrix, a spin
// about a principal axis).
//
// Euler's equations and the kinematics are quadratic, so the Taylor coefficients follow from Cauchy
// products (no derivatives to code by hand):
//   ω̇₁ = a₁ ω₂ω₃ (cyclic), aᵢ = (I_j − I_k)/Iᵢ  ⇒  ω₁[n+1] = a₁/(n+1) Σ_{k≤n} ω₂[k] ω₃[n−k],
//   q̇ = ½ q ⊗ (0, ω_b)                       ⇒  q[n+1] = 1/(2(n+1)) Σ_{k≤n} q[k] ⊗ (0, ω[n−k]).
// With order 30 and steps well inside the radius of convergence the truncation error is far below
// the rounding of long double (64-bit mantissa, ε = 1.1e-19), so the reference is ~1e-16 accurate over
// 1e4 steps; the tests check that by halving the step. Near the separatrix every step's rounding is
// amplified ~7e7 at each flip (the racket I = (1.5, 2.5, 4), ω₁ = 0.002: a perturbation's growth
// across a flip, measured with this reference in two precisions): there the reference runs in __float128 (ε = 1.9e-34).
#include <algorithm>
#include <array>
#include <type_traits>
#include <vector>

#include "tumble/math/lanes.hpp"
#include "tumble/math/types.hpp"

namespace tumble {

template <class Real>
struct FreeBodyStateT {
  std::array<Real, 3> w;  ///< ω_b
  std::array<Real, 4> q;  ///< (w, x, y, z), body → world
};

template <class Real>
class FreeBodyTaylorT {
 public:
  static constexpr int kMaxOrder = 40;

  FreeBodyTaylorT(const Vec3& I, int order = 30)
      : FreeBodyTaylorT(std::array<Real, 3>{Real(I(0)), Real(I(1)), Real(I(2))}, order) {}
  /// The principal moments in Real (seeded dual numbers give the derivatives with respect to them).
  FreeBodyTaylorT(const std::array<Real, 3>& I, int order) : order_(std::min(order, kMaxOrder)) {
    a_ = {(I[1] - I[2]) / I[0], (I[2] - I[0]) / I[1], (I[0] - I[1]) / I[2]};
    inv_I_ = {Real(1) / I[0], Real(1) / I[1], Real(1) / I[2]};
  }
  /// A gyrostat: rotors of constant momentum h relative to the body (principal axes), whose equation
  /// Λ ω̇ = (Λω + h) × ω adds the linear term Λ⁻¹(h × ω):  ω[n+1] += Λ⁻¹(h × ω[n])/(n+1).
  FreeBodyTaylorT(const Vec3& I, const Vec3& h, int order)
      : FreeBodyTaylorT(std::array<Real, 3>{Real(I(0)), Real(I(1)), Real(I(2))},
                        std::array<Real, 3>{Real(h(0)), Real(h(1)), Real(h(2))}, order) {}
  /// The same in Real (a pack of bodies, or dual numbers).
  FreeBodyTaylorT(const std::array<Real, 3>& I, const std::array<Real, 3>& h, int order)
      : FreeBodyTaylorT(I, order) {
    h_ = h;
    gyrostat_ = true;
  }
  /// aᵢ = (I_j − I_k)/Iᵢ: ω̇ᵢ = aᵢ ω_j ω_k.
  const std::array<Real, 3>& a() const { return a_; }

  /// One step of size h.
  FreeBodyStateT<Real> step(const FreeBodyStateT<Real>& s, Real h) const {
    return step(s, h, order_, order_);
  }

  /// One step of size h with the series truncated after the term of order `lane_order` (a number, or a
  /// pack of them, one per lane), P ≥ each: the terms above a lane's order are left out of its sum, so a
  /// lane computes, bit for bit, what a series of its own order gives (Horner from zeros: 0·h + c = c).
  template <class Order>
  FreeBodyStateT<Real> step(const FreeBodyStateT<Real>& s, Real h, const Order& lane_order, int P) const {
    std::array<std::array<Real, 3>, kMaxOrder + 1> w;
    std::array<std::array<Real, 4>, kMaxOrder + 1> q;
    w[0] = s.w;
    q[0] = s.q;
    for (int n = 0; n < P; ++n) {
      std::array<Real, 3> cw{0, 0, 0};
      std::array<Real, 4> cq{0, 0, 0, 0};
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
      for (int i = 0; i < 3; ++i) cw[i] *= a_[i];
      if (gyrostat_) {
        const auto& y = w[n];
        cw[0] += (h_[1] * y[2] - h_[2] * y[1]) * inv_I_[0];
        cw[1] += (h_[2] * y[0] - h_[0] * y[2]) * inv_I_[1];
        cw[2] += (h_[0] * y[1] - h_[1] * y[0]) * inv_I_[2];
      }
      for (int i = 0; i < 3; ++i) w[n + 1][i] = cw[i] / Real(n + 1);
      for (int i = 0; i < 4; ++i) q[n + 1][i] = cq[i] / Real(2 * (n + 1));
    }
    FreeBodyStateT<Real> out{{0, 0, 0}, {0, 0, 0, 0}};
    for (int n = P; n >= 0; --n) {  // Horner
      if constexpr (std::is_same_v<Order, int>) {
        for (int i = 0; i < 3; ++i) out.w[i] = out.w[i] * h + w[n][i];
        for (int i = 0; i < 4; ++i) out.q[i] = out.q[i] * h + q[n][i];
      } else {
        const auto in = Order(n) <= lane_order;
        for (int i = 0; i < 3; ++i) out.w[i] = out.w[i] * h + select(in, w[n][i], Real(0));
        for (int i = 0; i < 4; ++i) out.q[i] = out.q[i] * h + select(in, q[n][i], Real(0));
      }
    }
    return out;
  }

  /// States at t = 0, h, 2h, …, n h.
  std::vector<FreeBodyStateT<Real>> run(const FreeBodyStateT<Real>& s0, Real h, int n) const {
    std::vector<FreeBodyStateT<Real>> out{s0};
    for (int i = 0; i < n; ++i) out.push_back(step(out.back(), h));
    return out;
  }

 private:
  int order_;
  std::array<Real, 3> a_, inv_I_;
  std::array<Real, 3> h_{Real(0), Real(0), Real(0)};
  bool gyrostat_ = false;
};

}  // namespace tumble
