#pragma once
// Carlson's symmetric elliptic integral R_J on tumble's number types (double or a pack of lanes,
// math/lanes.hpp), for the exact Euler–Poinsot flow on packs:
//     Π(n; φ | m) = F(φ | m) + (n/3) s³ R_J(c², d², 1, 1 − n s²)   (DLMF 19.25.14),
// where F(φ | m) = s R_F(c², d², 1) is the Jacobi argument itself at the points the flow evaluates
// (jacobi_elliptic.hpp's elliptic_pi), so R_F is not needed there.
// Boost's ellint_rj branches on the arguments and iterates until converged, so it cannot run on a
// pack. Here every lane does the same work: a FIXED number of duplication steps (DLMF 19.36.2; B. C.
// Carlson, "Numerical computation of real or complex elliptic integrals", Numer. Algorithms 10 (1995)
// 13–26), then the 5th-order series; the one choice (R_C at small argument) is a select.
//
// The domain the step counts are tuned for (they hold the error there, not beyond):
//     x = c², y = d², z = 1 with k′² = m₁ ∈ [1e-16, 1], c ∈ (0, 1], d ∈ [k′, 1], d² = c² + m₁ s²;
//     the Jacobi functions reflect arguments past K/2 (jacobi_elliptic.hpp), which keeps
//     c ≥ cn(K/2) = √(k′/(1 + k′)) and d ≥ dn(K/2) = √k′, so x, y ≥ k′/(1 + k′) ≥ 1e-8 (1 − 1e-8);
//     for R_J, s² = 1 − c² and either p = 1 + N s² with N = −n ∈ [0, 1e12] (p ∈ [1, 1 + 1e12]), or, at
//     a reflected point, p = 1 − n′ s² with n′ = (m + N)/(1 + N) ∈ [m, 1) (then x ≤ p ≤ y).
// Both have p ≥ x and δ = (p − x)(p − y)(p − z) ≥ 0, which carlson_rj relies on. Smaller x and y, or
// larger p, converge more slowly (the arguments' spread shrinks 4× per step but has further to go) and
// would need more steps.
//
// The order of operations is as written (the build uses -ffp-contract=off, and nothing here is a
// reduction that Eigen could reorder), so double, the reference pack and an xsimd pack agree lane by
// lane: bit for bit on double and the reference pack, and on xsimd packs up to the last bits of xsimd's
// own atan (≤ 2 ulps measured).
#include <cmath>

#include "tumble/math/lanes.hpp"

