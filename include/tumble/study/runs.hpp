#pragma once
// Studies: a study's runs simulated into their rows (io/ensemble.hpp reads the study and writes its
// tables). Runs whose draws leave the structure alone — they change bodies' values and events only
// (EnsembleStudy::structural_columns) — are stepped together as lanes of one stacked system
// (forces/stack.hpp, sim/simulate.hpp's Lane), many per SIMD pack, by the engine tumble run uses; the
// others one group per structure, or one run alone. Each run's row is the same, bit for bit, either way.
#include <functional>
#include <span>
#include <vector>

#include "tumble/io/ensemble.hpp"

namespace tumble {

/// What a chosen run's trajectory file receives as run_alone runs it: every sample and every crossing
/// of the scene's events (EventHit::index into scene.events), in time order.
struct RunTrajectory {
  std::function<void(const Scene&, const SystemState&)> sample;
  std::function<void(const Scene&, const EventHit&)> event;
};

/// Runs run i alone: its row. `trajectory`, if given, receives its samples and crossings.
EnsembleRow run_alone(const EnsembleStudy& study, long i, const RunTrajectory& trajectory = {});

/// The rows of several runs, in their order, the runs that share a structure stepped together (one run
/// alone when none shares it, when it has particles or a system force model, or for an adaptive
/// integrator). Each row equals run_alone's, bit for bit.
std::vector<EnsembleRow> run_batch(const EnsembleStudy& study, std::span<const long> runs);

/// Runs `runs` (indices) of the study on `threads` threads (0: one per core), in batches of up to 512
/// consecutive runs (run_batch); each finished row goes to `done` (called under a lock, in any order);
/// `stop()` is asked between batches (Ctrl-C). Returns the rows in the order of `runs`, those not run
/// (stopped) left out.
std::vector<EnsembleRow> run_ensemble(const EnsembleStudy& study, const std::vector<long>& runs, int threads,
                                      const std::function<void(const EnsembleRow&)>& done,
                                      const std::function<bool()>& stop = {});

}  // namespace tumble
