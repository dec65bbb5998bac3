#pragma once
// The exact motion of a torque-free gyrostat (Zhukovsky–Volterra): a rigid body carrying rotors whose
// motors hold their speeds, so that their momentum h relative to the body is constant in its axes.
//
// In principal axes, with M = Λω + h the total angular momentum in the body frame:
//   Ṁ = M × ω,  Ṙ = R[ω]×,  ω = Λ⁻¹(M − h);
// |M| = m, 2E = ωᵀΛω and L = R M are constant. The derivation is docs/research/gyrostat-exact-flow.md
// (checked there at 40 digits against a Taylor-series integrator); in short:
//   - the stereographic coordinate z = (M′₁ + iM′₂)/(m − M′₃) of M′ = S M (S turns a "pole" axis b
//     of the body onto e₃) obeys ż² = P(z), a quartic, so (Whittaker & Watson §20.6)
//       z(t) = z₀ + [−ż₀℘′(t) + ½P′(z₀)(℘(t) − P″(z₀)/24) + P(z₀)P‴(z₀)/24]
//                 / [2(℘(t) − P″(z₀)/24)² − P(z₀)P⁗(z₀)/48],
//     ℘ = ℘(t; g₂, g₃) with P's invariants g₂, g₃, which are real: ω(t) is rational in ℘(t), ℘′(t);
//   - the attitude is R(t) = W Rz(ψ(t)) Q(n′(t)) S, W a world frame with e₃ along L, Q the frame of
//     n′ = M′/m, and the precession rate ψ̇ = m(ω′·M′ − ω′₃M′₃)/(m² − M′₃²) is elliptic in t with
//     simple poles where M′₃ = ±m, residues ±i/2, so
//       ψ(t) = ψ₀ + C₀t − Σₖ Im[ln σ(t − uₖ) − ln σ(−uₖ)]
//     over the four points uₖ of the curve where z = 0 or z = ∞ (Abel's map: ℘(uₖ) from the point,
//     uₖ = ℘⁻¹ by Carlson's R_F).
// No regime needs a branch of its own (h along an axis, h = 0, any ordering of the moments) but those
// where the lattice degenerates: a steady spin (Ṁ = 0: ω constant, R = R₀ exp(t[ω]×)); an
// axisymmetric body (A, A, C about axis k) with h along its axis, where ω = M/A + c e_k with
// c = ω_k − M_k/A constant, so M_b turns about e_k at −c and R(t) = Rot(L, |L|t/A) R₀ Rot(e_k, ct)
// (the classical dual-spin satellite); and the separatrix between polhode families to rounding, where
// the motion is integrated by its Taylor series instead (series: exact to rounding per step, its cost
// growing with t).
#include <array>

#include "tumble/math/types.hpp"
#include "weierstrass.hpp"

namespace tumble {

class GyrostatFlow {
 public:
  enum class Regime {
    closed_form,   ///< the elliptic solution above
    steady,        ///< Ṁ = 0: a uniform rotation
    axisymmetric,  ///< two equal moments, h on the third axis: ω = M/A + c e_k, a regular precession
    series,        ///< a degenerate lattice (separatrix): the Taylor series, step by step
  };

  /// Principal moments `Lambda` (kg·m², > 0), rotor momentum `h_b` (kg·m²/s, principal axes, constant),
  /// orientation q0 (body → world) and ω_b(0). Throws InvalidArgument for non-positive or non-finite
  /// moments, non-finite h or ω, or a zero quaternion.
  /// The stereographic coordinate's pole b is the best of a few candidates over a whole polhode: the
  /// formulas lose accuracy as 1/(1 − |n·b|) where the momentum's direction n = M/m passes near ±b.
  GyrostatFlow(const Vec3& Lambda, const Vec3& h_b, const Quat& q0, const Vec3& omega_b0);

  struct State {
    Quat q;        ///< orientation (body → world)
    Vec3 omega_b;  ///< body angular velocity (rad/s)
  };
  /// The state at t (any real t; negative runs the motion backwards).
  State state(double t) const;
  Vec3 omega_b(double t) const { return state(t).omega_b; }
  Quat q(double t) const { return state(t).q; }
  Regime regime() const { return regime_; }
  /// The period of ω_b(t) (+∞ unless closed_form).
  double period() const;

 private:
  /// The curve and ℘ for the pole b: everything ω needs.
  void set_up_curve(const Vec3& b);
  /// The poles of ψ̇, C₀, ψ₀ and the precession over one period: what the attitude needs.
  void set_up_attitude();
  Vec3 choose_pole() const;
  /// z at t ∈ [0, T) and M′ (pole frame) from it.
  detail::cplx z_at(double t_reduced) const;
  Vec3 M_aux_at(double t_reduced) const;
  /// ψ − ψ₀ at t ∈ [0, T] from the σ-sum.
  double precession(double t_reduced) const;
  /// ψ̇ at M′ (pole frame).
  double precession_rate(const Vec3& M_aux) const;
  /// The frame Q(n′): rows p₁ = (e₃ − n′₃n′)/|·|, p₂ = n′ × p₁, p₃ = n′.
  static Mat3 momentum_frame(const Vec3& M_aux);
  State series_state(double t) const;

  Vec3 Lambda_, h_, M0_, omega0_;
  int axis_ = 0;  ///< axisymmetric: the symmetry axis k
  Quat q0_;
  double m_ = 0.0, two_E_ = 0.0;
  Regime regime_ = Regime::closed_form;
  // The curve in the pole frame.
  Mat3 S_;     ///< rows: the pole frame's axes in the body (S b = e₃)
  Mat3 Jinv_;  ///< S Λ⁻¹ Sᵀ
  Vec3 h_aux_;
  std::array<std::array<detail::cplx, 3>, 3> F_;  ///< F(z, w) = Σ F[i][j] zⁱ wʲ, the energy integral
  detail::cplx z0_, zdot0_, P_[5];                ///< z(0), ż(0), P⁽ᵏ⁾(z₀)
  detail::RealLattice lattice_{1.0L, 0.0L};
  // The attitude.
  std::array<detail::cplx, 4> u_{}, log_sigma0_{};   ///< the poles uₖ and ln σ(−uₖ)
  double C0_ = 0.0, psi0_ = 0.0, psi_period_ = 0.0;  ///< C₀, ψ(0), ψ(T) − ψ(0)
  Mat3 W_;                                           ///< world frame, e₃ along L
};

}  // namespace tumble
