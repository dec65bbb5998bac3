#pragma once
// Conserved quantities of a whole Model: energy, linear momentum, angular momentum about the origin.
#include <optional>

#include "tumble/integrate/system_coordinates.hpp"

namespace tumble {

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
