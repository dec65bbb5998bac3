#pragma once
// A system's variables in dual numbers (issue 25): what Integrator::step_tangent steps. Each number
// carries its derivatives along up to kTangentDirections seeded directions (initial-state tangents,
// principal moments, masses), and a step computes them by instantiating the integrator's own templated
// stage updates, Newton–Euler rates and force laws on TangentScalar: the derivatives are those of the
// discrete map the integrator applies (renormalisation of q included), not of a separate set of
// tangent equations.
#include <span>
#include <vector>

#include "tumble/dynamics/newton_euler.hpp"
#include "tumble/forces/model.hpp"

namespace tumble {

struct TangentCoordinates {
  double t = 0.0;
  std::vector<Coordinates<TangentScalar>> bodies;  ///< o, q, v, ω in the formulation's frames
  std::vector<TangentScalar> m;                    ///< each body's mass (seeded for ∂/∂m)
  std::vector<Vec3T<TangentScalar>> Lambda;        ///< its principal moments (seeded for ∂/∂Λ)
  /// Each force model's parameters() (seeded for ∂/∂p); empty: their values, unseeded.
  std::vector<std::vector<TangentScalar>> force_parameters;
};

/// The world state of a body from its formulation's variables (o, q, v_w, ω_w), on any number type.
template <class T>
BodyStateT<T> world_state(Formulation formulation, const Coordinates<T>& x, const T& m,
                          const Vec3T<T>& Lambda) {
  const auto [v_w, omega_w] = world_velocities<T>(formulation, x);
  return {x.o, x.q, v_w, omega_w, m, Lambda};
}

/// The loads and Newton–Euler rates of every body of a TangentCoordinates: every force model's
/// accumulate_tangent at the bodies' world states, then newton_euler<TangentScalar>. Keeps its storage
/// from call to call.
class TangentRates {
 public:
  /// The loads (world force and torque about the centre of mass) at y, time y.t.
  std::span<const WrenchT<TangentScalar>> loads(const Model& model, Formulation formulation,
                                                const TangentCoordinates& y);
  /// The rates at y, time y.t (after loads(), into `rates`).
  void rates(const Model& model, Formulation formulation, const TangentCoordinates& y,
             std::vector<CoordinateRates<TangentScalar>>& rates);

 private:
  std::vector<BodyStateT<TangentScalar>> states_;
  std::vector<WrenchT<TangentScalar>> loads_;
  std::vector<TangentScalar> unseeded_;
};

}  // namespace tumble
