#pragma once
// The exact motion of a torque-free rigid body (Euler–Poinsot), evaluated at any time in O(1).
//
// Conventions (docs/ARCHITECTURE.md): {b} = principal axes, Λ = diag(principal moments), R maps body to
// world (x_w = o + R x_b), ω_b = Rᵀ ω_w. Euler's equation Λ ω̇_b = (Λω_b) × ω_b with Ṙ = R [ω_b]×
// conserves 2E = ω_bᵀΛω_b and the world angular momentum L_w = R Λ ω_b.
//
// Solution (Landau & Lifshitz, Mechanics, §§33, 37; Celledoni, Fassò, Säfström & Zanna, SIAM J. Sci.
// Comput. 30, 2008):
//   - triaxial I₁ < I₂ < I₃ (moments sorted internally by a proper signed permutation): ω_b is a triple
//     of Jacobi elliptic functions of u = λt + u₀ with parameter m = k²; the orientation is
//       R(t) = G · Rz(φ(t)) · Rx(θ(t)) Rz(ψ(t)) · C P,
//     where the rotation G (fixed) takes e₃ to L_w/|L|, θ, ψ are the polar angles of the unit body
//     momentum in a frame whose z is the "pole" axis the polhode circles, and
//       φ(t) = |L|t/I_p + κ [Π(−N; am u | m) − Π(−N; am u₀ | m)],  N and κ constants (see the .cpp);
//   - the separatrix D = L²/2E = I₂ (m = 1): sn → tanh, cn, dn → sech, Π in closed form;
//   - two equal moments: ω_b cones about the symmetry axis e_s at n = (I_s − I_t) ω_s / I_t and
//     R(t) = Rot(L̂_w, |L| t / I_t) R₀ Rot(e_s, −n t);
//   - three equal moments, ω_b = 0, or spin about the intermediate axis: ω_b constant,
//     R(t) = Rot(ω_w, |ω| t) R₀.
//
// Numerics: the differences 2E I_j − L² = Σ Iᵢ (I_j − Iᵢ) ωᵢ² are formed from the components (no
// cancellation of large invariants), k′² = 1 − m comes from them directly, and sn, cn, dn, K are
// evaluated from (k, k′) (jacobi_elliptic.hpp). Arguments are reduced modulo the period and
// Π(n; φ + jπ | m) = Π(n; φ | m) + 2jΠ(n | m), so the cost and the relative accuracy of the phase do
// not depend on t.
#include <cstddef>
#include <string>

#include "tumble/math/types.hpp"

namespace tumble {

namespace detail {
class FreeRotation;
}

class EulerPoinsot {
 public:
  /// The kind of motion, decided once from the data.
  enum class Regime {
    rest,              ///< ω_b = 0
    sphere,            ///< I₁ = I₂ = I₃: uniform rotation about a fixed axis
    axisymmetric,      ///< exactly two equal moments: regular precession (closed form)
    about_minor_axis,  ///< D = L²/2E < I₂: the polhode circles the axis of least moment
    about_major_axis,  ///< D > I₂: the polhode circles the axis of largest moment
    separatrix,        ///< D = I₂: one asymptotic flip (or steady spin about the intermediate axis)
  };

  /// Moments are "equal" when they differ by at most this fraction of the largest moment: a few
  /// rounding errors of moments computed by an eigen-solver. Above it the triaxial formulas are used;
  /// they stay accurate however small I₂ − I₁ is, so the two answers agree to rounding at the threshold.
  static constexpr double kEqualMomentsTolerance = 16 * 2.220446049250313e-16;
  /// The state is on the separatrix when |2E I₂ − L²| ≤ this × (I₁(I₂−I₁)ω₁² + I₃(I₃−I₂)ω₃²): the
  /// difference is then below the rounding error of its own two terms (k′² indistinguishable from 0).
  static constexpr double kSeparatrixTolerance = 16 * 2.220446049250313e-16;

