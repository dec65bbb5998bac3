#pragma once
// A run of a model with inputs held between samples (ForceModel::input_interval: a controller's
// zero-order hold): simulate() steps it as one run of pieces between samples, each piece the one time
// loop (simulate_steps) from where the last ended. Private to tumble_sim.
#include "tumble/sim/simulate.hpp"

namespace tumble {

/// The one time loop (simulate.cpp), for a model whose inputs do not change during the run.
SystemState simulate_steps(const Model& model, SystemState state, const RunSettings& settings,
                           const RunHooks& hooks);

/// The interval of the model's held inputs (ForceModel::input_interval), 0 when it has none. Throws
/// InvalidArgument when two models give different ones.
double input_interval(const Model& model);

/// simulate() for a model whose inputs are sampled every `interval` from the start (t₀ + k·interval;
/// the samples of the output grid and the inputs' samples are both step ends): the samples, events and
/// stop requests are those of one run. Throws InvalidArgument for lanes and run points (a resumed run
/// would need the inputs held when it stopped).
SystemState simulate_held_inputs(const Model& model, SystemState state, const RunSettings& settings,
                                 const RunHooks& hooks, double interval);

}  // namespace tumble
