#pragma once
// Derived quantities of a moving rigid body: energy, momenta, velocities of body points, world inertia.
#include "tumble/dynamics/state.hpp"

namespace tumble {

/// I in world axes at this instant: I = R Λ Rᵀ (tutorial, "Euler's Equation").
inline Mat3 inertia_world(const RigidBody& body, const BodyState& s) {
  const Mat3 R = s.R();
  return R * body.Lambda().asDiagonal() * R.transpose();
}

/// ½ m v·v.
inline double kinetic_energy_translational(const RigidBody& body, const BodyState& s) {
  return 0.5 * body.mass() * s.v.squaredNorm();
}
/// ½ ^bω·Λ ^bω (= ½ ω·Iω).
inline double kinetic_energy_rotational(const RigidBody& body, const BodyState& s) {
  const Vec3 w = s.omega_b();
  return 0.5 * w.dot(body.Lambda().cwiseProduct(w));
}
inline double kinetic_energy(const RigidBody& body, const BodyState& s) {
  return kinetic_energy_translational(body, s) + kinetic_energy_rotational(body, s);
}

/// p = m v.
inline Vec3 linear_momentum(const RigidBody& body, const BodyState& s) { return body.mass() * s.v; }

/// Angular momentum about the centre of mass, world: l = Iω = R Λ ^bω.
inline Vec3 angular_momentum(const RigidBody& body, const BodyState& s) {
  return rotate<double>(s.q, Vec3(body.Lambda().cwiseProduct(s.omega_b())));  // Eigen's q * v, inlined
}

/// Angular momentum about a fixed world point x₀: l = (o − x₀) × p + Iω.
inline Vec3 angular_momentum_about(const RigidBody& body, const BodyState& s, const Vec3& x0) {
  return (s.o - x0).cross(linear_momentum(body, s)) + angular_momentum(body, s);
}

/// World position of a body-fixed point given in reference-frame coordinates: o + R Uᵀ(r − c).
inline Vec3 point_position(const RigidBody& body, const BodyState& s, const Vec3& r_ref) {
  return s.o + s.q * Vec3(body.U().transpose() * (r_ref - body.center_of_mass()));
}

/// Velocity of a body-fixed point (reference coordinates): v + ω × (x − o) (tutorial, section II).
inline Vec3 point_velocity(const RigidBody& body, const BodyState& s, const Vec3& r_ref) {
  return s.v + s.omega_w.cross(point_position(body, s, r_ref) - s.o);
}

/// Acceleration of a body-fixed point: a + ω̇ × r + ω × (ω × r), r = x − o, given the centre-of-mass
/// acceleration a and the angular acceleration ω̇ (world).
inline Vec3 point_acceleration(const RigidBody& body, const BodyState& s, const Vec3& r_ref, const Vec3& a,
                               const Vec3& omega_dot_w) {
  const Vec3 r = point_position(body, s, r_ref) - s.o;
  return a + omega_dot_w.cross(r) + s.omega_w.cross(s.omega_w.cross(r));
}

}  // namespace tumble
