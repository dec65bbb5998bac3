#include "gyrostat_flow.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "free_body_taylor.hpp"
#include "tumble/error.hpp"
#include "tumble/integrate/euler_poinsot.hpp"

namespace tumble {

using detail::cplx;

namespace {

constexpr double kEps = std::numeric_limits<double>::epsilon();
constexpr cplx kI{0.0, 1.0};

/// p(x) = Σ c[k] xᵏ and its derivatives p⁽ʲ⁾(x), j = 0 … 4, for a quartic.
std::array<cplx, 5> derivatives_at(const std::array<cplx, 5>& c, cplx x) {
  std::array<cplx, 5> d{};
  std::array<cplx, 5> coef = c;
  for (int j = 0; j < 5; ++j) {
    cplx v = 0.0;
    for (int k = 4 - j; k >= 0; --k) v = v * x + coef[k];
    d[j] = v;
    for (int k = 0; k + 1 < 5 - j; ++k) coef[k] = coef[k + 1] * double(k + 1);  // differentiate
    coef[4 - j] = 0.0;
  }
  return d;
}

/// The roots of c₂x² + c₁x + c₀ (c₂ ≠ 0), without cancellation.
std::array<cplx, 2> quadratic_roots(cplx c2, cplx c1, cplx c0) {
  cplx s = std::sqrt(c1 * c1 - 4.0 * c2 * c0);
  if (std::real(std::conj(c1) * s) < 0) s = -s;
  const cplx q = -0.5 * (c1 + s);
  return {q / c2, q == 0.0 ? cplx(0.0) : c0 / q};
}

/// Rows (e₁′, e₂′, b): a right-handed frame whose third axis is the unit vector b.
Mat3 frame_from_pole(const Vec3& b) {
  const Vec3 a = std::abs(b.x()) < 0.9 ? Vec3::UnitX() : Vec3::UnitY();
  const Vec3 e1 = a.cross(b).normalized(), e2 = b.cross(e1);
  Mat3 S;
  S.row(0) = e1.transpose(), S.row(1) = e2.transpose(), S.row(2) = b.transpose();
  return S;
}

Mat3 Rz(double psi) {
  const double c = std::cos(psi), s = std::sin(psi);
  Mat3 R;
  R << c, -s, 0, s, c, 0, 0, 0, 1;
  return R;
}

}  // namespace

GyrostatFlow::GyrostatFlow(const Vec3& Lambda, const Vec3& h_b, const Quat& q0, const Vec3& omega_b0)
    : Lambda_(Lambda), h_(h_b), omega0_(omega_b0) {
  if (!(Lambda.minCoeff() > 0) || !Lambda.allFinite()) {
    throw InvalidArgument(
        fmt::format("gyrostat: principal moments must be positive and finite, got ({}, {}, {})", Lambda(0),
                    Lambda(1), Lambda(2)));
  }
  if (!h_b.allFinite() || !omega_b0.allFinite() || !q0.coeffs().allFinite() || q0.norm() == 0) {
    throw InvalidArgument(
        "gyrostat: the rotor momentum, the angular velocity and the orientation must be finite, "
        "and the quaternion non-zero");
  }
  q0_ = q0.normalized();
  M0_ = Lambda.cwiseProduct(omega_b0) + h_b;
  m_ = M0_.norm();
  two_E_ = omega_b0.dot(Lambda.cwiseProduct(omega_b0));
  // Ṁ = M × ω = 0 to the rounding of its products: a steady rotation (also ω = 0 and M = 0).
  if (M0_.cross(omega_b0).norm() <= 16 * kEps * m_ * omega_b0.norm()) {
    regime_ = Regime::steady;
    return;
  }
  // Two moments equal (to EulerPoinsot's tolerance) and h on the third axis, to rounding.
  for (int k = 0; k < 3; ++k) {
    const int i = (k + 1) % 3, j = (k + 2) % 3;
    if (std::abs(Lambda(i) - Lambda(j)) <= EulerPoinsot::kEqualMomentsTolerance * Lambda.maxCoeff() &&
        std::hypot(h_b(i), h_b(j)) <= 16 * kEps * h_b.norm()) {
      regime_ = Regime::axisymmetric;
      axis_ = k;
      return;
    }
  }
  const Vec3 n0 = M0_ / m_;
  try {
    set_up_curve(-n0);  // a first curve to sample the polhode: n stays away from −n₀ near t = 0
    set_up_curve(choose_pole());
    set_up_attitude();
    bool finite = std::isfinite(C0_) && std::isfinite(psi0_) && std::isfinite(psi_period_);
    for (const cplx& u : u_) finite = finite && std::isfinite(u.real()) && std::isfinite(u.imag());
    if (!finite) regime_ = Regime::series;  // never seen; a closed form that cannot be evaluated is not used
  } catch (const InvalidArgument&) {
    regime_ = Regime::series;  // the lattice degenerates: the separatrix to rounding
  }
}

void GyrostatFlow::set_up_curve(const Vec3& b) {
  S_ = frame_from_pole(b);
  Jinv_ = S_ * Lambda_.cwiseInverse().asDiagonal() * S_.transpose();
  h_aux_ = S_ * h_;
  const Vec3 M_aux = S_ * M0_;
  // The curve of the gyrostat (J, h′, M′₀) — this frame's data, rounded once — in long double: near a
  // steady spin or a separatrix the invariants' discriminant is a small difference, from which the
  // lattice's shape follows (weierstrass.cpp). m and 2E are this data's own.
  using LD = long double;
  using C = std::complex<LD>;
  const Eigen::Matrix<LD, 3, 1> M = M_aux.cast<LD>(), hp = h_aux_.cast<LD>();
  const Eigen::Matrix<LD, 3, 3> J = Jinv_.cast<LD>();
  const LD m = M.norm(), two_E = (M - hp).dot(J * (M - hp));
  // V(z, w) = m N(z, w) − (1 + zw) h′, N = (z + w, −i(z − w), zw − 1): M′ = V/(1 + zw) on the sphere.
  const C i(0, 1);
  const std::array<C, 3> V[2][2] = {
      {std::array<C, 3>{-hp(0), -hp(1), -m - hp(2)}, std::array<C, 3>{m, i * m, 0}},
      {std::array<C, 3>{m, -i * m, 0}, std::array<C, 3>{-hp(0), -hp(1), m - hp(2)}}};
  // The energy integral F(z, w) = Vᵀ J V − 2E (1 + zw)² = 0, J = Λ⁻¹ in the pole frame.
  std::array<std::array<C, 3>, 3> F{};
  for (int a1 = 0; a1 < 2; ++a1) {
    for (int b1 = 0; b1 < 2; ++b1) {
      for (int a2 = 0; a2 < 2; ++a2) {
        for (int b2 = 0; b2 < 2; ++b2) {
          for (int r = 0; r < 3; ++r) {
            for (int c = 0; c < 3; ++c) F[a1 + a2][b1 + b2] += V[a1][b1][r] * J(r, c) * V[a2][b2][c];
          }
        }
      }
    }
  }
  F[0][0] -= two_E, F[1][1] -= 2 * two_E, F[2][2] -= two_E;
  // ż = κ ∂F/∂w with κ = −i/(4m) (the Lie–Poisson bracket on the sphere), so ż² = P(z) = κ²(b² − 4ac)
  // with F = a(z)w² + b(z)w + c(z).
  std::array<C, 5> P{};
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) P[r + c] += F[r][1] * F[c][1] - LD(4) * F[r][2] * F[c][0];
  }
  for (C& p : P) p *= LD(-1) / (16 * m * m);
  // The invariants of P = a₀z⁴ + 4a₁z³ + 6a₂z² + 4a₃z + a₄ (real on the real motion's curve).
  const C a0 = P[4], a1 = P[3] / LD(4), a2 = P[2] / LD(6), a3 = P[1] / LD(4), a4 = P[0];
  const C g2 = a0 * a4 - LD(4) * a1 * a3 + LD(3) * a2 * a2;
  const C g3 = a0 * a2 * a4 + LD(2) * a1 * a2 * a3 - a2 * a2 * a2 - a0 * a3 * a3 - a1 * a1 * a4;
  lattice_ = detail::RealLattice(g2.real(), g3.real());
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) F_[r][c] = cplx(F[r][c]);
  }
  std::array<cplx, 5> Pd;
  for (int k = 0; k < 5; ++k) Pd[k] = cplx(P[k]);
  const Vec3 M_aux_dot = M_aux.cross(Jinv_ * (M_aux - h_aux_));
  const cplx xy(M_aux(0), M_aux(1)), xy_dot(M_aux_dot(0), M_aux_dot(1));
  const double below = m_ - M_aux(2);
  z0_ = xy / below;
  zdot0_ = (xy_dot * below + xy * M_aux_dot(2)) / (below * below);
  const std::array<cplx, 5> d = derivatives_at(Pd, z0_);
  std::copy(d.begin(), d.end(), P_);
}

