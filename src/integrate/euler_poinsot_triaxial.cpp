// The torque-free triaxial body I₁ < I₂ < I₃ in closed form (Landau & Lifshitz, Mechanics, §37;
// Celledoni, Fassò, Säfström & Zanna, SIAM J. Sci. Comput. 30, 2008, for the attitude). Everything is written in the sorted frame {s} (ω_s = P ω_b).
//
// Invariant differences, formed from the components so that nothing large cancels:
//   d₁ = L² − 2EI₁ = I₂(I₂−I₁)ω₂² + I₃(I₃−I₁)ω₃² ≥ 0,   d₃ = 2EI₃ − L² = I₁(I₃−I₁)ω₁² + I₂(I₃−I₂)ω₂² ≥ 0,
//   d₂ = 2EI₂ − L² = I₁(I₂−I₁)ω₁² − I₃(I₃−I₂)ω₃²   (> 0: D = L²/2E < I₂, < 0: D > I₂).
//
// With u = λt + u₀ and signs σ₁, σ₃ of the components that keep their sign:
//   pole p = 3 (D > I₂): ω = (σ₁A₁ cn, σ₁σ₃A₂ sn, σ₃A₃ dn),  A₁² = d₃/(I₁(I₃−I₁)), A₂² = d₃/(I₂(I₃−I₂)),
//        A₃² = d₁/(I₃(I₃−I₁)),  λ² = (I₃−I₂)d₁/(I₁I₂I₃),  m = (I₂−I₁)d₃/((I₃−I₂)d₁),
//        k′² = (I₃−I₁)(−d₂)/((I₃−I₂)d₁);  σ₁ = +1 off the separatrix (cn changes sign).
//   pole p = 1 (D < I₂): ω = (σ₁A₁ dn, σ₁σ₃A₂ sn, σ₃A₃ cn),  A₁² = d₃/(I₁(I₃−I₁)), A₂² = d₁/(I₂(I₂−I₁)),
//        A₃² = d₁/(I₃(I₃−I₁)),  λ² = (I₂−I₁)d₃/(I₁I₂I₃),  m = (I₃−I₂)d₁/((I₂−I₁)d₃),
//        k′² = (I₃−I₁)d₂/((I₂−I₁)d₃);  σ₃ = +1 off the separatrix.
//   separatrix d₂ = 0 (m = 1): the same with sn = tanh, cn = dn = sech; both σ₁ and σ₃ are free.
//
// Orientation: R = G Rz(φ) Rx(θ)Rz(ψ) C P. C is a proper signed permutation taking the pole axis to +e₃
// with the unit body momentum μ = C Λ_s ω_s / |L| = (T₁, T₂, c dn) (third component > 0 always), so
// cos θ = c dn, (sin ψ, cos ψ) ∝ (T₁, T₂). For z-x-z angles φ̇ sin²θ = ω·μ − ω₃μ₃ (in the C frame)
// gives φ̇ = |L|/I_p + (2EI_p − L²)/(|L| I_p (1 − c² dn²u)), and with 1 − c²dn² = (1−c²)(1 + N sn²):
//   φ(t) = |L|t/I_p + κ [Π(−N; am u | m) − Π(−N; am u₀ | m)],
//   p = 3: N = I₃(I₂−I₁)/(I₁(I₃−I₂)),  κ = +(I₃−I₁)|L|/(I₁I₃λ),
//   p = 1: N = I₁(I₃−I₂)/(I₃(I₂−I₁)),  κ = −(I₃−I₁)|L|/(I₁I₃λ)
// (the small factors 2EI_p − L² and 1 − c² cancel exactly, which is what makes spin about the pole
// itself regular). G is fixed by R(0) = R₀ (φ(0) = 0).
#include <algorithm>
#include <cmath>
#include <limits>

#include "euler_poinsot_flows.hpp"
#include "tumble/integrate/jacobi_elliptic.hpp"

