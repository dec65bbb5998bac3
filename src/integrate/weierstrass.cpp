#include "weierstrass.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "tumble/error.hpp"

namespace tumble::detail {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr cplx kI{0.0, 1.0};

/// Carlson's R_F(x, y, z) = ½∫₀^∞ dt/√((t+x)(t+y)(t+z)) for complex arguments off the negative real
/// axis, at most one of them zero, by duplication (B. C. Carlson, Numer. Algorithms 10 (1995) 13–26,
/// algorithm 1, with principal square roots) and the 5th-order series. Boost's ellint_rf is real only.
cplx carlson_rf(cplx x, cplx y, cplx z) {
  const cplx A0 = (x + y + z) / 3.0;
  // Carlson's stopping rule for a relative error below r = 1e-16: 4⁻ⁿQ < |Aₙ|, Q = (3r)^(−1/6) max|A₀ − ·|.
  const double Q = 380.0 * std::max({std::abs(A0 - x), std::abs(A0 - y), std::abs(A0 - z)});
  cplx A = A0;
  double scale = 1.0;  // 4⁻ⁿ
  const cplx x0 = x, y0 = y;
  for (int n = 0; n < 64 && scale * Q >= std::abs(A); ++n) {
    const cplx sx = std::sqrt(x), sy = std::sqrt(y), sz = std::sqrt(z);
    const cplx lambda = sx * sy + sx * sz + sy * sz;
    x = 0.25 * (x + lambda), y = 0.25 * (y + lambda), z = 0.25 * (z + lambda);
    A = 0.25 * (A + lambda);
    scale *= 0.25;
  }
  const cplx X = (A0 - x0) * scale / A, Y = (A0 - y0) * scale / A, Z = -X - Y;
  const cplx E2 = X * Y - Z * Z, E3 = X * Y * Z;
  return (1.0 - E2 / 10.0 + E3 / 14.0 + E2 * E2 / 24.0 - 3.0 * E2 * E3 / 44.0) / std::sqrt(A);
}

}  // namespace

RealLattice::RealLattice(long double g2, long double g3) : g2_(static_cast<double>(g2)) {
  // In long double: near a steady spin or a separatrix two roots nearly coincide, and m (or m₁), the
  // parameter of the Jacobi functions, is the small difference of the roots over their spread. The
  // invariants come in long double (gyrostat_flow.cpp), so m keeps its relative accuracy in double.
  using LD = long double;
  constexpr LD pi = std::numbers::pi_v<LD>;
  const LD Delta = g2 * g2 * g2 - 27 * g3 * g3;
  const LD scale = std::max(std::abs(g2 * g2 * g2), 27 * g3 * g3);
  if (!std::isfinite(Delta) || !(std::abs(Delta) > 64 * std::numeric_limits<LD>::epsilon() * scale)) {
    throw InvalidArgument(
        fmt::format("a degenerate Weierstrass lattice: g2 = {}, g3 = {}", double(g2), double(g3)));
  }
  rectangular_ = Delta > 0;
  if (rectangular_) {
    // 4x³ − g₂x − g₃ = 0 by its trigonometric form, x = r cos(φ − 2πj/3), r = 2√(g₂/12), and the
    // differences of the roots as products of sines (no cancellation near coincident roots).
    const LD r = 2 * std::sqrt(g2 / 12);
    const LD c3 = std::clamp(g3 / (r * r * r), LD(-1), LD(1));  // cos 3φ, as 4x³ − 3r²x = r³ cos 3φ
    const LD phi = std::acos(c3) / 3;                           // φ ∈ [0, π/3]
    e_[0] = double(r * std::cos(phi));
    e_[1] = double(r * std::cos(phi - 2 * pi / 3));
    e_[2] = double(r * std::cos(phi + 2 * pi / 3));
    const LD s3 = std::sqrt(LD(3)) * r;
    const LD e13 = s3 * std::sin(phi + pi / 3), e23 = s3 * std::sin(phi), e12 = s3 * std::sin(pi / 3 - phi);
    jacobi_ = JacobiElliptic(double(e23 / e13), double(e12 / e13));
    a_ = double(e13);
    lambda_ = std::sqrt(a_);
    const double K = jacobi_.K(), Kp = JacobiElliptic(jacobi_.m1(), jacobi_.m()).K();
    omega1_ = K / lambda_;
    omega3_ = kI * (Kp / lambda_);
    q2_ = std::exp(-2 * kPi * Kp / K);
  } else {
    // The real root by Cardano in its cancellation-free form, one Newton step; then H² = (e₂ − e₁)(e₂ − e₃)
    // = (12e₂² − g₂)/4, e₁ = −e₂/2 + iβ with β² = H² − 9e₂²/4, and m = ½ − 3e₂/4H = β²/(H(2H + 3e₂))
    // (no cancellation where β is small: a near-steady spin).
    const LD p = -g2 / 4, q = -g3 / 4;
    const LD A = -std::copysign(std::cbrt(std::abs(q) / 2 + std::sqrt(q * q / 4 + p * p * p / 27)), q);
    LD e2 = A == 0 ? LD(0) : A - p / (3 * A);
    e2 -= (4 * e2 * e2 * e2 - g2 * e2 - g3) / (12 * e2 * e2 - g2);
    const LD H2 = (12 * e2 * e2 - g2) / 4, H = std::sqrt(H2);
    const LD beta2 = std::max(LD(0), -Delta / (64 * H2 * H2));  // Δ = −64 H⁴ β²
    e_[0] = cplx(double(-e2 / 2), double(std::sqrt(beta2))), e_[1] = double(e2), e_[2] = std::conj(e_[0]);
    const LD m = e2 > 0 ? beta2 / (H * (2 * H + 3 * e2)) : LD(0.5) - LD(0.75) * e2 / H;
    const LD m1 = e2 < 0 ? beta2 / (H * (2 * H - 3 * e2)) : LD(0.5) + LD(0.75) * e2 / H;
    jacobi_ = JacobiElliptic(double(m), double(m1));
    a_ = double(H);
    lambda_ = 2 * std::sqrt(a_);
    const double K = jacobi_.K(), Kp = JacobiElliptic(jacobi_.m1(), jacobi_.m()).K();
    omega1_ = K / std::sqrt(a_);
    omega3_ = cplx(K, Kp) / (2 * std::sqrt(a_));
    q2_ = -std::exp(-kPi * Kp / K);  // q = i e^{−πK′/2K}
  }
  m1_ = jacobi_.m1();
  // Factors of the θ-product to keep: the largest, |q²ⁿ e^{2|Im v|}| ≤ |q|^(2n−1), below ε/4.
  const double abs_q = std::sqrt(std::abs(q2_));
  terms_ = abs_q <= 0
               ? 0
               : std::min(20000, static_cast<int>(std::ceil(
                                     (std::log(0.25 * 2.220446049250313e-16) / std::log(abs_q) + 1) / 2)) +
                                     1);
  // η₁ = (π²/12ω₁)(1 − 24 Σ q²ⁿ/(1 − q²ⁿ)²): θ₁‴(0)/θ₁′(0) from the product's v² coefficient.
  double sum = 0.0, qn = 1.0;
  for (int n = 1; n <= terms_; ++n) {
    qn *= q2_;
    sum += qn / ((1 - qn) * (1 - qn));
  }
  eta1_ = kPi * kPi / (12 * omega1_) * (1 - 24 * sum);
}

