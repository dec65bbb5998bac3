#pragma once
// Conserved quantities of a whole Model: energy, linear momentum, angular momentum about the origin.
#include <optional>

#include "tumble/dynamics/newton_euler.hpp"
#include "tumble/integrate/system_coordinates.hpp"

namespace tumble {

/// What bodies contribute to the invariants, summed (T: double, or a pack holding one run per lane).
template <class T>
struct BodySums {
  T kinetic_energy = T(0.0);
  Vec3T<T> linear_momentum = Vec3T<T>(T(0.0), T(0.0), T(0.0));   ///< Σ m v (world)
  Vec3T<T> angular_momentum = Vec3T<T>(T(0.0), T(0.0), T(0.0));  ///< Σ (o × p + R Λ ^bω), about the origin
};

/// One body's share added to `sum`, from its variables `x` in formulation F (^bω and v read as they are
/// where the formulation holds them, rotated where it does not), with mass m and principal moments Λ:
///   T = ½ m v·v + ½ ^bω·Λ^bω,   p = m v,   L = o × p + R Λ ^bω.
/// The one source of these sums, for a run's diagnostics and for a study's lanes (in one fixed order of
/// operations, so that a lane of a pack gives the bits of the same run on doubles).
template <class T>
TUMBLE_INLINE void add_body_sums(const T& m, const Vec3T<T>& Lambda, const Coordinates<T>& x, Formulation F,
                                 BodySums<T>& sum) {
  const Vec3T<T> omega_b = F == Formulation::world ? rotate_inverse<T>(x.q, x.omega) : x.omega;
  const Vec3T<T> v = F == Formulation::body ? rotate<T>(x.q, x.v) : x.v;
  const Vec3T<T> p = m * v;
  const Vec3T<T> L_b = Lambda.cwiseProduct(omega_b);  // Λ ^bω, the body's angular momentum in {b}
  const T omega_L = omega_b.x() * L_b.x() + omega_b.y() * L_b.y() + omega_b.z() * L_b.z();
  sum.kinetic_energy += T(0.5) * m * squared_norm<T>(v) + T(0.5) * omega_L;
  sum.linear_momentum += p;
  sum.angular_momentum += x.o.cross(p) + rotate<T>(x.q, L_b);
}

struct Invariants {
  double kinetic_energy = 0.0;
  std::optional<double> potential_energy;  ///< nullopt when some force model has no potential
  Vec3 linear_momentum = Vec3::Zero();     ///< Σ m v (world)
  Vec3 angular_momentum = Vec3::Zero();    ///< about the world origin: Σ (o × p + Iω) + Σ x × p

  /// Kinetic plus potential energy, when every force model is conservative (or there are none).
  std::optional<double> total_energy() const {
    if (!potential_energy) return std::nullopt;
    return kinetic_energy + *potential_energy;
  }
};

Invariants invariants(const Model& model, const SystemState& state);

/// One body's kinetic energy, momentum and angular momentum about the origin added to `inv`, from its
/// variables in `formulation`: ½ m v·v + ½ ^bω·Λ^bω, m v, o × m v + R Λ ^bω (^bω and v read as they
/// are where the formulation holds them, rotated where it does not). The one source of these sums.
void add_body_invariants(const RigidBody& body, const Coordinates<double>& x, Formulation formulation,
                         Invariants& inv);

/// The invariants of the run whose bodies are first … first + model.bodies.size() − 1 of `x` (its
/// particles x.particles, if it has any), straight from the formulation's variables: a study's runs,
/// stepped alone or as lanes of a batch, are observed this way at every sample. The potential needs
/// the bodies' states: they are converted into `scratch` only when the model has force models.
Invariants invariants(const Model& model, Formulation formulation, const SystemCoordinates& x, size_t first,
                      SystemState& scratch);

}  // namespace tumble
