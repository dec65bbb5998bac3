#pragma once
// Jacobi elliptic functions sn, cn, dn and the amplitude am for a parameter given as the pair
// (m, m₁) = (k², k′²), the complete integrals K and Π from k′², and the incomplete Π(n; am u | m).
//
// Why not boost::math::jacobi_elliptic(k, u, …) and ellint_1(k): they take the modulus k alone and
// re-derive k′ = √(1 − k²) inside. Near m = 1 (the separatrix of the free rigid body, where k′² is a
// small number computed accurately from the body's state) that subtraction loses most digits of k′,
// and K ≈ ln(4/k′) and the functions near u = K inherit the loss (measured when tumble's solution was
// written: 5e-11 relative error in a flip period against 3e-16 from k′). Here k′ is an input: the AGM of the
// descending Landen transformation is seeded with b₀ = k′, c₀ = k, and K = R_F(0, k′², 1) (Boost).
//
// The evaluation itself is written once, as templates on the number type T (double for one argument, a
// SIMD pack for one body per lane: math/lanes.hpp), branch-free on values: landen_point, jacobi_sn_cn_dn
// and elliptic_pi below. JacobiElliptic and EllipticPi evaluate them on double; the batched splitting
// drift (src/integrate/splitting.cpp) on packs.
#include <cmath>
#include <cstdint>
#include <numbers>
#include <type_traits>
#include <utility>

#include "tumble/math/carlson.hpp"
#include "tumble/math/lanes.hpp"

