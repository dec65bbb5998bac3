#pragma once
// The splittings' drift for a body whose rotors' motors hold their speeds (h constant over the step):
// the torque-free gyrostat's flow
//   Λ ω̇ = (Λω + h) × ω,  q̇ = ½ q ⊗ (0, ω),
// by its Taylor series (free_body_taylor.hpp), exact to rounding: each substep advances at most
// τ r = 1/8 with r = |ω| + |Λ⁻¹h| (|Λ⁻¹h| ≤ r' for every term of the rates: the moments' triangle
// inequality bounds |(I_j − I_k)/I_i| by 1), so the order-18 series leaves ~(1/8)¹⁹ = 1.4e-17 of the
// step — below the rounding of one step. Why not the closed form (gyrostat_flow.hpp), which `exact`
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

inline constexpr int kSeriesOrder = 18;
inline constexpr double kSeriesReach = 0.125;  ///< τ r per substep

/// ⌈|τ| r / reach⌉ (at least 1) for a rate bound r: the substeps of one lane, as a number.
inline double series_substeps(double tau_times_rate) {
  return std::max(1.0, std::ceil(std::abs(tau_times_rate) / kSeriesReach));
}

/// The gyrostat's flow over τ from (q, ω_b) in n substeps of τ/n (n: a number, or a pack of them with
/// n_max their largest; a lane's state stops changing after its own n).
template <class T, class N>
detail::FlowState<T> series_flow(const Vec3T<T>& Lambda, const Vec3T<T>& h, const QuatT<T>& q,
                                 const Vec3T<T>& w_b, double tau, const N& n, double n_max) {
  const FreeBodyTaylorT<T> taylor(std::array<T, 3>{Lambda(0), Lambda(1), Lambda(2)},
                                  std::array<T, 3>{h(0), h(1), h(2)}, kSeriesOrder);
  FreeBodyStateT<T> s{{w_b(0), w_b(1), w_b(2)}, {q.w(), q.x(), q.y(), q.z()}};
  const T dt = T(tau) / T(n);
  for (double k = 0; k < n_max; ++k) {
    const FreeBodyStateT<T> next = taylor.step(s, dt);
    const auto live = N(k) < n;
    for (int i = 0; i < 3; ++i) s.w[i] = select(live, next.w[i], s.w[i]);
    for (int i = 0; i < 4; ++i) s.q[i] = select(live, next.q[i], s.q[i]);
  }
  using std::sqrt;
  const T norm = sqrt(s.q[0] * s.q[0] + s.q[1] * s.q[1] + s.q[2] * s.q[2] + s.q[3] * s.q[3]);
  return {QuatT<T>(s.q[0] / norm, s.q[1] / norm, s.q[2] / norm, s.q[3] / norm), Vec3T<T>(s.w[0], s.w[1], s.w[2])};
}

}  // namespace tumble::gyrostat