cplx GyrostatFlow::z_at(double t) const {
  // The inversion formula with numerator and denominator multiplied by s² (℘ − c = A/s, ℘′ = B/s²),
  // finite through ℘'s pole at t = 0.
  const cplx c = P_[2] / 24.0;
  const detail::RealLattice::Scaled p = lattice_.p_scaled(t, c);
  const cplx N = -zdot0_ * p.B + 0.5 * P_[1] * p.A * p.s + P_[0] * P_[3] / 24.0 * (p.s * p.s);
  const cplx D = 2.0 * p.A * p.A - P_[0] * P_[4] / 48.0 * (p.s * p.s);
  return z0_ + N / D;
}

Vec3 GyrostatFlow::M_aux_at(double t) const {
  const cplx z = z_at(t);
  const double r2 = std::norm(z);
  return m_ / (1 + r2) * Vec3(2 * z.real(), 2 * z.imag(), r2 - 1);
}

Vec3 GyrostatFlow::choose_pole() const {
  // n over one period; candidates: the principal axes, the mean of n and two directions across it.
  constexpr int kSamples = 48;
  const double T = lattice_.period();
  std::array<Vec3, kSamples> n;
  Vec3 mean = Vec3::Zero();
  for (int k = 0; k < kSamples; ++k) {
    n[k] = (S_.transpose() * M_aux_at(T * (k + 1.0 / 3) / kSamples)).normalized();
    mean += n[k];
  }
  const Vec3 c = mean.norm() > 1e-8 * kSamples ? Vec3(mean.normalized()) : Vec3::UnitX();
  const Mat3 across = frame_from_pole(c);
  const Vec3 candidates[] = {Vec3::UnitX(), Vec3::UnitY(), Vec3::UnitZ(), c, across.row(0), across.row(1)};
  Vec3 best = c;
  double best_score = -1;
  for (const Vec3& b : candidates) {
    double score = 1.0;
    for (const Vec3& x : n) score = std::min(score, 1 - std::abs(x.dot(b)));
    if (score > best_score) best_score = score, best = b;
  }
  return best;
}