namespace tumble {

/// Duplication steps carlson_rj needs for the arguments of one flow: p ≤ 1 + N at m₁ = k′² (and its
/// reflected points, p ≤ 1). p ≫ x, y, z converges slowly: p_m − x_m = 4⁻ᵐ(p − x), so the steps grow
/// like log₄ N; small x, y (x ≥ k′/(1 + k′)) need a few more. The smallest counts whose truncation is
/// ≤ 0.05ε over x ∈ [k′/(1 + k′), 1] (and the reflected p) were measured by evaluating carlson_rj in
/// long double against Boost's in long double (bench/carlson_rj_steps.cpp), for 65 values of m₁ from
/// 1e-16 to 1 and 40 of N from 0 to 1e12: they are base(m₁) + ⌈log₄(1 + N)⌉ at most, with base 3 for
/// m₁ ≥ 0.056, 4 down to 3.2e-4, 5 down to 5.6e-9 and 6 below (one step fewer than the 5th-order series
/// needed: 4, 5 down to 1e-4, 6 down to 5.6e-10, 7). The count below is that with the thresholds moved
/// up (0.1, 1e-3, 1e-8) and one step of margin; the error is then rounding alone
/// (tests/integrate/carlson_test.cpp: ≤ 6ε over the domain). The usual bodies (N ≲ 15, m₁ ≥ 0.1) take 5
/// or 6 steps, where a count from N alone (the m₁ = 1e-16 one) took 8 or 9, and the 27 that N = 1e12
/// needs would be 5× the cost.
inline int carlson_rj_steps(double N, double m1) {
  int steps = m1 >= 0.1 ? 4 : m1 >= 1e-3 ? 5 : m1 >= 1e-8 ? 6 : 7;
  for (double power = 1.0; power < 1.0 + N && steps < 64; power *= 4.0) ++steps;
  return steps;
}

namespace carlson_detail {

/// 4⁻ᵐ, exactly (a power of two).
constexpr double quarter_power(int m) {
  double r = 1.0;
  for (int i = 0; i < m; ++i) r *= 0.25;
  return r;
}

/// R_C(1, 1 + e) = atan(√e)/√e for e ≥ 0 (DLMF 19.2.19). Below e = 0.02 the Taylor series
/// Σ (−e)ᵏ/(2k + 1), k = 0 … 9 (truncation < e¹⁰/21 < 5e-19) replaces it. Both are computed and
/// selected; the atan branch sees e = 1 in those lanes, so e = 0 gives exactly 1 and no lane ever
/// forms 0/0. The series takes over from the second duplication step on for the usual bodies
/// (e_m falls ~64× a step), where the atan form costs a square root and three divisions.
template <class T>
TUMBLE_INLINE T rc_one(T e) {
  using std::atan;
  using std::sqrt;
  const auto small = e < T(0.02);
  T by_series = T(1.0 / 19);  // Horner, from the last term in: 1 − e(1/3 − e(1/5 − …))
  for (int k = 8; k >= 0; --k) by_series = T(1.0 / (2 * k + 1)) - e * by_series;
  // Every lane small (all but the first step or two): the atan form would be computed and discarded.
  // Skipping it changes no lane's bits.
  if (all(small)) return by_series;
  const T t = sqrt(select(small, T(1), e));
  const T by_atan = atan(t) / t;
  return select(small, by_series, by_atan);
}

}  // namespace carlson_detail

/// R_J(x, y, z, p) = (3/2) ∫₀^∞ dt / ((t + p) √((t + x)(t + y)(t + z))), in the domain above (p ≥ x and
/// δ ≥ 0: every e_m ≥ 0, so R_C(1, 1 + e_m) is the atan form), with `steps` duplication steps
/// (carlson_rj_steps). On a pack each lane has its own count: the loop runs `max_steps`, the largest,
/// and a lane past its own count keeps its values (so it computes the bits of its own count).
/// Given also √x, √y, √z (≥ 0), the first duplication step takes one square root (√p) instead of four:
/// the exact flow has them (x = cn², y = dn², z = 1: jacobi_elliptic.hpp), and its drift on packs is
/// bound by the divider, which takes the square roots.
template <class T>
TUMBLE_INLINE T carlson_rj_with_roots(T x, T y, T z, T sx, T sy, T sz, T p, T steps, int max_steps) {
  using std::sqrt;
  // A₀ = (x + y + z + 2p)/5. Each duplication maps x ← (x + λ)/4 (likewise y, z, A, p) with
  // λ = √x√y + √x√z + √y√z; A_m − x_m = 4⁻ᵐ(A₀ − x), so the deviations are taken once at step 0 (no
  // cancellation later) and only A is carried to the end. Step m adds
  // 6·4⁻ᵐ R_C(1, 1 + e_m)/d_m with d_m = (√p_m + √x_m)(√p_m + √y_m)(√p_m + √z_m) and
  // e_m = 4⁻³ᵐ δ/d_m², δ = (p − x)(p − y)(p − z) from the inputs (p_m − x_m = 4⁻ᵐ(p − x): no
  // cancellation); e_m = Π (√p_m − √x_m)/(√p_m + √x_m) ∈ [0, 1).
  T A = (x + y + z + p + p) / T(5);
  const T dx = A - x, dy = A - y, dz = A - z;
  const T delta = (p - x) * (p - y) * (p - z);
  // p_m = x_m + 4⁻ᵐ(p − x), a sum of two non-negative numbers, rather than its own recurrence: for
  // p ≫ x that lost ~0.5ε of p in each of ~20 steps, which d_m ∝ p_m^{3/2} carried into the sum
  // (measured: worst error at N = 1e12 5.5ε → 4.5ε, mean 0.62ε → 0.57ε).
  const T p_minus_x = p - x;
  T sum = T(0), carry = T(0);
  T scale = T(1);            // 4⁻ᵐ of each lane, exact
  double scale_cubed = 1.0;  // 4⁻³ᵐ
  for (int m = 0; m < max_steps; ++m) {
    const auto active = T(static_cast<double>(m)) < steps;
    const T sp = sqrt(p);
    const T lambda = sx * sy + sx * sz + sy * sz;
    const T d = (sp + sx) * (sp + sy) * (sp + sz);
    // One division a step (the divider bounds this loop on packs): 1/d serves e_m and the term.
    const T inv_d = T(1) / d;
    const T e = delta * T(scale_cubed) * inv_d * inv_d;
    const T term = select(active, scale * carlson_detail::rc_one(e) * inv_d, T(0));  // + 0 changes nothing
    // Compensated sum (Knuth's TwoSum: carry collects what sum + term rounds off). Several terms are of
    // the same size, and plain summation was R_J's largest rounding error (measured over the domain:
    // worst 5.8ε → 4.1ε, mean 0.9ε → 0.6ε).
    const T total = sum + term, back = total - sum;
    carry = carry + ((sum - (total - back)) + (term - back));
    sum = total;
    x = select(active, (x + lambda) * T(0.25), x);
    y = select(active, (y + lambda) * T(0.25), y);
    z = select(active, (z + lambda) * T(0.25), z);
    A = select(active, (A + lambda) * T(0.25), A);
    scale = select(active, scale * T(0.25), scale);
    scale_cubed *= 1.0 / 64;
    p = x + scale * p_minus_x;
    if (m + 1 < max_steps) sx = sqrt(x), sy = sqrt(y), sz = sqrt(z);
  }
  // Now scale = 4⁻ᴹ. X, Y, Z = (A₀ − ·)/(4ᴹ A_M), P = (−X − Y − Z)/2;
  // E₂ = XY + XZ + YZ − 3P², E₃ = XYZ + 2E₂P + 4P³, E₄ = (2XYZ + E₂P + 3P³)P, E₅ = XYZP²;
  // R_J ≈ 4⁻ᴹ A_M^{−3/2} (1 − 3E₂/14 + E₃/6 + 9E₂²/88 − 3E₄/22 − 9E₂E₃/52 + 3E₅/26 − E₂³/16 + 3E₃²/40
  //                       + 3E₂E₄/20 + 45E₂²E₃/272 − 9(E₃E₄ + E₂E₅)/68) + 6 Σ,
  // the series to 7th order (DLMF 19.36.2; Carlson 1995): its truncation is O(|X|⁸), and |X| shrinks
  // 4× a duplication step, so each step gains 2¹⁶ (2¹² to 5th order) and fewer steps reach the same
  // truncation (carlson_rj_steps). The six terms cost a dozen products; a step costs four square roots.
  const T sqrt_A = sqrt(A), inv_A_3_2 = T(1) / (A * sqrt_A), inv_A = inv_A_3_2 * sqrt_A;  // one division
  const T X = dx * scale * inv_A, Y = dy * scale * inv_A, Z = dz * scale * inv_A;
  const T P = -(X + Y + Z) * T(0.5);
  const T XYZ = X * Y * Z, P2 = P * P;
  const T E2 = X * Y + X * Z + Y * Z - T(3) * P2;
  const T E3 = XYZ + T(2) * E2 * P + T(4) * P2 * P;
  const T E4 = (T(2) * XYZ + E2 * P + T(3) * P2 * P) * P;
  const T E5 = XYZ * P2;
  const T E2E2 = E2 * E2;
  const T series = T(1) - T(3.0 / 14) * E2 + T(1.0 / 6) * E3 + T(9.0 / 88) * E2E2 - T(3.0 / 22) * E4 -
                   T(9.0 / 52) * E2 * E3 + T(3.0 / 26) * E5 - T(1.0 / 16) * E2E2 * E2 +
                   T(3.0 / 40) * E3 * E3 + T(3.0 / 20) * E2 * E4 + T(45.0 / 272) * E2E2 * E3 -
                   T(9.0 / 68) * (E3 * E4 + E2 * E5);
  return scale * series * inv_A_3_2 + T(6) * (sum + carry);
}

/// R_J(x, y, z, p) from the arguments alone.
template <class T>
TUMBLE_INLINE T carlson_rj(T x, T y, T z, T p, T steps, int max_steps) {
  using std::sqrt;
  return carlson_rj_with_roots<T>(x, y, z, sqrt(x), sqrt(y), sqrt(z), p, steps, max_steps);
}

}  // namespace tumble
