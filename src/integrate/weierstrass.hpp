#pragma once
// Weierstrass's ℘, ζ and σ on a real lattice (real invariants g₂, g₃), for the exact gyrostat flow
// (gyrostat_flow.cpp; the derivation is docs/research/gyrostat-exact-flow.md, §§2b, 3).
//
// ℘ at real arguments comes from the Jacobi functions of the lattice's real period (DLMF 23.6):
//   Δ = g₂³ − 27g₃² > 0 (rectangular, roots e₁ > e₂ > e₃):
//       ℘(t) = e₃ + (e₁ − e₃)/sn²(λt | m),  λ = √(e₁ − e₃),  m = (e₂ − e₃)/(e₁ − e₃),  ω₁ = K/λ;
//   Δ < 0 (rhombic, e₂ real, e₁ = ē₃, H = |e₂ − e₁|):
//       ℘(t) = e₂ + H (1 + cn(2√H t | m))/(1 − cn(2√H t | m)),  m = ½ − 3e₂/(4H),  ω₁ = K/√H.
// Boost has no Weierstrass functions and no complex elliptic functions; these are written here.
// ζ and σ at complex u (the poles of the gyrostat's precession rate lie off the real axis) come from
// Jacobi's θ₁ with nome q = e^{iπτ}, τ = ω₃/ω₁, v = πu/(2ω₁) (DLMF 23.6.(i), 20.5.1):
//   ζ(u) = η₁u/ω₁ + (π/2ω₁) θ₁′(v)/θ₁(v),   ln σ(u) = η₁u²/(2ω₁) + ln θ₁(v) + const,
//   η₁ = −π²θ₁‴(0)/(12ω₁θ₁′(0)) = (π²/12ω₁)(1 − 24 Σ q²ⁿ/(1 − q²ⁿ)²),
// with θ₁ as its product, each factor's logarithm principal: for Im v > 0
//   ln θ₁(v) = const + ln(i/2) − iv + ln(1 − e^{2iv}) + Σₙ [ln(1 − q²ⁿe^{2iv}) + ln(1 − q²ⁿe^{−2iv})]
// (and the mirror for Im v < 0), every argument in the right half-plane for |Im v| < π Im τ, so ln σ
// is continuous along horizontal lines: the precession angle needs no unwrapping.
#include <complex>
#include <utility>

#include "tumble/integrate/jacobi_elliptic.hpp"

namespace tumble::detail {

using cplx = std::complex<double>;

/// The real lattice of the invariants (g₂, g₃) and ℘, ζ, σ on it.
class RealLattice {
 public:
  /// Throws InvalidArgument when Δ = g₂³ − 27g₃² is zero to rounding (a degenerate lattice: the
  /// gyrostat's separatrix or a steady spin, which gyrostat_flow.cpp handles before it gets here).
  RealLattice(long double g2, long double g3);

  bool rectangular() const { return rectangular_; }
  double period() const { return 2 * omega1_; }  ///< the real period 2ω₁
  double omega1() const { return omega1_; }
  cplx omega3() const { return omega3_; }
  double eta1() const { return eta1_; }
  /// k′² of the Jacobi functions ℘ is written with: small near a separatrix (the periods grow).
  double m1() const { return m1_; }

  /// ℘ at real t, in the form that stays finite through its poles at t ≡ 0 (mod 2ω₁):
  ///   ℘(t) − c = A/s,  ℘′(t) = B/s²,  A = (e − c)s + a,
  /// with s = sn²(λt) (rectangular, e = e₃, a = e₁ − e₃, B = −2λ³ sn cn dn) or s = 1 − cn(2√H t)
  /// (rhombic, e = e₂, A = (e₂ − c)s + H(2 − s), B = −4H^{3/2} sn dn). c is the caller's shift.
  struct Scaled {
    double s;  ///< sn² or 1 − cn, in [0, 1] or [0, 2]: zero at the pole of ℘
    cplx A;    ///< (℘ − c)s
    double B;  ///< ℘′s²
  };
  Scaled p_scaled(double t, cplx c) const;

  /// ζ(u) at complex u with |Im u| ≤ Im ω₃ (Im u ≠ 0 unless u is real and not a lattice point).
  cplx zeta(cplx u) const;
  /// ln σ(u) without its constant (which cancels in every difference the flow takes), continuous in
  /// Re u for fixed Im u ≠ 0, |Im u| ≤ Im ω₃.
  cplx log_sigma(cplx u) const;
  /// ℘(u) and ℘′(u) at complex u, |Im u| ≤ Im ω₃, Im u ≠ 0 (from θ₁: ℘ = −η₁/ω₁ − c² (ln θ₁)″(v),
  /// ℘′ = −c³ (ln θ₁)‴(v), c = π/2ω₁).
  std::pair<cplx, cplx> p_and_derivative(cplx u) const;
  double g2() const { return g2_; }
  /// ℘′(u) at a point u where ℘(u) = p: its two values are ±√(4p³ − g₂p − g₃); this is the one of
  /// u = inverse(p) (the principal Carlson R_F below), −2 √(p − e₁)√(p − e₂)√(p − e₃).
  cplx p_prime_of_inverse(cplx p) const;
  /// One u with ℘(u) = p, u = R_F(p − e₁, p − e₂, p − e₃) (principal; ℘′(u) = p_prime_of_inverse(p)).
  cplx inverse(cplx p) const;
  /// u reduced by the lattice to |Im u| ≤ Im ω₃ and 0 ≤ Re u < 2ω₁.
  cplx reduce(cplx u) const;

 private:
  /// ln θ₁(v) (without its constant) and its first three derivatives in v, Im v ≠ 0 (d[0] … d[3]).
  void log_theta1(cplx v, int derivatives, cplx d[4]) const;

  bool rectangular_;
  cplx e_[3];  ///< e₁, e₂, e₃ (rectangular: real, descending; rhombic: e₂ real, e₁ = ē₃, Im e₁ > 0)
  double g2_, omega1_, eta1_, m1_;
  cplx omega3_;
  double lambda_;                    ///< λ (rectangular) or 2√H (rhombic): the Jacobi argument per unit t
  double a_;                         ///< e₁ − e₃ (rectangular) or H (rhombic)
  double q2_;                        ///< q², real on a real lattice
  int terms_;                        ///< θ-product factors kept: |q|^(2n) below rounding
  JacobiElliptic jacobi_{0.0, 1.0};  ///< sn, cn, dn of parameter m on the real period
};

}  // namespace tumble::detail