double GyrostatFlow::precession_rate(const Vec3& M) const {
  const Vec3 w = Jinv_ * (M - h_aux_);
  return m_ * (w.dot(M) - w(2) * M(2)) / (m_ * m_ - M(2) * M(2));
}

Mat3 GyrostatFlow::momentum_frame(const Vec3& M) {
  const Vec3 n = M.normalized();
  const Vec3 p1 = (Vec3::UnitZ() - n(2) * n).normalized(), p2 = n.cross(p1);
  Mat3 Q;
  Q.row(0) = p1.transpose(), Q.row(1) = p2.transpose(), Q.row(2) = n.transpose();
  return Q;
}

void GyrostatFlow::set_up_attitude() {
  const cplx c = P_[2] / 24.0, kappa = -kI / (4 * m_);
  const cplx PP3 = P_[0] * P_[3] / 24.0, PP4 = P_[0] * P_[4] / 48.0;
  auto numerator = [&](cplx p, cplx p_prime) { return -zdot0_ * p_prime + 0.5 * P_[1] * (p - c) + PP3; };
  auto z_of = [&](cplx p, cplx p_prime) {
    return z0_ + numerator(p, p_prime) / (2.0 * (p - c) * (p - c) - PP4);
  };
  // The four points where M′₃ = ±m with residue +i/2 (the other four, w = 0 and w = ∞, are their
  // conjugates): ℘ there from the point, u = ℘⁻¹ and of ±u the one the point is on.
  int k = 0;
  for (const cplx w : quadratic_roots(F_[0][2], F_[0][1], F_[0][0])) {  // z = 0: F(0, w) = 0
    const cplx y = kappa * (2.0 * F_[0][2] * w + F_[0][1]);             // ż there
    const cplx p = (y * zdot0_ + P_[0]) / (2.0 * z0_ * z0_) - P_[1] / (4.0 * z0_) + c;
    const cplx u = lattice_.inverse(p), pp = lattice_.p_prime_of_inverse(p);
    u_[k++] = std::abs(z_of(p, pp)) <= std::abs(z_of(p, -pp)) ? u : -u;
  }
  for (const double sign : {1.0, -1.0}) {  // z = ∞: the inversion's denominator vanishes
    const cplx p = c + sign * std::sqrt(PP4 / 2.0);
    const cplx u = lattice_.inverse(p), pp = lattice_.p_prime_of_inverse(p);
    u_[k++] = std::abs(numerator(p, pp)) >= std::abs(numerator(p, -pp)) ? u : -u;
  }
  // ℘(u*) from the point has the rounding of a few terms that may cancel, and u* = ℘⁻¹ amplifies it by
  // 1/|℘′(u*)|; Newton's method on the point's own equation (z = 0 for the first two, 1/z = D/N = 0 for
  // the others), with ℘ and ℘′ from θ₁ at the complex u, brings each uₖ to rounding (two steps; near a
  // separatrix, case near_separatrix of the tests, ψ's error over 100 s went from 2.5e-13 to 3.7e-14).
  const double g2 = lattice_.g2();
  for (int j = 0; j < 4; ++j) {
    for (int iteration = 0; iteration < 2; ++iteration) {
      const auto [p, dp] = lattice_.p_and_derivative(u_[j]);
      const cplx ddp = 6.0 * p * p - 0.5 * g2;
      const cplx N = numerator(p, dp), dN = -zdot0_ * ddp + 0.5 * P_[1] * dp;
      const cplx D = 2.0 * (p - c) * (p - c) - PP4, dD = 4.0 * (p - c) * dp;
      u_[j] -= j < 2 ? (N + (z0_ * D)) * D / (dN * D - N * dD)  // z = z₀ + N/D: z/z′
                     : D * N / (dD * N - D * dN);               // (D/N)/(D/N)′
    }
  }
  const Vec3 M_aux0 = S_ * M0_;
  C0_ = precession_rate(M_aux0);
  for (int j = 0; j < 4; ++j) {
    u_[j] = lattice_.reduce(u_[j]);
    C0_ += std::imag(lattice_.zeta(-u_[j]));
    log_sigma0_[j] = lattice_.log_sigma(-u_[j]);
  }
  const Mat3 R0 = q0_.toRotationMatrix();
  const Vec3 Ez = (R0 * M0_).normalized();
  const Vec3 a = std::abs(Ez.x()) < 0.9 ? Vec3::UnitX() : Vec3::UnitY();
  const Vec3 Ex = a.cross(Ez).normalized();
  W_.col(0) = Ex, W_.col(1) = Ez.cross(Ex), W_.col(2) = Ez;
  const Mat3 Rz0 = W_.transpose() * R0 * (momentum_frame(M_aux0) * S_).transpose();
  psi0_ = std::atan2(Rz0(1, 0), Rz0(0, 0));
  psi_period_ = precession(lattice_.period());
}