namespace tumble {

/// Most AGM steps of any parameter: m₁ = 1e-300 needs 15 (the ratio b/a doubles its exponent's square
/// root per step, then converges quadratically).
inline constexpr int kMaxLandenSteps = 40;

/// What the Jacobi functions of one parameter need at every argument (one lane per body for a pack).
template <class T>
struct JacobiConstants {
  T K = T(0);                ///< K(m)
  T inv_2K = T(0);           ///< 1/(2K): the half-periods in u, by a product (0 where K = ∞)
  T a_N = T(1);              ///< the arithmetic–geometric mean of 1 and k′
  T m1 = T(1), k1 = T(1);    ///< k′² and k′
  int steps = 0;             ///< AGM steps N: for a pack, the largest of its lanes'
  T ratio[kMaxLandenSteps];  ///< k_n = c_n/a_n, n = 1 … N; a lane with fewer steps has zeros after its own
};

/// The argument u reduced and reflected, and sn, cn, dn at the point the Landen recursion evaluates.
template <class T>
struct LandenPoint {
  using Mask = decltype(std::declval<T>() < std::declval<T>());
  T j;             ///< half-periods removed (an integer): u = 2Kj + r
  T r;             ///< |r| ≤ K
  Mask reflected;  ///< |r| > K/2: the point is v = K − |r| (else r itself)
  T arg;           ///< that point, r or v
  T s, c, d;       ///< sn, cn, dn at arg
};

/// u = 2Kj + r, the point arg (r, or K − |r| beyond K/2) and sn, cn, dn there by the descending Landen
/// (Gauss) transformation (DLMF 22.7.1–3), whose moduli are the AGM's k_n = c_n/a_n: with s, c, d the
/// functions of modulus k_n at z/(1 + k_n),
///   sn(z | k_{n−1}) = (1 + k_n) s/(1 + k_n s²),  cn(z | k_{n−1}) = c d/(1 + k_n s²),
///   dn(z | k_{n−1}) = (1 − k_n s²)/(1 + k_n s²),
/// from sin and cos of z_N = a_N·arg at the last level (k_N < ε: sn = sin, dn = 1 to ε²), since
/// Π(1 + k_n) = 1/a_N; sn and cn are then scaled onto sn² + cn² = 1. One sin and one cos and a few products per level, where the angle form of the same
/// recursion (A&S 16.4) took a sin and an asin per level (measured: 5× the cost on packs). Products keep
/// cn's relative accuracy where it is small; dn at arg is then formed as √(cn² + k′² sn²) (no cancellation,
/// where 1 − k_n s² would lose ε/√k′). A lane with fewer AGM steps than the pack's count has k_n = 0 in
/// the extra levels, which leave s, c and d = 1 unchanged, bit for bit: the lane computes what its own
/// count gives.
template <class T>
TUMBLE_INLINE LandenPoint<T> landen_point(const JacobiConstants<T>& J, T u) {
  using std::abs, std::fma, std::nearbyint, std::sqrt;
  LandenPoint<T> p;
  p.j = nearbyint(u * J.inv_2K);   // where u/(2K) is within its rounding of j + ½, either j serves
  p.r = fma(-T(2) * J.K, p.j, u);  // rounds 2Kj − u once
  const T r_abs = abs(p.r);
  p.reflected = r_abs > T(0.5) * J.K;
  p.arg = select(p.reflected, J.K - r_abs, p.r);
  const T z = J.a_N * p.arg;
  const auto [sin_z, cos_z] = sincos(z);
  // The levels keep s, c, d as S/D, C/D, E/D over one denominator D, so that a level takes no
  // division (on packs the divider bounds the flow): with ks² = kS²/D²,
  //   S ← (1 + k) S D,  C ← C E,  E ← D² − kS²,  D ← D² + kS².
  // D = D²(1 + k s²) squares what the levels above left, but those have the small k (they come first),
  // and the levels of k near 1 are squared least: D stays below 1e81 even at k′² = 5e-324 with s = 1
  // (the largest D), far from overflow. A level of k = 0 (a lane's padding above its own count) leaves
  // S, C and E = D = 1 as they are, bit for bit.
  T S = sin_z, C = cos_z, E = T(1), D = T(1);
  for (int n = J.steps; n >= 1; --n) {
    const T k = J.ratio[n - 1], D2 = D * D, kS2 = k * S * S;
    S = (T(1) + k) * S * D;
    C = C * E;
    E = D2 - kS2;
    D = D2 + kS2;
  }
  // Each level rounds S and C apart, so sn² + cn² strays from 1 by about an ε a level; dividing by
  // their norm (D cancels) puts the pair back on the circle (and dn² + m sn² = 1 with it), to ~2ε as
  // sin and cos of one angle are.
  const T inv_norm = T(1) / sqrt(S * S + C * C);
  p.s = S * inv_norm;
  p.c = C * inv_norm;
  // dn = √(1 − m sn²) = √(cn² + k′² sn²): a sum of squares, no cancellation.
  p.d = sqrt(p.c * p.c + J.m1 * p.s * p.s);
  return p;
}

template <class T>
struct SnCnDn {
  T sn, cn, dn;
};

/// sn, cn, dn at u from its Landen point. Reflected: r = ±(K − v), sn r = ±cn v/dn v, cn r = k′ sn v/dn v,
/// dn r = k′/dn v (A&S 16.8), all to full relative accuracy where cn r and dn r are small; then
/// sn u = (−1)ʲ sn r, cn u = (−1)ʲ cn r, dn u = dn r.
template <class T>
TUMBLE_INLINE SnCnDn<T> jacobi_sn_cn_dn(const JacobiConstants<T>& J, const LandenPoint<T>& p) {
  using std::copysign, std::floor;
  const T inv_d = T(1) / p.d;  // one division for the three (on packs the divider bounds the flow)
  const T sn_r = select(p.reflected, copysign(p.c * inv_d, p.r), p.s);
  const T cn_r = select(p.reflected, J.k1 * p.s * inv_d, p.c);
  const T dn = select(p.reflected, J.k1 * inv_d, p.d);
  const T half_j = T(0.5) * p.j;
  const T sign = select(floor(half_j) != half_j, T(-1), T(1));  // (−1)ʲ
  return {sign * sn_r, sign * cn_r, dn};
}

/// m = 1 (k′ = 0, the separatrix of the free rigid body): sn = tanh u, cn = dn = sech u, no period.
inline SnCnDn<double> separatrix_sn_cn_dn(double u) {
  const double sech = 1.0 / std::cosh(u);
  return {std::tanh(u), sech, sech};
}

/// What Π(n; am u | m) of one n needs at every argument (EllipticPi below).
template <class T>
struct PiConstants {
  T n = T(0);            ///< the characteristic, ≤ 0
  T n_reflected = T(0);  ///< n′ = (m − n)/(1 − n)
  T c_linear = T(1);     ///< m/(m − n)
  T c_Pi = T(0);         ///< −n m₁/((m − n)(1 − n))
  T complete = T(0);     ///< Π(n | m)
  T rj_steps = T(8);     ///< carlson_rj_steps(−n, m₁): R_J's duplication steps (enough for n′ too)
  int rj_max_steps = 8;  ///< for a pack, the largest of its lanes'
};

/// Π(n; am u | m) = 2jΠ(n) + Π(n; am r), continuous in u, from the Landen point of u (EllipticPi).
/// The incomplete integral at the point (s, c, d) = sn, cn, dn there (|am| ≤ π/2) is
///   s R_F(c², d², 1) + (n/3) s³ R_J(c², d², 1, 1 − n s²)          (DLMF 19.25.14),
/// with n, or n′ where reflected: Π(n; am(K − v)) = Π(n) − (m/(m−n)) v − c_Π Π(n′; am v).
/// Its first term is F(am a | m) at the point's argument a (|a| ≤ K/2, on the principal branch of
/// am), which is a itself: the argument is taken for it, exactly, instead of R_F (a third of the cost,
/// and R_F would only return a to its rounding).
template <class T>
TUMBLE_INLINE T elliptic_pi(const PiConstants<T>& P, const LandenPoint<T>& p) {
  using std::copysign;
  const T n = select(p.reflected, P.n_reflected, P.n);
  const T c2 = p.c * p.c, d2 = p.d * p.d, s2 = p.s * p.s;
  const T incomplete = p.arg + n * T(1.0 / 3) * p.s * s2 *
                                   carlson_rj_with_roots<T>(c2, d2, T(1), p.c, p.d, T(1), T(1) - n * s2,
                                                            P.rj_steps, P.rj_max_steps);
  const T periods = T(2) * p.j * P.complete;
  return periods + select(p.reflected, copysign(P.complete - (P.c_linear * p.arg + P.c_Pi * incomplete), p.r),
                          incomplete);
}

/// sn, cn, dn and am at one argument u, written u = 2K·j + r with |r| ≤ K (j = 0 when m₁ = 0).
/// Where |r| > K/2 the functions are evaluated at v = K − |r| and reflected (sn r = ±cd v,
/// cn r = k′ sd v, dn r = k′ nd v): near r = ±K, cn and dn are small and the angle am r ≈ ±π/2
/// would give them (and Π(n; am r), whose φ-derivative is ∝ 1/dn) only absolute accuracy.
struct JacobiValues {
  double sn = 0.0, cn = 1.0, dn = 1.0;                 ///< at u
  double am = 0.0;                                     ///< am u, continuous in u: jπ + am r
  double j = 0.0;                                      ///< half-periods removed (an integer)
  double r = 0.0;                                      ///< u − 2Kj
  double sn_r = 0.0, cn_r = 1.0;                       ///< sn r, cn r (dn r = dn u)
  bool reflected = false;                              ///< |r| > K/2: the values below are set
  double v = 0.0, sn_v = 0.0, cn_v = 1.0, dn_v = 1.0;  ///< v = K − |r| and sn, cn, dn there
};

/// The Jacobi elliptic functions of one parameter m ∈ [0, 1], set up once (the AGM sequence) and
/// evaluated at many arguments. m = 0 gives sin, cos, 1; m = 1 (m₁ = 0) gives tanh, sech, sech and
/// am = gd u (K = ∞, no reduction).
class JacobiElliptic {
 public:
  /// m = k² and m₁ = 1 − m = k′², both given so that neither is derived from the other by subtraction.
  /// Throws InvalidArgument unless both lie in [0, 1] and m + m₁ = 1 to 1e-12.
  JacobiElliptic(double m, double m1);

