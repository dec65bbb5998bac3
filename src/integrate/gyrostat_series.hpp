#pragma once
// The splittings' drift for a body whose rotors' motors hold their speeds (h constant over the step):
// the torque-free gyrostat's flow
//   Λ ω̇ = (Λω + h) × ω,  q̇ = ½ q ⊗ (0, ω),
// by its Taylor series (free_body_taylor.hpp), exact to rounding: each substep advances at most
// τ r = 1/8 with r a bound of the rates (series_rate), so the order-18 series leaves ~(1/8)¹⁹ = 1.4e-17
// of the step — below the rounding of one step. Why not the closed form (gyrostat_flow.hpp), which `exact`
// evaluates: a drift starts from a new state each step, and the closed form's set-up costs 35–110 µs
// (bench/gyrostat_flow_bench.cpp), where the series costs ~0.3 µs a body on packs; the two agree to
// rounding (tests/integrate/gyrostat_flow_test.cpp).
//
// One template for double, SIMD packs (one body per lane; each lane takes its own number of substeps,
// so a body steps the same alone as in a pack) and dual numbers (the sensitivities differentiate the
// same drift the values take).
#include <algorithm>
#include <array>
#include <cmath>

#include "euler_poinsot_flows.hpp"
#include "free_body_taylor.hpp"
#include "tumble/math/lanes.hpp"

namespace tumble::gyrostat {

inline constexpr int kSeriesOrder = 18;        ///< the most terms a substep keeps
inline constexpr double kSeriesReach = 0.125;  ///< τ r per substep, at most

/// r = |ω| + |h|/min Λ: a bound of every rate in the equations (|a_i ω_j ω_k| ≤ |ω|², as |a_i| ≤ 1 by the
/// moments' triangle inequality; |(h × ω)_i/I_i| ≤ |h||ω|/min Λ), so that the series' terms shrink
/// like (τ r)ⁿ.
template <class T>
T series_rate(const Vec3T<T>& w_b, const Vec3T<T>& h, const Vec3T<T>& Lambda) {
  using std::sqrt, std::min;
  return sqrt(w_b.squaredNorm()) + sqrt(h.squaredNorm()) / min(Lambda(0), min(Lambda(1), Lambda(2)));
}

/// The largest lane of a pack (a number is its own).
inline double largest(double x) { return x; }
template <class Pack>
double largest(const Pack& x) {
  alignas(64) double lanes[Pack::size];
  x.store_aligned(lanes);
  return *std::max_element(lanes, lanes + Pack::size);
}

/// The gyrostat's flow over τ from (q, ω_b), for the rate bound r (series_rate; a number for T = double
/// or dual numbers, a pack for a pack). Each lane takes n = ⌈|τ| r/reach⌉ substeps of τ/n (a lane's
/// state stops changing after its own n) and keeps the series' terms up to the order N at which
/// (τ r/n)^(N+1) ≤ ε/8 (at most 18, at least 2): a short step takes few terms.
template <class T, class N>
detail::FlowState<T> series_flow(const Vec3T<T>& Lambda, const Vec3T<T>& h, const QuatT<T>& q,
                                 const Vec3T<T>& w_b, double tau, const N& rate) {
  using std::abs, std::ceil, std::log, std::max, std::min, std::sqrt;
  const N n = max(N(1.0), ceil(abs(N(tau) * rate) / N(kSeriesReach)));
  const N reach = abs(N(tau) * rate) / n;
  const N order = min(N(kSeriesOrder),
                      max(N(2.0), ceil(N(std::log(0.125 * 2.220446049250313e-16)) / log(reach)) - N(1.0)));
  const FreeBodyTaylorT<T> taylor(std::array<T, 3>{Lambda(0), Lambda(1), Lambda(2)},
                                  std::array<T, 3>{h(0), h(1), h(2)}, kSeriesOrder);
  FreeBodyStateT<T> s{{w_b(0), w_b(1), w_b(2)}, {q.w(), q.x(), q.y(), q.z()}};
  const T dt = T(tau) / T(n);
  const double n_max = largest(n);
  const int P = static_cast<int>(largest(order));
  for (double k = 0; k < n_max; ++k) {
    const FreeBodyStateT<T> next = taylor.step(s, dt, order, P);
    const auto live = N(k) < n;
    for (int i = 0; i < 3; ++i) s.w[i] = select(live, next.w[i], s.w[i]);
    for (int i = 0; i < 4; ++i) s.q[i] = select(live, next.q[i], s.q[i]);
  }
  const T norm = sqrt(s.q[0] * s.q[0] + s.q[1] * s.q[1] + s.q[2] * s.q[2] + s.q[3] * s.q[3]);
  return {QuatT<T>(s.q[0] / norm, s.q[1] / norm, s.q[2] / norm, s.q[3] / norm),
          Vec3T<T>(s.w[0], s.w[1], s.w[2])};
}

}  // namespace tumble::gyrostat
