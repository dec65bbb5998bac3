#pragma once
// The splittings (splitting, splitting4) for bodies with rotors (issue 26): second order, and the total
// angular momentum conserved to rounding, as for a rigid body alone.
//
// A gyrostat (forces/rotors.hpp) in its body axes, with M = Λω + h its total angular momentum there,
// is the Lie–Poisson system Ṁ = M × ∇H, Ṙ = R [∇H]× of the Hamiltonian
//   H(M) = ½ (M − h)ᵀ Λ⁻¹ (M − h) = ½ Mᵀ Λ⁻¹ M − aᵀ M + const,  a = Λ⁻¹ h,
// since ∇H = Λ⁻¹ (M − h) = ω gives d/dt (Λω + h) = (Λω + h) × ω, Euler's gyrostat equation without
// motor torque. Each part has an exact flow:
//   H₁ = ½ Mᵀ Λ⁻¹ M: the free rigid body whose angular velocity is ω₁ = Λ⁻¹ M = ω + a (Euler–Poinsot,
//       the splittings' own drift);
//   H₂ = −aᵀ M: ∇H₂ = −a is constant, so the body turns about the body-fixed axis −a at the rate |a|,
//       R(τ) = R E, E = exp(−τ [a]×), while M turns the other way in body axes, M(τ) = Eᵀ M.
// Both keep R M, the angular momentum in world axes, and both are Poisson maps, so the Strang step
//   S(h) = K(h/2) ∘ G(h/2) ∘ D₁(h) ∘ G(h/2) ∘ K(h/2)
// (K the kick of the other loads, G the flow of H₂, D₁ of H₁) is second order and symmetric, splitting4's
// composition of it fourth order, and without external torque L = R M changes by rounding only. With
// motor torques h = h(t): M's equation does not hold ḣ (d/dt (Λω + h) = M × ω + τ), which only enters
// through ω = Λ⁻¹(M − h(t)); H₂ with h frozen at the middle of the step keeps second order (the midpoint
// rule in time), and ω and M are converted with h at the step's ends, where the state holds ω.
//
// On the splittings' variables: ω (the formulation's: ω_w in world, ^bω otherwise) becomes ω₁ = ω + a
// before G and the drift, and ω = ω₁ − a after them. A body without rotors has a = 0 and every step
// here leaves it as it is, bit for bit (E = 1). The same templates step packs of bodies (double lanes)
// and dual numbers (the sensitivities).
#include <memory>
#include <type_traits>
#include <vector>

#include "tumble/dynamics/columns.hpp"
#include "tumble/dynamics/state.hpp"
#include "tumble/forces/model.hpp"
#include "tumble/forces/rotors.hpp"
#include "tumble/math/quaternion.hpp"
#include "tumble/math/simd.hpp"