  double m() const { return m_; }
  double m1() const { return m1_; }
  /// K(m) = R_F(0, k′², 1) (Carlson; +∞ when m₁ = 0). sn, cn have period 4K, dn period 2K.
  double K() const { return c_.K; }

  /// sn, cn, dn, am at u. The argument is first reduced to |r| ≤ K (u = 2Kj + r): the cost does not
  /// grow with |u|, and sn u = (−1)ʲ sn r, cn u = (−1)ʲ cn r, dn u = dn r, am u = jπ + am r.
  JacobiValues operator()(double u) const;

  /// The constants of landen_point (m < 1 only: m = 1 has no period and uses tanh and sech).
  const JacobiConstants<double>& constants() const { return c_; }

 private:
  double m_, m1_;
  JacobiConstants<double> c_;
};

/// Bulirsch's cel(k_c, p, a, b) = ∫₀^{π/2} (a cos²θ + b sin²θ) dθ / ((cos²θ + p sin²θ) √(cos²θ + k_c² sin²θ))
/// (Numer. Math. 13 (1969) 305; Numerical Recipes §6.11) with k_c = k′ = √m₁, p = 1 − n > 0, a = b = 1:
/// Π(n | m). A Gauss (AGM-like) transformation, quadratically convergent: it stops when the test
/// quantity agrees to `tolerance` (√ε of L), so that the last step leaves ~ε. On long double for
/// elliptic_Pi_complete; on dual numbers for the derivatives of Π(n | m) with respect to n and m.
template <class L>
L bulirsch_Pi_complete(const L& n, const L& m1, const L& tolerance) {
  using std::abs, std::sqrt;
  L kc = sqrt(m1), p = sqrt(L(1) - n);
  L a = L(1), b = L(1) / p, e = kc, em = L(1);
  for (int i = 0; i < 64; ++i) {  // ≤ 12 steps for m₁ ≥ 1e-300
    const L f = a;
    a += b / p;
    L g = e / p;
    b += f * g;
    b += b;
    p += g;
    g = em;
    em += kc;
    if (abs(g - kc) <= g * tolerance) break;
    kc = L(2) * sqrt(e);
    e = kc * em;
  }
  L half_pi;
  if constexpr (std::is_floating_point_v<L>) {
    half_pi = std::numbers::pi_v<L> / 2;
  } else {
    half_pi = L(std::numbers::pi / 2);
  }
  return half_pi * (b + a * em) / (em * (em + p));
}

/// The complete integral of the third kind, Π(n | m) = ∫₀^{π/2} dθ / ((1 − n sin²θ) √(1 − m sin²θ)),
/// from k′² = m₁ (Bulirsch's cel(k′, 1 − n, 1, 1) in long double: correctly rounded, also for n ≪ −1
/// where the Carlson form R_F(0, m₁, 1) + (n/3) R_J(0, m₁, 1, 1 − n) cancels); n < 1, m₁ ≥ 0 (+∞ at 0).
double elliptic_Pi_complete(double n, double m1);

/// The incomplete integral Π(n; φ | m) for |φ| ≤ π/2, given s = sin φ, c = cos φ and d = √(1 − m s²):
/// s R_F(c², d², 1) + (n/3) s³ R_J(c², d², 1, 1 − n s²) (n < 1). With n = 0 it is F(φ | m).
double elliptic_Pi_incomplete(double n, double s, double c, double d);

/// Π(n; am u | m) = ∫₀ᵘ du′ / (1 − n sn²u′) for all real u and one n ≤ 0, continuous in u:
/// 2jΠ(n) + Π(n; am r), and for |r| > K/2 (am r near ±π/2, where Π(n; φ) has slope 1/((1 − n s²) d)
/// that grows like 1/k′) the reflection about K, with n′ = (m − n)/(1 − n) ∈ [0, 1):
///   Π(n; am(K − v)) = Π(n) − ∫₀ᵛ dn²/((1−n) − (m−n) sn²) = Π(n) − (m/(m−n)) v − (−n m₁/((m−n)(1−n))) Π(n′; am v).
class EllipticPi {
 public:
  /// Throws InvalidArgument unless n ≤ 0 (the free rigid body needs n = −N ≤ 0).
  EllipticPi(double n, const JacobiElliptic& f);
  /// Π(n; am u | m) from the values f(u) (elliptic_pi). The complete Π(n | m) (it multiplies the
  /// half-periods j) is evaluated once, correctly rounded (elliptic_Pi_complete); the incomplete part
  /// |Π(n; am r)| ≤ Π(n | m) is the argument plus an R_J term in double (math/carlson.hpp, a few ε
  /// relative against 0.5ε): the phase of the free rigid body then moves by at most one ulp of itself.
  double operator()(const JacobiValues& v) const;

  const PiConstants<double>& constants() const { return c_; }

 private:
  PiConstants<double> c_;
};

}  // namespace tumble
