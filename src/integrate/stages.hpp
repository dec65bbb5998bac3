#pragma once
// The updates explicit methods build their stages from, templated like the equations (one body or a
// pack of bodies per call).
#include "tumble/dynamics/newton_euler.hpp"
#include "tumble/dynamics/particle.hpp"

namespace tumble {

/// x + h·k; the quaternion is projected back onto |q| = 1 (which keeps the method's order).
template <class T>
TUMBLE_INLINE Coordinates<T> advanced(const Coordinates<T>& x, T h, const CoordinateRates<T>& k) {
  return {x.o + h * k.o_dot, normalized<T>(QuatT<T>(x.q.coeffs() + h * k.q_dot.coeffs())), x.v + h * k.v_dot,
          x.omega + h * k.omega_dot};
}

/// a + w·b.
template <class T>
TUMBLE_INLINE CoordinateRates<T> axpy(const CoordinateRates<T>& a, T w, const CoordinateRates<T>& b) {
  return {a.o_dot + w * b.o_dot, QuatT<T>(a.q_dot.coeffs() + w * b.q_dot.coeffs()), a.v_dot + w * b.v_dot,
          a.omega_dot + w * b.omega_dot};
}

/// Semi-implicit Euler's update of one body from its rates k at the step's start: velocities first,
/// v ← v + h v̇, ω ← ω + h ω̇, then position and orientation with the new velocities, o ← o + h ȯ(v),
/// q ← q + h q̇(ω) (projected back onto |q| = 1).
template <class T>
TUMBLE_INLINE Coordinates<T> semi_implicit_euler_update(Formulation F, Coordinates<T> c, const T& h,
                                                        const CoordinateRates<T>& k) {
  c.v += h * k.v_dot;
  c.omega += h * k.omega_dot;
  const auto [o_dot, q_dot] = kinematics<T>(F, c);  // with the updated velocities
  c.o += h * o_dot;
  c.q = normalized<T>(QuatT<T>(c.q.coeffs() + h * q_dot.coeffs()));
  return c;
}

/// Newton's second law for a particle, ẋ = v, v̇ = f/m (tutorial, section I), as a (ẋ, v̇) pair.
inline ParticleState particle_rates(const Particle& p, const ParticleState& s, const Vec3& f) {
  return {s.v, f / p.mass};
}

inline ParticleState advanced(const ParticleState& s, double h, const ParticleState& k) {
  return {s.x + h * k.x, s.v + h * k.v};
}
inline ParticleState axpy(const ParticleState& a, double w, const ParticleState& b) {
  return {a.x + w * b.x, a.v + w * b.v};
}

}  // namespace tumble
