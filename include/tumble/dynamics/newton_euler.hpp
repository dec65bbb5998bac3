#pragma once
// The Newton–Euler equations in the three formulations of the tutorial (section VII), each written
// once, templated on the scalar type so the single-body path, batched paths and tests share the lines.
//
//   world:  f = m v̇,                      τ = I ω̇ + ω × (I ω),  I = R Λ Rᵀ,   Ṙ = [ω]× R
//   mixed:  f = m v̇,                     ^bτ = Λ ^bω̇ + ^bω × (Λ ^bω),         Ṙ = R [^bω]×
//   body:  ^bf = m(^bv̇ + ^bω × ^bv),     ^bτ = Λ ^bω̇ + ^bω × (Λ ^bω),         Ṙ = R [^bω]×,  ȯ = R ^bv
//
// R is kept as a unit quaternion q: Ṙ = [ω]× R  ⇔  q̇ = ½ (0, ω) ⊗ q  ⇔  q̇ = ½ q ⊗ (0, ^bω).
#include <utility>

#include "tumble/dynamics/state.hpp"
#include "tumble/math/quaternion.hpp"

namespace tumble {

/// Which frame the integrated velocities live in (tutorial, "Simulating Dynamics", "Dynamics in Mixed
/// Frames", "Dynamics in the Body Frame").
enum class Formulation {
  world,  ///< v and ω in {w}
  mixed,  ///< v in {w}, ω in {b}
  body,   ///< v and ω in {b}
};

/// The variables a formulation integrates: centre of mass o (world), orientation q of {b}, and v, ω in
/// the formulation's frames (see Formulation).
template <class T>
struct Coordinates {
  Vec3T<T> o;
  QuatT<T> q;
  Vec3T<T> v;
  Vec3T<T> omega;
};

/// Their time derivatives.
template <class T>
struct CoordinateRates {
  Vec3T<T> o_dot;
  QuatT<T> q_dot;  ///< not a unit quaternion: the derivative of one
  Vec3T<T> v_dot;
  Vec3T<T> omega_dot;
};

/// Ṙ = [ω]× R as a quaternion: q̇ = ½ (0, ω) ⊗ q = (0, ½ω) ⊗ q (halving is exact: the same bits).
template <class T>
TUMBLE_INLINE QuatT<T> q_dot_world(const QuatT<T>& q, const Vec3T<T>& omega_w) {
  return pure_mul_quat<T>(T(0.5) * omega_w, q);
}

/// Ṙ = R [^bω]× as a quaternion: q̇ = ½ q ⊗ (0, ^bω) = q ⊗ (0, ½ ^bω).
template <class T>
TUMBLE_INLINE QuatT<T> q_dot_body(const QuatT<T>& q, const Vec3T<T>& omega_b) {
  return quat_mul_pure<T>(q, T(0.5) * omega_b);
}

/// A body's constants as the rates use them: Λ, and 1/m and Λ⁻¹ = diag(1/Λ₁, 1/Λ₂, 1/Λ₃), by which the
/// rates multiply. The reciprocals are taken once per body rather than dividing at every evaluation: a
/// division has the throughput of about eight multiplications, and the rates would divide six times.
template <class T>
struct MassConstants {
  T m_inv;              ///< 1/m (1/kg)
  Vec3T<T> Lambda;      ///< principal moments (kg·m²)
  Vec3T<T> Lambda_inv;  ///< their reciprocals (1/(kg·m²))
};
template <class T>
TUMBLE_INLINE MassConstants<T> mass_constants(T m, const Vec3T<T>& Lambda) {
  return {T(1) / m, Lambda, {T(1) / Lambda.x(), T(1) / Lambda.y(), T(1) / Lambda.z()}};
}

/// Euler's equation in the body frame solved for the angular acceleration:
/// d/dt(^bω) = Λ⁻¹(^bτ − ^bω × (Λ ^bω)).
template <class T>
TUMBLE_INLINE Vec3T<T> euler_body(const MassConstants<T>& c, const Vec3T<T>& omega_b, const Vec3T<T>& tau_b) {
  return (tau_b - omega_b.cross(c.Lambda.cwiseProduct(omega_b))).cwiseProduct(c.Lambda_inv);
}

/// World formulation. ω̇ = I⁻¹(τ − ω × Iω) with I = RΛRᵀ, I⁻¹ = RΛ⁻¹Rᵀ. Since R is a rotation,
/// ω × (RΛRᵀω) = R(^bω × Λ^bω), so ω̇ = R Λ⁻¹(Rᵀτ − ^bω × Λ^bω) = R · euler_body(Λ, Rᵀω, Rᵀτ): the same
/// world-frame rate, with three rotations instead of two 3×3 products.
template <class T>
TUMBLE_INLINE CoordinateRates<T> newton_euler_world(const MassConstants<T>& c, const Coordinates<T>& x,
                                                    const Vec3T<T>& f_w, const Vec3T<T>& tau_w) {
  CoordinateRates<T> r;
  r.o_dot = x.v;
  r.q_dot = q_dot_world<T>(x.q, x.omega);
  r.v_dot = f_w * c.m_inv;
  r.omega_dot =
      rotate<T>(x.q, euler_body<T>(c, rotate_inverse<T>(x.q, x.omega), rotate_inverse<T>(x.q, tau_w)));
  return r;
}

/// Mixed formulation: v in world, ^bω in body.
template <class T>
TUMBLE_INLINE CoordinateRates<T> newton_euler_mixed(const MassConstants<T>& c, const Coordinates<T>& x,
                                                    const Vec3T<T>& f_w, const Vec3T<T>& tau_b) {
  CoordinateRates<T> r;
  r.o_dot = x.v;
  r.q_dot = q_dot_body<T>(x.q, x.omega);
  r.v_dot = f_w * c.m_inv;
  r.omega_dot = euler_body<T>(c, x.omega, tau_b);
  return r;
}

/// Body formulation: ^bv and ^bω in body; ^bv̇ = ^bf/m − ^bω × ^bv, ȯ = R ^bv.
template <class T>
TUMBLE_INLINE CoordinateRates<T> newton_euler_body(const MassConstants<T>& c, const Coordinates<T>& x,
                                                   const Vec3T<T>& f_b, const Vec3T<T>& tau_b) {
  CoordinateRates<T> r;
  r.o_dot = rotate<T>(x.q, x.v);
  r.q_dot = q_dot_body<T>(x.q, x.omega);
  r.v_dot = f_b * c.m_inv - x.omega.cross(x.v);
  r.omega_dot = euler_body<T>(c, x.omega, tau_b);
  return r;
}

/// The kinematic part alone, (ȯ, q̇), of any formulation (used by integrators that update velocities
/// and positions separately).
template <class T>
TUMBLE_INLINE std::pair<Vec3T<T>, QuatT<T>> kinematics(Formulation formulation, const Coordinates<T>& x) {
  switch (formulation) {
    case Formulation::world:
      return {x.v, q_dot_world<T>(x.q, x.omega)};
    case Formulation::mixed:
      return {x.v, q_dot_body<T>(x.q, x.omega)};
    case Formulation::body:
      return {rotate<T>(x.q, x.v), q_dot_body<T>(x.q, x.omega)};
  }
  return {};
}

/// The rates of any formulation for a wrench given in world axes (force, torque about the centre of
/// mass): the wrench is rotated into the frames the formulation needs, ^bu = Rᵀ u.
template <class T>
TUMBLE_INLINE CoordinateRates<T> newton_euler(Formulation formulation, const MassConstants<T>& c,
                                              const Coordinates<T>& x, const Vec3T<T>& f_w,
                                              const Vec3T<T>& tau_w) {
  switch (formulation) {
    case Formulation::world:
      return newton_euler_world<T>(c, x, f_w, tau_w);
    case Formulation::mixed:
      return newton_euler_mixed<T>(c, x, f_w, rotate_inverse<T>(x.q, tau_w));
    case Formulation::body:
      return newton_euler_body<T>(c, x, rotate_inverse<T>(x.q, f_w), rotate_inverse<T>(x.q, tau_w));
  }
  return {};
}

/// The formulation's variables for a state.
inline Coordinates<double> to_coordinates(Formulation formulation, const BodyState& s) {
  const Quat q_inv = s.q.conjugate();
  switch (formulation) {
    case Formulation::world:
      return {s.o, s.q, s.v, s.omega_w};
    case Formulation::mixed:
      return {s.o, s.q, s.v, q_inv * s.omega_w};
    case Formulation::body:
      return {s.o, s.q, q_inv * s.v, q_inv * s.omega_w};
  }
  return {};
}

/// The velocities v, ω of a formulation's variables in world axes: ω_w = R ^bω, v_w = R ^bv where the
/// formulation holds them in the body frame.
template <class T>
TUMBLE_INLINE std::pair<Vec3T<T>, Vec3T<T>> world_velocities(Formulation formulation,
                                                             const Coordinates<T>& x) {
  switch (formulation) {
    case Formulation::world:
      return {x.v, x.omega};
    case Formulation::mixed:
      return {x.v, rotate<T>(x.q, x.omega)};
    case Formulation::body:
      return {rotate<T>(x.q, x.v), rotate<T>(x.q, x.omega)};
  }
  return {};
}

/// The state for a formulation's variables.
inline BodyState to_state(Formulation formulation, const Coordinates<double>& x) {
  const auto [v_w, omega_w] = world_velocities<double>(formulation, x);
  return {x.o, x.q, v_w, omega_w};
}

}  // namespace tumble
