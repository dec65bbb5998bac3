#pragma once
// Carlson's symmetric elliptic integrals R_F and R_J on tumble's number types (double or a pack of
// lanes, math/lanes.hpp), for the exact Euler–Poinsot flow on packs:
//     Π(n; φ | m) = s R_F(c², d², 1) + (n/3) s³ R_J(c², d², 1, 1 − n s²)   (DLMF 19.25.14).
// Boost's ellint_rf/ellint_rj branch on the arguments and iterate until converged, so they cannot run
// on a pack. Here every lane does the same work: a FIXED number of duplication steps (DLMF 19.36.1–2;
// B. C. Carlson, "Numerical computation of real or complex elliptic integrals", Numer. Algorithms 10
// (1995) 13–26), then the 5th-order series; the one choice (R_C at small argument) is a select.
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
// lane: bit for bit for R_F (only +, −, ×, ÷ and √, all correctly rounded), and for R_J up to the last
// bits of xsimd's own atan (≤ 2 ulps measured).
#include <cmath>

#include "tumble/math/lanes.hpp"

namespace tumble {

/// Duplication steps of carlson_rf. The truncation error of the series, measured over the domain
/// against Boost in long double, is 880ε after 6 steps and 0.22ε after 7 (both at x = y = 1e-8, the
/// corner m₁ = 1e-16 with c = cn(K/2)); from 8 on it is below 0.002ε. 7 + 1 of margin: the error is
/// then rounding alone, ≤ 3.3ε relative (mean 0.53ε) on 1.6e6 points, Boost in double ≤ 2.6ε.
inline constexpr int kCarlsonRfSteps = 8;

/// Duplication steps carlson_rj needs for p ≤ 1 + N (and for every reflected point, p ≤ 1). p ≫ x, y, z
/// converges slowly: p_m − x_m = 4⁻ᵐ(p − x), so the steps grow like log₄ N. Smallest counts with
/// truncation ≤ 0.05ε over the domain (measured against Boost in long double, as for R_F): 10 for
/// N ≤ 1e2, 14 for 1e4, 17 for 1e6, 20 for 1e8, 24 for 1e10, 27 for 1e12 (26 leaves 16ε at
/// x = y = 1e-8, N = 1e12), about 7 + log₄(1 + N); the reflected points converge within R_F's 8. This
/// gives 8 + ⌈log₄(1 + N)⌉, one of margin: 12 for N ≤ 1e2, 28 for 1e12. The error is then rounding
/// alone, on 1.6e6 points ≤ 5.3ε relative for p ≥ 1 (at N ~ 1e12) and ≤ 3.5ε reflected, mean 0.57ε;
/// Boost in double ≤ 23ε (at x = y = z). A count per characteristic, rather than the 28 that N = 1e12
/// needs for all, makes R_J of the usual bodies (N ≲ 1e2) 2.3× cheaper.
inline int carlson_rj_steps(double N) {
  int steps = 8;
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

/// R_C(1, 1 + e) = atan(√e)/√e for e ≥ 0 (DLMF 19.2.19). Below e = 1e-4 the Taylor series
/// 1 − e/3 + e²/5 − e³/7 + e⁴/9 (truncation < e⁵/11 < 1e-21) replaces it. Both are computed and
/// selected; the atan branch sees e = 1 in those lanes, so e = 0 gives exactly 1 and no lane ever
/// forms 0/0.
template <class T>
TUMBLE_INLINE T rc_one(T e) {
  using std::atan;
  using std::sqrt;
  const auto small = e < T(1e-4);
  const T by_series = T(1) - e * (T(1.0 / 3) - e * (T(1.0 / 5) - e * (T(1.0 / 7) - e * T(1.0 / 9))));
  // Every lane small (all but the first few steps): the atan form would be computed and discarded.
  // Skipping it changes no lane's bits.
  if (all(small)) return by_series;
  const T t = sqrt(select(small, T(1), e));
  const T by_atan = atan(t) / t;
  return select(small, by_series, by_atan);
}

}  // namespace carlson_detail

/// R_F(x, y, z) = ½ ∫₀^∞ dt / √((t + x)(t + y)(t + z)), for x, y, z ≥ 0 in the domain above.
template <class T>
TUMBLE_INLINE T carlson_rf(T x, T y, T z) {
  using std::sqrt;
  // A₀ = (x + y + z)/3. Each duplication maps x ← (x + λ)/4 (likewise y, z, A) with
  // λ = √x√y + √x√z + √y√z; R_F is unchanged, and A_m − x_m = 4⁻ᵐ(A₀ − x), so the deviations are
  // taken once at step 0 (no cancellation later) and only A is carried to the end.
  T A = (x + y + z) / T(3);
  const T dx = A - x, dy = A - y;
  for (int m = 0; m < kCarlsonRfSteps; ++m) {
    const T sx = sqrt(x), sy = sqrt(y), sz = sqrt(z);
    const T lambda = sx * sy + sx * sz + sy * sz;
    x = (x + lambda) * T(0.25);
    y = (y + lambda) * T(0.25);
    z = (z + lambda) * T(0.25);
    A = (A + lambda) * T(0.25);
  }
  // X = (A₀ − x)/(4ᴹ A_M), Y likewise, Z = −X − Y; E₂ = XY − Z², E₃ = XYZ;
  // R_F ≈ (1 − E₂/10 + E₃/14 + E₂²/24 − 3E₂E₃/44)/√A_M.
  constexpr double scale = carlson_detail::quarter_power(kCarlsonRfSteps);
  const T X = dx * T(scale) / A, Y = dy * T(scale) / A, Z = -(X + Y);
  const T E2 = X * Y - Z * Z, E3 = X * Y * Z;
  const T series = T(1) + E2 * (T(1.0 / 24) * E2 - T(0.1) - T(3.0 / 44) * E3) + T(1.0 / 14) * E3;
  return series / sqrt(A);
}

/// R_J(x, y, z, p) = (3/2) ∫₀^∞ dt / ((t + p) √((t + x)(t + y)(t + z))), in the domain above (p ≥ x and
/// δ ≥ 0: every e_m ≥ 0, so R_C(1, 1 + e_m) is the atan form), with `steps` duplication steps
/// (carlson_rj_steps). On a pack each lane has its own count: the loop runs `max_steps`, the largest,
/// and a lane past its own count keeps its values (so it computes the bits of its own count).
template <class T>
TUMBLE_INLINE T carlson_rj(T x, T y, T z, T p, T steps, int max_steps) {
  using std::sqrt;
  // A₀ = (x + y + z + 2p)/5, duplicated like R_F's, and p_m likewise. Step m adds
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
    const T sx = sqrt(x), sy = sqrt(y), sz = sqrt(z), sp = sqrt(p);
    const T lambda = sx * sy + sx * sz + sy * sz;
    const T d = (sp + sx) * (sp + sy) * (sp + sz);
    const T e = delta * T(scale_cubed) / (d * d);
    const T term = select(active, scale * carlson_detail::rc_one(e) / d, T(0));  // + 0 changes nothing
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
  }
  // Now scale = 4⁻ᴹ. X, Y, Z = (A₀ − ·)/(4ᴹ A_M), P = (−X − Y − Z)/2;
  // E₂ = XY + XZ + YZ − 3P², E₃ = XYZ + 2E₂P + 4P³, E₄ = (2XYZ + E₂P + 3P³)P, E₅ = XYZP²;
  // R_J ≈ 4⁻ᴹ A_M^{−3/2} (1 − 3E₂/14 + E₃/6 + 9E₂²/88 − 3E₄/22 − 9E₂E₃/52 + 3E₅/26) + 6 Σ.
  const T X = dx * scale / A, Y = dy * scale / A, Z = dz * scale / A;
  const T P = -(X + Y + Z) * T(0.5);
  const T XYZ = X * Y * Z, P2 = P * P;
  const T E2 = X * Y + X * Z + Y * Z - T(3) * P2;
  const T E3 = XYZ + T(2) * E2 * P + T(4) * P2 * P;
  const T E4 = (T(2) * XYZ + E2 * P + T(3) * P2 * P) * P;
  const T E5 = XYZ * P2;
  const T series = T(1) - T(3.0 / 14) * E2 + T(1.0 / 6) * E3 + T(9.0 / 88) * E2 * E2 - T(3.0 / 22) * E4 -
                   T(9.0 / 52) * E2 * E3 + T(3.0 / 26) * E5;
  return scale * series / (A * sqrt(A)) + T(6) * (sum + carry);
}

}  // namespace tumble
