#pragma once
// The time loop: fixed steps from t₀ to t₀ + duration, samples at every output interval and at the end.
#include <functional>
#include <string>

#include "tumble/integrate/integrator.hpp"

namespace tumble {

struct RunSettings {
  double duration = 1.0;         ///< s
  double timestep = 1e-3;        ///< s; the last step before a sample time is shortened to land on it.
                                 ///< For adaptive integrators: the first trial step.
  double output_interval = 0.0;  ///< s between samples; 0 = every step. The final time is always sampled.
  Formulation formulation = Formulation::mixed;
  std::string integrator = "rk4";
  Tolerances tolerances;         ///< for adaptive integrators (dopri45)
};

/// Throws InvalidArgument unless duration ≥ 0, timestep > 0, output_interval ≥ 0, all finite, and the
/// integrator and formulation exist.
void validate(const RunSettings& settings);

/// Called with every sample (the initial state first); return false to stop the run early (Ctrl-C).
using SampleSink = std::function<bool(const SystemState&)>;

/// Runs the model from `state` and returns the final state. Throws tumble::Error naming the body,
/// time and step if a state becomes non-finite (a step too large, or a force that blows up).
/// `stats`, if given, receives the work done (steps, rejections, force evaluations).
/// `stop_requested`, if given, is asked after every step (fixed-step integrators) or every sample
/// (adaptive ones); when it answers true the current state is handed to `on_sample` as a last,
/// off-grid sample and the run ends there (Ctrl-C).
SystemState simulate(const Model& model, SystemState state, const RunSettings& settings,
                     const SampleSink& on_sample = {}, IntegratorStats* stats = nullptr,
                     const std::function<bool()>& stop_requested = {});

}  // namespace tumble
