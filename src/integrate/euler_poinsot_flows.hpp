#pragma once
// The closed-form flows behind EulerPoinsot, one per kind of body (internal to the library).
#include <memory>

#include "tumble/integrate/euler_poinsot.hpp"

namespace tumble::detail {

/// A torque-free motion given in closed form from t = 0.
class FreeRotation {
 public:
  virtual ~FreeRotation() = default;
  virtual Vec3 omega_b(double t) const = 0;
  virtual Quat q(double t) const = 0;
  virtual double period_omega() const = 0;
  virtual double flip_interval() const = 0;
};

/// ω_b constant (rest, sphere, spin about a principal axis that stays one): R(t) = Rot(ω_w, |ω|t) R₀.
std::shared_ptr<const FreeRotation> make_steady_rotation(const Quat& q0, const Vec3& omega_b0);

/// Two equal moments: regular precession about L_w. `axis` is the index (in the caller's axes) of the
/// distinct moment; the equal pair is replaced by its mean.
std::shared_ptr<const FreeRotation> make_axisymmetric_rotation(const Vec3& Lambda, int axis, const Quat& q0,
                                                               const Vec3& omega_b0);

/// The body in sorted principal axes: I₁ < I₂ < I₃ (all three distinct), ω_s = P ω_b with P a signed
/// permutation (det P = +1). I and ω_s may be scaled by powers of two (exactly): I by any factor, ω_s
/// by 1/omega_scale, so the physical angular velocity is omega_scale · w.
struct SortedBody {
  Vec3 I;
  Vec3 w;
  Mat3 P;
  double omega_scale = 1.0;
};

/// Three distinct moments: the elliptic-function solution (both regimes and the separatrix). Requires
/// w not along the intermediate axis (w₁ or w₃ non-zero). Sets `regime`.
std::shared_ptr<const FreeRotation> make_triaxial_rotation(const SortedBody& body, const Quat& q0,
                                                           EulerPoinsot::Regime& regime);

/// Rz(φ) Rx(θ) Rz(ψ) as a unit quaternion (z-x-z Euler angles). The three factors are multiplied
/// rather than combined into angles (φ ± ψ)/2: φ grows with t, and rounding φ + ψ would perturb the
/// body part Rx(θ)Rz(ψ) (and so L_w) by ε|φ| — 1e-9 rad at t = 1e6 s. Kept apart, the rounding of φ
/// only rotates about the fixed L_w.
inline Quat quat_zxz(double phi, double theta, double psi) {
  const Quat qz_phi(std::cos(0.5 * phi), 0.0, 0.0, std::sin(0.5 * phi));
  const Quat qx_theta(std::cos(0.5 * theta), std::sin(0.5 * theta), 0.0, 0.0);
  const Quat qz_psi(std::cos(0.5 * psi), 0.0, 0.0, std::sin(0.5 * psi));
  return qz_phi * (qx_theta * qz_psi);
}

}  // namespace tumble::detail
