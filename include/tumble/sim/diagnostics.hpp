#pragma once
// Conserved quantities of a whole Model: energy, linear momentum, angular momentum about the origin.
#include <optional>

#include "tumble/forces/model.hpp"

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

}  // namespace tumble
