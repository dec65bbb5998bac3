#pragma once
// Small helpers for running models in tests.
#include <vector>

#include "tumble/sim/simulate.hpp"

namespace tumble::test {

/// Runs `model` from `initial` for `duration` with step h and returns the final state.
inline SystemState run(const Model& model, const SystemState& initial, double duration, double h,
                       const std::string& integrator, Formulation formulation = Formulation::mixed) {
  RunSettings s;
  s.duration = duration;
  s.timestep = h;
  s.output_interval = duration;
  s.integrator = integrator;
  s.formulation = formulation;
  return simulate(model, initial, s);
}

/// Every state, one per step.
inline std::vector<SystemState> trajectory(const Model& model, const SystemState& initial, double duration,
                                           double h, const std::string& integrator,
                                           Formulation formulation = Formulation::mixed) {
  RunSettings s;
  s.duration = duration;
  s.timestep = h;
  s.output_interval = 0;
  s.integrator = integrator;
  s.formulation = formulation;
  std::vector<SystemState> out;
  simulate(model, initial, s, [&](const SystemState& x) {
    out.push_back(x);
    return true;
  });
  return out;
}

inline SystemState single(const BodyState& s) { return SystemState{0.0, {s}, {}}; }

}  // namespace tumble::test