namespace tumble::detail {
namespace {

double sign_of(double x) { return std::signbit(x) ? -1.0 : 1.0; }

}  // namespace

TriaxialRotation::TriaxialRotation(const SortedBody& b, const Quat& q0, Regime& regime) {
  TriaxialConstants<double>& k = k_;
  k.P = b.P;
  const double I1 = b.I(0), I2 = b.I(1), I3 = b.I(2);
  const double w1 = b.w(0), w2 = b.w(1), w3 = b.w(2);
  const double d1 = I2 * (I2 - I1) * w2 * w2 + I3 * (I3 - I1) * w3 * w3;
  const double d3 = I1 * (I3 - I1) * w1 * w1 + I2 * (I3 - I2) * w2 * w2;
  const double t1 = I1 * (I2 - I1) * w1 * w1, t3 = I3 * (I3 - I2) * w3 * w3;
  const double d2 = t1 - t3;
  separatrix_ = std::abs(d2) <= EulerPoinsot::kSeparatrixTolerance * (t1 + t3);
  const int pole = d2 >= 0.0 ? 1 : 3;
  k.pole = pole;
  regime = separatrix_ ? Regime::separatrix : pole == 1 ? Regime::about_minor_axis : Regime::about_major_axis;

  const Vec3 L_s = b.I.cwiseProduct(b.w);
  const double L = L_s.norm();  // |L| in scaled units
  double lambda, m, m1, s1, s3;
  Vec3 A;
  double x, y;  // ∝ (cn u₀, sn u₀) (sech, tanh on the separatrix)
  if (pole == 3) {
    lambda = std::sqrt((I3 - I2) * d1 / (I1 * I2 * I3));
    m = (I2 - I1) * d3 / ((I3 - I2) * d1);
    m1 = (I3 - I1) * (-d2) / ((I3 - I2) * d1);
    A = Vec3(std::sqrt(d3 / (I1 * (I3 - I1))), std::sqrt(d3 / (I2 * (I3 - I2))),
             std::sqrt(d1 / (I3 * (I3 - I1))));
    s1 = separatrix_ ? sign_of(w1) : 1.0;
    s3 = sign_of(w3);
    N_ = I3 * (I2 - I1) / (I1 * (I3 - I2));
    k.kappa = (I3 - I1) * L / (I1 * I3 * lambda);
    k.c = std::sqrt(I3 * d1 / (I3 - I1)) / L;
    k.rho = std::sqrt(d3) / L;
    k.h1 = std::sqrt(I1 / (I3 - I1));
    k.h2 = std::sqrt(I2 / (I3 - I2));
    x = s1 * w1 * std::sqrt(I1 * (I3 - I1));
    y = s1 * s3 * w2 * std::sqrt(I2 * (I3 - I2));
  } else {
    lambda = std::sqrt((I2 - I1) * d3 / (I1 * I2 * I3));
    m = (I3 - I2) * d1 / ((I2 - I1) * d3);
    m1 = (I3 - I1) * d2 / ((I2 - I1) * d3);
    A = Vec3(std::sqrt(d3 / (I1 * (I3 - I1))), std::sqrt(d1 / (I2 * (I2 - I1))),
             std::sqrt(d1 / (I3 * (I3 - I1))));
    s1 = sign_of(w1);
    s3 = separatrix_ ? sign_of(w3) : 1.0;
    N_ = I1 * (I3 - I2) / (I3 * (I2 - I1));
    k.kappa = -(I3 - I1) * L / (I1 * I3 * lambda);
    k.c = std::sqrt(I1 * d3 / (I3 - I1)) / L;
    k.rho = std::sqrt(d1) / L;
    k.h1 = std::sqrt(I2 / (I2 - I1));
    k.h2 = std::sqrt(I3 / (I3 - I1));
    x = s3 * w3 * std::sqrt(I3 * (I3 - I1));
    y = s1 * s3 * w2 * std::sqrt(I2 * (I2 - I1));
  }
  k.A = b.omega_scale * Vec3(s1 * A(0), s1 * s3 * A(1), s3 * A(2));
  k.lambda = b.omega_scale * lambda;
  k.rate = b.omega_scale * L / (pole == 3 ? I3 : I1);  // |L|/I_p (rad/s)

  // Initial phase u₀ from (cn u₀, sn u₀) ∝ (x, y), and Π₀ = Π(−N; am u₀ | m).
  const double norm = std::hypot(x, y);
  SnCnDn<double> f0;
  if (separatrix_) {
    k.jacobi.K = std::numeric_limits<double>::infinity();
    // sinh u₀ = tanh u₀ / sech u₀; x > 0 unless ω₁ and ω₃ underflowed.
    k.u0 = std::asinh(y / std::max(x, std::numeric_limits<double>::min()));
    f0 = separatrix_sn_cn_dn(k.u0);
    const double rN = std::sqrt(N_);
    k.Pi0 = (k.u0 + rN * std::atan(rN * f0.sn)) / (1.0 + N_);
  } else {
    // m and k′² come from separate formulas; each is in [0, 1] in exact arithmetic.
    const JacobiElliptic jacobi(std::clamp(m, 0.0, 1.0), std::clamp(m1, 0.0, 1.0));
    k.jacobi = jacobi.constants();
    const double cn0 = norm > 0.0 ? x / norm : 1.0, sn0 = norm > 0.0 ? y / norm : 0.0;
    const double dn0 = std::sqrt(cn0 * cn0 + m1 * sn0 * sn0);
    // u₀ = F(φ₀ | m) = sn R_F(cn², dn², 1) for |φ₀| ≤ π/2; F(±π − φ) = ±2K − F(φ) beyond.
    const double F = elliptic_Pi_incomplete(0.0, sn0, cn0, dn0);
    k.u0 = cn0 >= 0.0 ? F : std::copysign(2.0 * jacobi.K(), sn0) - F;
    k.pi = EllipticPi(-N_, jacobi).constants();
    const LandenPoint<double> p0 = landen_point<double>(k.jacobi, k.u0);
    f0 = jacobi_sn_cn_dn<double>(k.jacobi, p0);
    k.Pi0 = elliptic_pi<double>(k.pi, p0);
  }

  // C P: C takes the pole axis to +e₃ with μ = (T₁, T₂, c dn); det C = +1.
  Mat3 C;
  if (pole == 3) {
    C = Vec3(s1, s1 * s3, s3).asDiagonal();
  } else {
    Mat3 cyclic;  // (v₁, v₂, v₃) ↦ (v₂, v₃, v₁)
    cyclic << 0, 1, 0, 0, 0, 1, 1, 0, 0;
    C = Vec3(s1 * s3, s3, s1).asDiagonal() * cyclic;
  }
  k.CP = Quat(Mat3(C * k.P));
  // R(0) = G B(0) C P = R₀  ⇒  G = R₀ (CP)ᵀ B(0)ᵀ.
  k.G = q0 * k.CP.conjugate() * triaxial_body_part<double>(k, 0.0, f0).conjugate();
}

}  // namespace tumble::detail