  /// Torque-free motion with principal moments `Lambda` (kg·m², any order, all > 0) from the
  /// orientation q0 (body → world; normalised here) and body angular velocity omega_b0 (rad/s) at t = 0.
  /// Throws InvalidArgument for non-positive or non-finite moments, a zero or non-finite quaternion or
  /// a non-finite angular velocity.
  EulerPoinsot(const Vec3& Lambda, const Quat& q0, const Vec3& omega_b0);
  /// The same from a rotation matrix R0 (body → world).
  EulerPoinsot(const Vec3& Lambda, const Mat3& R0, const Vec3& omega_b0);
  /// A value: copies are independent and, like construction and evaluation, never allocate.
  EulerPoinsot(const EulerPoinsot& other);
  EulerPoinsot& operator=(const EulerPoinsot& other);
  ~EulerPoinsot() = default;  // the flow in flow_ is trivially destructible (checked where it is built)

  /// Body angular velocity ω_b(t) (rad/s), for any real t (negative t runs the motion backwards).
  Vec3 omega_b(double t) const;
  /// World angular velocity ω_w(t) = R(t) ω_b(t).
  Vec3 omega_w(double t) const;
  /// Orientation at t, a unit quaternion (body → world).
  Quat q(double t) const;
  Mat3 R(double t) const { return q(t).toRotationMatrix(); }
  /// The orientation and the body angular velocity at t together.
  struct State {
    Quat q;        ///< q(t)
    Vec3 omega_b;  ///< omega_b(t)
  };
  /// q(t) and omega_b(t), bit for bit, for little more than the cost of q(t): the elliptic functions
  /// at t, which both need, are evaluated once.
  State state(double t) const;

  Regime regime() const { return regime_; }
  /// The period of ω_b(t): 4K/λ for a triaxial body (for spin exactly about the major or minor axis,
  /// the limit of nearby motions, the period of small oscillations); 2π/|n| for an axisymmetric body;
  /// +∞ on the separatrix and when ω_b is constant (rest, sphere).
  double period_omega() const;
  /// The time between successive sign changes of ω₂, the component on the intermediate axis (the
  /// "flips" of a tumbling racket): 2K/λ for a triaxial body; π/|n| for an axisymmetric one (any
  /// transverse component, the limit of nearly symmetric bodies); +∞ on the separatrix, sphere, rest.
  double flip_interval() const;

  const Vec3& Lambda() const { return Lambda_; }
  /// The closed-form flow itself, for the library's batched splitting drift (src/integrate), which
  /// evaluates triaxial flows on SIMD packs with the same templates.
  const detail::FreeRotation& free_rotation() const { return flow(); }
  /// Kinetic energy E = ½ ω_bᵀ Λ ω_b (J), from the initial data.
  double energy() const { return 0.5 * omega_b0_.dot(Lambda_.cwiseProduct(omega_b0_)); }
  /// World angular momentum L_w = R₀ Λ ω_b(0) (kg·m²/s), constant.
  Vec3 angular_momentum_w() const { return R0_ * Lambda_.cwiseProduct(omega_b0_); }

 private:
  /// Bytes for the closed-form flow, a detail::FreeRotation (src/integrate/euler_poinsot_flows.hpp: a
  /// std::variant of the steady, axisymmetric and triaxial flows) built in place in flow_, so that no
  /// EulerPoinsot ever touches the heap. euler_poinsot.cpp checks that it fits.
  static constexpr std::size_t kFlowBytes = 768;
  const detail::FreeRotation& flow() const;
  detail::FreeRotation& flow();

  Vec3 Lambda_;
  Mat3 R0_;
  Vec3 omega_b0_;
  Regime regime_;
  alignas(Quat) unsigned char flow_[kFlowBytes];  // holds a detail::FreeRotation once constructed
};

/// "rest", "sphere", "axisymmetric", "about_minor_axis", "about_major_axis", "separatrix".
std::string regime_name(EulerPoinsot::Regime regime);

}  // namespace tumble
