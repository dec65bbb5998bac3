#pragma once
// Jacobi elliptic functions sn, cn, dn and the amplitude am for a parameter given as the pair
// (m, m₁) = (k², k′²), and the complete integrals K and Π from k′² through Boost's Carlson forms.
//
// Why not boost::math::jacobi_elliptic(k, u, …) and ellint_1(k): they take the modulus k alone and
// re-derive k′ = √(1 − k²) inside. Near m = 1 (the separatrix of the free rigid body, where k′² is a
// small number computed accurately from the body's state) that subtraction loses most digits of k′,
// and K ≈ ln(4/k′) and the functions near u = K inherit the loss (shared/research/numerics.md §1:
// 5e-11 relative error in a flip period against 3e-16 from k′). Here k′ is an input: the descending
// Landen/AGM algorithm (Abramowitz & Stegun 16.4) is seeded with b₀ = k′, c₀ = k, and K = R_F(0, k′², 1).
#include <cstdint>

namespace tumble {

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
  double K() const { return K_; }

  /// sn, cn, dn, am at u. The argument is first reduced to |r| ≤ K (u = 2Kj + r): the cost does not
  /// grow with |u|, and sn u = (−1)ʲ sn r, cn u = (−1)ʲ cn r, dn u = dn r, am u = jπ + am r.
  JacobiValues operator()(double u) const;

 private:
  static constexpr int kMaxSteps = 40;
  double landen_am(double r) const;  // am r by the descending Landen recursion (|r| ≤ K/2 in use)
  double m_, m1_, K_;
  int steps_ = 0;            // N, the number of AGM steps
  double a_N_ = 1.0;         // a_N, the arithmetic–geometric mean of 1 and k′
  double ratio_[kMaxSteps];  // c_n / a_n, n = 1 … N
};

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
  /// Π(n; am u | m) from the values f(u). The complete Π(n | m) (it multiplies the half-periods j) is
  /// evaluated once, correctly rounded (elliptic_Pi_complete); the incomplete part
  /// |Π(n; am r)| ≤ Π(n | m) evaluates R_F and R_J in double (≤ 3ε relative instead of 0.5ε, and
  /// 3× faster): the phase of the free rigid body then moves by at most one ulp of itself.
  double operator()(const JacobiValues& v) const;

 private:
  double n_, m_, m1_;
  double complete_ = 0.0;                                   // Π(n | m)
  double n_reflected_ = 0.0, c_linear_ = 0.0, c_Pi_ = 0.0;  // n′, m/(m−n), −n m₁/((m−n)(1−n))
};

}  // namespace tumble
