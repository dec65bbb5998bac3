#pragma once
// The right-hand side of a whole Model in a formulation: loads from every force model, then the
// Newton–Euler rates of each body (newton_euler.hpp) and f = m a for each particle.
#include <vector>

#include "tumble/dynamics/newton_euler.hpp"
#include "tumble/forces/model.hpp"

namespace tumble {

/// A Model's integrated variables in one formulation.
struct SystemCoordinates {
  double t = 0.0;
  std::vector<Coordinates<double>> bodies;
  std::vector<ParticleState> particles;
};

struct SystemRates {
  std::vector<CoordinateRates<double>> bodies;
  std::vector<ParticleState> particles;  ///< (ẋ, v̇)
};

SystemCoordinates to_coordinates(Formulation formulation, const SystemState& state);
SystemState to_state(Formulation formulation, const SystemCoordinates& x);

/// Evaluates every force model at x and the equations of motion.
SystemRates system_rates(const Model& model, Formulation formulation, const SystemCoordinates& x);

/// x + h·k for all variables; quaternions are renormalised (projection back onto unit quaternions,
/// which keeps the method's order), t advances by h.
SystemCoordinates advance(const SystemCoordinates& x, double h, const SystemRates& k);

/// Σ wᵢ kᵢ (for Runge–Kutta combinations).
SystemRates combine(std::initializer_list<std::pair<double, const SystemRates*>> terms);

}  // namespace tumble
