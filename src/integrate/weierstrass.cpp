#include "weierstrass.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
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

RealLattice::RealLattice(double g2, double g3) {
  const double Delta = g2 * g2 * g2 - 27 * g3 * g3;
  const double scale = std::max(std::abs(g2 * g2 * g2), 27 * g3 * g3);
  if (!std::isfinite(Delta) || !(std::abs(Delta) > 64 * 2.220446049250313e-16 * scale)) {
    throw InvalidArgument(fmt::format("a degenerate Weierstrass lattice: g2 = {}, g3 = {}", g2, g3));
  }
  rectangular_ = Delta > 0;
  if (rectangular_) {
    // 4x³ − g₂x − g₃ = 0 by its trigonometric form, x = r cos(φ − 2πj/3), r = 2√(g₂/12), and the
    // differences of the roots as products of sines (no cancellation near coincident roots).
    const double r = 2 * std::sqrt(g2 / 12);
    const double c3 = std::clamp(g3 / (r * r * r), -1.0, 1.0);  // cos 3φ, as 4x³ − 3r²x = r³ cos 3φ
    const double phi = std::acos(c3) / 3;                             // φ ∈ [0, π/3]
    e_[0] = r * std::cos(phi);
    e_[1] = r * std::cos(phi - 2 * kPi / 3);
    e_[2] = r * std::cos(phi + 2 * kPi / 3);
    const double s3 = std::sqrt(3.0) * r;
    const double e13 = s3 * std::sin(phi + kPi / 3), e23 = s3 * std::sin(phi), e12 = s3 * std::sin(kPi / 3 - phi);
    jacobi_ = JacobiElliptic(e23 / e13, e12 / e13);
    lambda_ = std::sqrt(e13);
    a_ = e13;
    const double K = jacobi_.K(), Kp = JacobiElliptic(jacobi_.m1(), jacobi_.m()).K();
    omega1_ = K / lambda_;
    omega3_ = kI * (Kp / lambda_);
    q2_ = std::exp(-2 * kPi * Kp / K);
  } else {
    // The real root by Cardano in its cancellation-free form, one Newton step; then H² = (e₂ − e₁)(e₂ − e₃)
    // = (12e₂² − g₂)/4 and e₁ = −e₂/2 + i√(H² − 9e₂²/4).
    const double p = -g2 / 4, q = -g3 / 4;
    const double A = -std::copysign(std::cbrt(std::abs(q) / 2 + std::sqrt(q * q / 4 + p * p * p / 27)), q);
    double e2 = A == 0 ? 0.0 : A - p / (3 * A);
    e2 -= (4 * e2 * e2 * e2 - g2 * e2 - g3) / (12 * e2 * e2 - g2);
    const double H2 = (12 * e2 * e2 - g2) / 4, H = std::sqrt(H2);
    const double beta = std::sqrt(std::max(0.0, H2 - 2.25 * e2 * e2));
    e_[0] = cplx(-e2 / 2, beta), e_[1] = e2, e_[2] = cplx(-e2 / 2, -beta);
    jacobi_ = JacobiElliptic(0.5 - 0.75 * e2 / H, 0.5 + 0.75 * e2 / H);
    lambda_ = 2 * std::sqrt(H);
    a_ = H;
    const double K = jacobi_.K(), Kp = JacobiElliptic(jacobi_.m1(), jacobi_.m()).K();
    omega1_ = K / std::sqrt(H);
    omega3_ = cplx(K, Kp) / (2 * std::sqrt(H));
    q2_ = -std::exp(-kPi * Kp / K);  // q = i e^{−πK′/2K}
  }
  m1_ = jacobi_.m1();
  // Factors of the θ-product to keep: the largest, |q²ⁿ e^{2|Im v|}| ≤ |q|^(2n−1), below ε/4.
  const double abs_q = std::sqrt(std::abs(q2_));
  terms_ = abs_q <= 0 ? 0 : std::min(20000, static_cast<int>(std::ceil((std::log(0.25 * 2.220446049250313e-16) / std::log(abs_q) + 1) / 2)) + 1);
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

void RealLattice::log_theta1(cplx v, cplx* log, cplx* derivative) const {
  // ln sin v and cot v on the side of the real axis v lies: e^{±2iv} is then inside the unit circle.
  const bool upper = v.imag() > 0;
  const cplx E = std::exp(upper ? 2.0 * kI * v : -2.0 * kI * v);
  const cplx sign = upper ? kI : -kI;
  *log = std::log(0.5 * sign) - sign * v + std::log(1.0 - E);
  *derivative = -sign * (1.0 + E) / (1.0 - E);
  const cplx up = std::exp(2.0 * kI * v), down = std::exp(-2.0 * kI * v);
  double qn = 1.0;
  for (int n = 1; n <= terms_; ++n) {
    qn *= q2_;
    const cplx a = qn * up, b = qn * down;
    *log += std::log(1.0 - a) + std::log(1.0 - b);
    *derivative += 2.0 * kI * (b / (1.0 - b) - a / (1.0 - a));
  }
}

cplx RealLattice::zeta(cplx u) const {
  const double c = kPi / (2 * omega1_);
  cplx log, derivative;
  log_theta1(c * u, &log, &derivative);
  return eta1_ * u / omega1_ + c * derivative;
}

cplx RealLattice::log_sigma(cplx u) const {
  cplx log, derivative;
  log_theta1(kPi / (2 * omega1_) * u, &log, &derivative);
  return eta1_ * u * u / (2 * omega1_) + log;
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
