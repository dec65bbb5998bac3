// Jacobi elliptic functions from (k, k′) by the descending Landen transformation (A&S 16.4), and
// Carlson forms of the third-kind integral. See jacobi_elliptic.hpp for why k′ is an input.
#include "tumble/integrate/jacobi_elliptic.hpp"

#include <boost/math/special_functions/ellint_rf.hpp>
#include <boost/math/special_functions/ellint_rj.hpp>
#include <cmath>
#include <limits>
#include <numbers>
#include <string>

#include "tumble/error.hpp"

namespace tumble {

JacobiElliptic::JacobiElliptic(double m, double m1) : m_(m), m1_(m1) {
  if (!(m >= 0.0 && m <= 1.0 && m1 >= 0.0 && m1 <= 1.0 && std::abs(m + m1 - 1.0) <= 1e-12)) {
    throw InvalidArgument("JacobiElliptic: the parameter m = " + std::to_string(m) +
                          " and m1 = 1 - m = " + std::to_string(m1) + " must lie in [0, 1] and add up to 1");
  }
  if (m1 == 0.0) {  // m = 1: sn = tanh, cn = dn = sech, no period
    c_.K = std::numeric_limits<double>::infinity();
    return;
  }
  c_.K = boost::math::ellint_rf(0.0, m1, 1.0);
  c_.inv_2K = 0.5 / c_.K;
  c_.m1 = m1;
  c_.k1 = std::sqrt(m1);
  // AGM: a₀ = 1, b₀ = k′, c₀ = k; aₙ = (aₙ₋₁ + bₙ₋₁)/2, bₙ = √(aₙ₋₁bₙ₋₁), and cₙ = (aₙ₋₁ − bₙ₋₁)/2
  // written as cₙ = cₙ₋₁²/(4aₙ) (since aₙ² − bₙ² = cₙ²), which never subtracts close numbers.
  double a = 1.0, b = std::sqrt(m1), c = std::sqrt(m);
  const double eps = std::numeric_limits<double>::epsilon();
  while (c > eps * a) {
    if (c_.steps == kMaxLandenSteps)
      throw Error("JacobiElliptic: the AGM did not converge (m = " + std::to_string(m) + ")");
    const double a_next = 0.5 * (a + b);
    c = c * c / (4.0 * a_next);
    b = std::sqrt(a * b);
    a = a_next;
    c_.ratio[c_.steps++] = c / a;
  }
  c_.a_N = a;
}

JacobiValues JacobiElliptic::operator()(double u) const {
  JacobiValues v;
  if (m1_ == 0.0) {
    // m = 1: sn = tanh u, cn = dn = sech u, am u = gd u = 2 atan(tanh(u/2)).
    const SnCnDn<double> f = separatrix_sn_cn_dn(u);
    v.sn = v.sn_r = f.sn;
    v.cn = v.cn_r = v.dn = f.cn;
    v.am = 2.0 * std::atan(std::tanh(0.5 * u));
    return v;
  }
  const LandenPoint<double> p = landen_point<double>(c_, u);
  const SnCnDn<double> f = jacobi_sn_cn_dn<double>(c_, p);
  v.sn = f.sn, v.cn = f.cn, v.dn = f.dn;
  v.j = p.j, v.r = p.r;
  v.reflected = p.reflected;
  const double sign = std::fmod(p.j, 2.0) != 0.0 ? -1.0 : 1.0;  // (−1)ʲ, undone: sn r, cn r
  v.sn_r = sign * f.sn, v.cn_r = sign * f.cn;
  double phi = std::atan2(p.s, p.c);  // am r, |am r| ≤ π/2
  if (p.reflected) {
    v.v = p.arg, v.sn_v = p.s, v.cn_v = p.c, v.dn_v = p.d;
    phi = std::copysign(std::atan2(p.c, c_.k1 * p.s), p.r);
  }
  v.am = v.j * std::numbers::pi + phi;
  return v;
}

double elliptic_Pi_complete(double n, double m1) {
  // Bulirsch's cel in long double (bulirsch_Pi_complete, jacobi_elliptic.hpp): against 50-digit values
  // on 3000 (n, m₁) with n from −10¹⁶ to 1 and m₁ down to 1e-300: ≤ 0.5ε (correctly rounded), where
  // the Carlson sum R_F(0, k′², 1) + (n/3) R_J(0, k′², 1, 1 − n) (DLMF 19.25.2) cancels for n ≪ −1
  // (465ε at n = −10³) and costs 30× more.
  if (m1 == 0.0) return std::numeric_limits<double>::infinity();  // m = 1: log-divergent
  using L = long double;
  return static_cast<double>(
      bulirsch_Pi_complete<L>(L(n), L(m1), std::sqrt(std::numeric_limits<L>::epsilon())));
}

double elliptic_Pi_incomplete(double n, double s, double c, double d) {
  // Π(n; φ | m) = s R_F(c², Δ², 1) + (n/3) s³ R_J(c², Δ², 1, 1 − n s²), s = sin φ, c = cos φ,
  // Δ² = 1 − m s² (DLMF 19.25.14), valid for |φ| ≤ π/2. With φ = am r: s = sn r, c = cn r, Δ = dn r.
  if (s == 0.0) return 0.0;
  const double c2 = c * c, d2 = d * d, s2 = s * s;
  const double F = s * boost::math::ellint_rf(c2, d2, 1.0);
  // n = 0 (F itself): the R_J term is ±0 and adding it changes no bit; skip the evaluation.
  if (n == 0.0) return F;
  return F + n / 3.0 * s * s2 * boost::math::ellint_rj(c2, d2, 1.0, 1.0 - n * s2);
}

}  // namespace tumble

namespace tumble {

EllipticPi::EllipticPi(double n, const JacobiElliptic& f) {
  if (!(n <= 0.0)) {
    throw InvalidArgument("EllipticPi: the characteristic n = " + std::to_string(n) + " must be <= 0");
  }
  const double m = f.m(), m1 = f.m1();
  if (m1 == 0.0) throw InvalidArgument("EllipticPi: m = 1 has no complete integral; use the closed form");
  c_.n = n;
  c_.complete = elliptic_Pi_complete(n, m1);
  c_.rj_max_steps = carlson_rj_steps(-n, m1);
  c_.rj_steps = c_.rj_max_steps;
  const double b = m - n;  // m − n ≥ 0; zero only for m = n = 0, where Π = u and no reflection term
  if (b > 0.0) {
    c_.n_reflected = b / (1.0 - n);
    c_.c_linear = m / b;
    c_.c_Pi = -n * m1 / (b * (1.0 - n));
  } else {
    c_.c_linear = 1.0;
  }
}

double EllipticPi::operator()(const JacobiValues& v) const {
  // The Landen point of v's argument, as landen_point left it (JacobiElliptic::operator()).
  LandenPoint<double> p;
  p.j = v.j, p.r = v.r, p.reflected = v.reflected;
  p.arg = v.reflected ? v.v : v.r;
  p.s = v.reflected ? v.sn_v : v.sn_r;
  p.c = v.reflected ? v.cn_v : v.cn_r;
  p.d = v.reflected ? v.dn_v : v.dn;
  return elliptic_pi<double>(c_, p);
}

}  // namespace tumble
