#pragma once
// Independent runs as one system: the models of a study's runs that share a structure (the same bodies
// but for their values, the same force models, no particles) stacked end to end, so that the engine
// steps all of them in one batch, many runs per SIMD pack (sim/simulate.hpp, Lane).
#include <optional>
#include <span>

#include "tumble/forces/model.hpp"

namespace tumble {

/// The runs' models as one: run r's body i is body r·n + i (n bodies per run), with its own mass
/// properties and name; each force model of runs[0] acts on every run's bodies as it acts on run 0's —
/// the caller's promise is that every run has the same force models (a study's runs of one structure).
/// nullopt when the runs cannot share a system: particles, a system force model (a spring, a user
/// ForceModel: they may read any body), or differing body counts. A local model that treats every body
/// alike (uniform gravity) is shared as it is; another (a force on body #i) acts on each run's copy of
/// body i. Rotors are stacked as one Rotors of every copy's wheels (a controller's: nullopt).
std::optional<Model> stack_runs(std::span<const Model* const> runs);

}  // namespace tumble