namespace tumble::gyrostat {

/// ω ← ω + sign·a: to ω₁ (sign +1) or back (−1), a in body axes.
template <class T>
TUMBLE_INLINE void shift(Formulation F, Coordinates<T>& c, const Vec3T<T>& a, double sign) {
  const Vec3T<T> da = T(sign) * a;
  c.omega += F == Formulation::world ? rotate<T>(c.q, da) : da;
}

/// G(τ), the flow of H₂ = −aᵀM on the state (R, ω₁ = Λ⁻¹M): R ← R E and M ← Eᵀ M, E = exp(−τ[a]×).
/// v in body axes follows R (v_w is unchanged).
template <class T>
TUMBLE_INLINE void turn(Formulation F, Coordinates<T>& c, const Vec3T<T>& a, const Vec3T<T>& Lambda,
                        const Vec3T<T>& Lambda_inv, const T& tau) {
  const QuatT<T> e = quat_exp<T>(Vec3T<T>(-tau * a));
  const Vec3T<T> w1_b = F == Formulation::world ? rotate_inverse<T>(c.q, c.omega) : c.omega;
  const Vec3T<T> w1_next = rotate_inverse<T>(e, Vec3T<T>(Lambda.cwiseProduct(w1_b))).cwiseProduct(Lambda_inv);
  c.q = quat_mul<T>(c.q, e);
  c.omega = F == Formulation::world ? rotate<T>(c.q, w1_next) : w1_next;
  if (F == Formulation::body) c.v = rotate_inverse<T>(e, c.v);
}

/// The state entering the drift D₁(h): ω₁ = ω + a(t) at the step's start, then G(h/2) with a(t + h/2);
/// a = Λ⁻¹ h from the rotors' h (body axes) at those times.
template <class T>
TUMBLE_INLINE void enter(Formulation F, Coordinates<T>& c, const Vec3T<T>& h_start, const Vec3T<T>& h_mid,
                         const Vec3T<T>& Lambda, const Vec3T<T>& Lambda_inv, const T& half_h) {
  shift<T>(F, c, Vec3T<T>(h_start.cwiseProduct(Lambda_inv)), 1.0);
  turn<T>(F, c, Vec3T<T>(h_mid.cwiseProduct(Lambda_inv)), Lambda, Lambda_inv, half_h);
}

/// The state the drift left, back in the splittings' variables: G(h/2) with a(t + h/2), then
/// ω = ω₁ − a(t + h) at the step's end.
template <class T>
TUMBLE_INLINE void leave(Formulation F, Coordinates<T>& c, const Vec3T<T>& h_mid, const Vec3T<T>& h_end,
                         const Vec3T<T>& Lambda, const Vec3T<T>& Lambda_inv, const T& half_h) {
  turn<T>(F, c, Vec3T<T>(h_mid.cwiseProduct(Lambda_inv)), Lambda, Lambda_inv, half_h);
  shift<T>(F, c, Vec3T<T>(h_end.cwiseProduct(Lambda_inv)), -1.0);
}

/// What a splitting needs of the model's rotors: the model its kicks load the bodies with (without the
/// rotors, whose torque is in the flows above) and h of every body at the three times of a step.
class RotorSplit {
 public:
  /// The model the kicks load the bodies with: `model` itself when it has no rotors, else a copy of it
  /// without them (made once, while the model stays the same).
  const Model& kick_model(const Model& model);
  /// Whether the last kick_model() found rotors.
  bool active() const { return rotors_ != nullptr; }
  /// h of every body (its principal axes) at t, t + h/2 and t + h (zero for a body without rotors).
  void momenta(double t, double h);
  /// h of body i at time k (0 start, 1 middle, 2 end), as a pack of bodies i … i + W − 1 or alone.
  template <class T>
  Vec3T<T> h(int k, size_t i) const;
  /// Whether the motors of body i (or of each body of the pack from i) hold its rotors' speeds over the
  /// step: h the same, and not zero, at the three times. Such a body drifts by the gyrostat's own flow
  /// (gyrostat_series.hpp) instead of G D₁ G.
  template <class T>
  auto held(size_t i) const;

 private:
  const Rotors* rotors_ = nullptr;
  const Model* source_ = nullptr;
  const RigidBody* source_bodies_ = nullptr;
  std::vector<std::shared_ptr<const ForceModel>> source_forces_;
  Model kick_model_;
  Columns h_;  ///< 9 columns: h at the start, the middle and the end
};

template <class T>
Vec3T<T> RotorSplit::h(int k, size_t i) const {
  const auto column = [&](int j) { return h_[static_cast<size_t>(3 * k + j)] + i; };
  if constexpr (std::is_same_v<T, xsimd::batch<double>>) {
    return {T::load_aligned(column(0)), T::load_aligned(column(1)), T::load_aligned(column(2))};
  } else {
    return {T(*column(0)), T(*column(1)), T(*column(2))};
  }
}

template <class T>
auto RotorSplit::held(size_t i) const {
  const Vec3T<T> h0 = h<T>(0, i), h1 = h<T>(1, i), h2 = h<T>(2, i);
  auto same = h0(0) != T(0.0) || h0(1) != T(0.0) || h0(2) != T(0.0);
  for (int k = 0; k < 3; ++k) same = same && h0(k) == h1(k) && h1(k) == h2(k);
  return same;
}

}  // namespace tumble::gyrostat
