#pragma once
// A Model's integrated variables in one formulation, as columns: what every integrator steps in place.
#include <vector>

#include "tumble/dynamics/columns.hpp"
#include "tumble/forces/model.hpp"

namespace tumble {

/// The variables of every body (o, q, v, ω in the formulation's frames, newton_euler.hpp) as columns,
/// and the particles' positions and velocities (world), at time t.
struct SystemCoordinates {
  double t = 0.0;
  BodyColumns bodies;
  std::vector<ParticleState> particles;
};

[[nodiscard]] SystemCoordinates to_coordinates(Formulation formulation, const SystemState& state);
[[nodiscard]] SystemState to_state(Formulation formulation, const SystemCoordinates& x);
/// The same into `state`, reusing its storage.
void to_state(Formulation formulation, const SystemCoordinates& x, SystemState& state);
/// Bodies first … first + n − 1 of x (no particles) into `part`, reusing its storage: one run's state out
/// of a batch of runs stepped together (sim/simulate.hpp, Lane).
void to_state(Formulation formulation, const SystemCoordinates& x, size_t first, size_t n, SystemState& part);

/// Whether x holds exactly these variables, bit for bit (the time is not compared): how integrators that
/// keep something between steps (splitting's loads and flows, exact's anchor) notice that the state they
/// are handed is not the one they produced.
bool same_variables(const SystemCoordinates& x, const BodyColumns& bodies,
                    const std::vector<ParticleState>& particles);

/// The first body or particle of x that is not finite, as "body 'name'" or "particle 'name'"; empty
/// when everything is finite.
std::string first_non_finite(const Model& model, const SystemCoordinates& x);
/// The index of the first body of x that is not finite; x.bodies.size() when every body is finite.
size_t first_non_finite_body(const SystemCoordinates& x);

/// Bodies first … first + n − 1 of x (and no particles) into `part`, at x's time, reusing its storage:
/// one run's variables out of a batch of runs stepped together (sim/simulate.hpp, Lane).
void copy_bodies(const SystemCoordinates& x, size_t first, size_t n, SystemCoordinates& part);

}  // namespace tumble
