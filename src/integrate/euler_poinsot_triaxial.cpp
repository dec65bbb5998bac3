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
#include "triaxial_setup.hpp"
#include "tumble/integrate/jacobi_elliptic.hpp"

namespace tumble::detail {

void elliptic_constants(double m, double m1, double n, JacobiConstants<double>& J, PiConstants<double>& P) {
  // m and k′² come from separate formulas; each is in [0, 1] in exact arithmetic.
  const JacobiElliptic jacobi(std::clamp(m, 0.0, 1.0), std::clamp(m1, 0.0, 1.0));
  J = jacobi.constants();
  P = EllipticPi(n, jacobi).constants();
}

double elliptic_first_kind(const JacobiConstants<double>&, double s, double c, double d, double) {
  return elliptic_Pi_incomplete(0.0, s, c, d);
}

TriaxialRotation::TriaxialRotation(const SortedBody& b, const Quat& q0, Regime& regime) {
  const TriaxialParts<double> parts = triaxial_amplitudes<double>(b, k_);
  separatrix_ = parts.separatrix;
  N_ = parts.N;
  regime = separatrix_       ? Regime::separatrix
           : parts.pole == 1 ? Regime::about_minor_axis
                             : Regime::about_major_axis;
  SnCnDn<double> f0;
  if (separatrix_) {
    // sn u₀ = tanh u₀, cn u₀ = sech u₀: sinh u₀ = y/x; x > 0 unless ω₁ and ω₃ underflowed. Π(−N; am u | 1)
    // = (u + √N atan(√N tanh u))/(1 + N).
    k_.jacobi.K = std::numeric_limits<double>::infinity();
    k_.u0 = std::asinh(parts.y / std::max(parts.x, std::numeric_limits<double>::min()));
    f0 = separatrix_sn_cn_dn(k_.u0);
    const double rN = std::sqrt(N_);
    k_.Pi0 = (k_.u0 + rN * std::atan(rN * f0.sn)) / (1.0 + N_);
  } else {
    triaxial_phase<double>(parts, k_, f0);
  }
  triaxial_frame<double>(parts, q0, f0, k_, b.P);
}

}  // namespace tumble::detail
