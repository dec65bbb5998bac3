#pragma once
// Small helpers for running models in tests.
#include <string>
#include <vector>

#include "tumble/sim/simulate.hpp"

namespace tumble::test {

/// Settings of a run of `duration` in steps of h by `integrator`, sampled at its start and end only.
inline RunSettings end_only(const std::string& integrator, double duration, double h,
                            Formulation formulation = Formulation::mixed) {
  RunSettings s;
  s.duration = duration;
  s.timestep = h;
  s.output_interval = duration;
  s.integrator = integrator;
  s.formulation = formulation;
  return s;
}

/// Runs `model` from `initial` for `duration` with step h and returns the final state.
inline SystemState run(const Model& model, const SystemState& initial, double duration, double h,
                       const std::string& integrator, Formulation formulation = Formulation::mixed) {
  return simulate(model, initial, end_only(integrator, duration, h, formulation));
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