double GyrostatFlow::precession(double t) const {
  double psi = C0_ * t;
  for (int j = 0; j < 4; ++j) psi -= std::imag(lattice_.log_sigma(t - u_[j]) - log_sigma0_[j]);
  return psi;
}

double GyrostatFlow::period() const {
  return regime_ == Regime::closed_form ? lattice_.period() : std::numeric_limits<double>::infinity();
}

GyrostatFlow::State GyrostatFlow::state(double t) const {
  if (t == 0) return {q0_, omega0_};
  switch (regime_) {
    case Regime::steady: {
      const double angle = omega0_.norm() * t;
      const Quat turn = angle == 0 ? Quat::Identity() : Quat(Eigen::AngleAxisd(angle, omega0_.normalized()));
      return {(q0_ * turn).normalized(), omega0_};
    }
    case Regime::series:
      return series_state(t);
    case Regime::axisymmetric: {
      const int k = axis_, i = (k + 1) % 3;
      const double A = Lambda_(i), c = omega0_(k) - M0_(k) / A;
      const Vec3 e = Vec3::Unit(k), L_w = q0_ * M0_;
      const Quat q = Quat(Eigen::AngleAxisd(m_ * t / A, L_w / m_)) * q0_ * Quat(Eigen::AngleAxisd(c * t, e));
      const Vec3 M = Eigen::AngleAxisd(-c * t, e) * M0_;
      return {q.normalized(), (M - h_).cwiseQuotient(Lambda_)};
    }
    case Regime::closed_form:
      break;
  }
  // Whole periods first: ω repeats, ψ advances by ψ(T) − ψ(0) each.
  const double T = lattice_.period();
  const double periods = std::floor(t / T), tr = t - periods * T;
  const Vec3 M_aux = M_aux_at(tr);
  const Vec3 M = S_.transpose() * M_aux;
  const double psi = psi0_ + periods * psi_period_ + precession(tr);
  const Mat3 R = W_ * Rz(psi) * momentum_frame(M_aux) * S_;
  return {Quat(R).normalized(), (M - h_).cwiseQuotient(Lambda_)};
}

GyrostatFlow::State GyrostatFlow::series_state(double t) const {
  // Steps of at most 0.1 rad of the fastest rate the motion has (|ω| and the rotors' |Λ⁻¹h|): order 24
  // leaves a truncation of ~0.1²⁵ per step, far below rounding.
  const double rate = omega0_.norm() + h_.cwiseQuotient(Lambda_).norm();
  const int steps = std::max(1, static_cast<int>(std::ceil(std::abs(t) * rate / 0.1)));
  const FreeBodyTaylorT<double> taylor(Lambda_, h_, 24);
  FreeBodyStateT<double> s{{omega0_(0), omega0_(1), omega0_(2)}, {q0_.w(), q0_.x(), q0_.y(), q0_.z()}};
  for (int i = 0; i < steps; ++i) s = taylor.step(s, t / steps);
  return {Quat(s.q[0], s.q[1], s.q[2], s.q[3]).normalized(), Vec3(s.w[0], s.w[1], s.w[2])};
}

}  // namespace tumble