RealLattice::Scaled RealLattice::p_scaled(double t, cplx c) const {
  const JacobiValues v = jacobi_(lambda_ * t);
  if (rectangular_) {
    const double s = v.sn * v.sn;
    return {s, (e_[2] - c) * s + a_, -2 * a_ * lambda_ * v.sn * v.cn * v.dn};
  }
  const double s = v.cn >= 0 ? v.sn * v.sn / (1 + v.cn) : 1 - v.cn;  // 1 − cn without cancellation
  return {s, (e_[1] - c) * s + a_ * (2 - s), -4 * a_ * std::sqrt(a_) * v.sn * v.dn};
}

void RealLattice::log_theta1(cplx v, int derivatives, cplx d[4]) const {
  // ln sin v on the side of the real axis v lies, where E = e^{±2iv} is inside the unit circle:
  //   ln sin v = ln(±i/2) ∓ iv + ln(1 − E),  (ln sin)′ = ∓i(1 + E)/(1 − E) = cot v,
  //   (ln sin)″ = −csc²v = 4E/(1 − E)²,  (ln sin)‴ = ±8iE(1 + E)/(1 − E)³.
  const bool upper = v.imag() > 0;
  const cplx E = std::exp(upper ? 2.0 * kI * v : -2.0 * kI * v);
  const cplx sign = upper ? kI : -kI, one_minus = 1.0 - E;
  d[0] = std::log(0.5 * sign) - sign * v + std::log(one_minus);
  d[1] = -sign * (1.0 + E) / one_minus;
  if (derivatives >= 2) {
    d[2] = 4.0 * E / (one_minus * one_minus);
    d[3] = 2.0 * sign * d[2] * (1.0 + E) / one_minus;
  }
  // Each factor ln(1 − X), X = q²ⁿe^{±2iv} (X′ = ±2iX): derivatives ∓2iX/(1 − X), 4X/(1 − X)²,
  // ±8iX(1 + X)/(1 − X)³.
  const cplx up = std::exp(2.0 * kI * v), down = std::exp(-2.0 * kI * v);
  double qn = 1.0;
  for (int n = 1; n <= terms_; ++n) {
    qn *= q2_;
    for (const auto& [X, s] : {std::pair{qn * up, 1.0}, std::pair{qn * down, -1.0}}) {
      const cplx r = 1.0 / (1.0 - X);
      d[0] += std::log(1.0 - X);
      d[1] -= s * 2.0 * kI * X * r;
      if (derivatives >= 2) {
        d[2] += 4.0 * X * r * r;
        d[3] += s * 8.0 * kI * X * (1.0 + X) * r * r * r;
      }
    }
  }
}

cplx RealLattice::zeta(cplx u) const {
  const double c = kPi / (2 * omega1_);
  cplx d[4];
  log_theta1(c * u, 1, d);
  return eta1_ * u / omega1_ + c * d[1];
}

cplx RealLattice::log_sigma(cplx u) const {
  cplx d[4];
  log_theta1(kPi / (2 * omega1_) * u, 1, d);
  return eta1_ * u * u / (2 * omega1_) + d[0];
}

std::pair<cplx, cplx> RealLattice::p_and_derivative(cplx u) const {
  const double c = kPi / (2 * omega1_);
  cplx d[4];
  log_theta1(c * u, 3, d);
  return {-eta1_ / omega1_ - c * c * d[2], -c * c * c * d[3]};
}

cplx RealLattice::p_prime_of_inverse(cplx p) const {
  return -2.0 * std::sqrt(p - e_[0]) * std::sqrt(p - e_[1]) * std::sqrt(p - e_[2]);
}

cplx RealLattice::inverse(cplx p) const { return carlson_rf(p - e_[0], p - e_[1], p - e_[2]); }

cplx RealLattice::reduce(cplx u) const {
  const double period = 2 * omega1_;
  u -= std::nearbyint(u.imag() / (2 * omega3_.imag())) * 2.0 * omega3_;
  return u - std::floor(u.real() / period) * period;
}

}  // namespace tumble::detail
