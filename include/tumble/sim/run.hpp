#pragma once
// A run and what observes it. One object owns a run: the model and its start, the settings, the events
// it watches, its drift monitor, when it stops, its run points; whatever consumes the run — a trajectory
// writer, a report recorder, Python's arrays, a progress bar — attaches to it as a RunObserver and is
// handed every sample (with its invariants and drifts, computed once for all of them), every crossing
// and every run point, in time order. tumble run, tumble resume and tumble.simulate build a Run and
// attach observers; simulate() (simulate.hpp) is its one time loop. A study's runs, stepped as lanes of
// one system, observe their samples through simulate's lanes instead (io/ensemble.hpp).
#include <functional>
#include <optional>
#include <vector>

#include "tumble/sim/drift_monitor.hpp"
#include "tumble/sim/sensitivities.hpp"
#include "tumble/sim/simulate.hpp"

namespace tumble {

class RunObserver {
 public:
  virtual ~RunObserver() = default;
  /// A sample (the initial state first), with its invariants and their drifts from t = 0.
  virtual void on_sample(const SystemState& /*state*/, const DriftSample& /*drift*/) {}
  /// A crossing of a watched event, in time order with the samples.
  virtual void on_event(const EventHit& /*hit*/) {}
  /// A point the run could be resumed from (only when the run keeps them: Run::keep_run_points).
  virtual void on_run_point(const RunPoint& /*point*/) {}
  /// The sensitivities at the sample just handed to on_sample (only when the run carries them:
  /// Run::carry_sensitivities).
  virtual void on_sensitivities(const Sensitivities& /*sensitivities*/) {}
};

class Run {
 public:
  /// A run of `model` (which must outlive it) from `initial` with `settings` (validated), whose drift
  /// monitor judges the quantities the forces conserve against settings.drift_threshold.
  Run(const Model& model, SystemState initial, const RunSettings& settings, Conservation conserved);

  /// Watches these events too.
  Run& watch(std::vector<Event> events);
  /// Hands the run to `observer` (which must outlive run()), after those attached before it.
  Run& attach(RunObserver& observer);
  /// Asked after every step (or chunk of steps: RunHooks::stop_requested) and after every sample; true
  /// ends the run there, its state reached handed over as a last sample.
  Run& stop_when(std::function<bool()> asked);
  /// Keeps `point` up to date at every point the run could be resumed from (RunHooks::run_point).
  Run& keep_run_points(RunPoint& point);
  /// Continues the run from `point`, taken by a run of the same model, start, settings and events.
  Run& resume_from(const RunPoint& point);
  /// Steps the system as these independent runs (RunHooks::lanes), each watching its own events (then
  /// watch() gives none); the observers still see the whole system's samples.
  Run& as_lanes(std::vector<Lane> lanes);

  /// Carries the sensitivities (sim/sensitivities.hpp) with respect to the initial state and these
  /// parameters: the run is then stepped on dual numbers (simulate_sensitivities), and every sample's are
  /// handed to on_sensitivities. run() refuses it with events, lanes and run points, which that loop
  /// does not keep.
  Run& carry_sensitivities(SensitivityParameters parameters);

  /// The drift monitor, e.g. to restore a resumed run's warning before run().
  DriftMonitor& monitor() { return monitor_; }
  /// Runs to the end, or until stop_when said so: the final state. Once per Run.
  SystemState run();
  /// Whether stop_when ended the run.
  bool stopped() const { return stopped_; }
  const IntegratorStats& stats() const { return stats_; }

 private:
  const Model& model_;
  SystemState initial_;
  RunSettings settings_;
  DriftMonitor monitor_;
  std::vector<Event> events_;
  std::vector<RunObserver*> observers_;
  std::function<bool()> stop_;
  RunPoint* point_ = nullptr;
  const RunPoint* resume_ = nullptr;
  std::vector<Lane> lanes_;
  IntegratorStats stats_;
  std::optional<SensitivityParameters> sensitivities_;
  bool stopped_ = false;
};

}  // namespace tumble
