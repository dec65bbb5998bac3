#pragma once
// How simulate's one time loop (simulate.cpp) advances a run: FixedSteps (steps of h landing on the sample
// grid, chunks of full steps between samples) or AdaptiveSteps (an adaptive integrator's own accepted
// steps, with dense output). Both answer the loop's questions the same way: take a step, where it
// started and ended, the variables inside it (to locate a crossing) and at a sample, what a run point
// holds. Private to tumble_sim.
#include <fmt/format.h>

#include <algorithm>
#include <memory>

#include "tumble/error.hpp"
#include "tumble/sim/simulate.hpp"

namespace tumble::steppers {

/// Throws InvalidArgument unless the sample times of a run that starts at t0, if given, are finite,
/// ascending, after the start, apart by more than the rounding of the step grid (1e-9 h, FixedSteps),
/// the last where the run ends.
void check_sample_times(const RunSettings& s, double t0);

/// The sample times of a run that starts at t0 (simulate's and simulate_sensitivities'): sample k ≥ 1 at
/// t₀ + k·Δ, computed from k (not accumulated) so the times do not drift, or at the k-th time given;
/// sample 0 is the start.
class SampleTimes {
 public:
  SampleTimes(const RunSettings& s, double t0);
  double operator()(long k) const;
  /// Where the run ends.
  double end() const { return t_end_; }

 private:
  double t0_, t_end_, dt_out_;
  const std::vector<double>* times_;
};

/// At most this many steps are handed to Integrator::steps at once (between samples, no events).
inline constexpr long kChunk = 16;

/// One run of a simulate call, as a stepper needs it to locate a crossing: its bodies in the system, its
/// own model, and the probe integrator (made on first use; one for every run of a batch: what it keeps
/// between steps, it keeps only while it is handed the same state, so it gives any run the same steps).
struct RunInStep {
  const Model& model;
  size_t first, n;
  std::unique_ptr<Integrator>& probe;
};

/// A fixed-step integrator's way through a run: steps of h, the last before a sample shortened (or
/// lengthened by rounding) to land on it, the clock on the grid t_last_sample + n·h; the full steps
/// between two samples handed over together when nothing needs the states between them.
class FixedSteps {
 public:
  FixedSteps(const Model& model, Formulation F, const RunSettings& settings, SystemCoordinates& x, double t0,
             double t_end, const RunPoint* from, bool batch, bool events)
      : model_(model),
        F_(F),
        settings_(settings),
        x_(x),
        h_(settings.timestep),
        tiny_(1e-9 * settings.timestep),
        t_end_(t_end),
        t_last_sample_(t0),
        integrator_(make_integrator(settings.integrator)),
        batch_(batch),
        events_(events) {
    integrator_->set_threads(settings.threads);
    chunks_ = !events && integrator_->fuses_steps(model);
    if (from) {
      integrator_->load_state(model, F, from->integrator);
      step_ = from->stats.steps;
      t_last_sample_ = from->t_last_sample;
      steps_since_sample_ = from->steps_since_sample;
    }
  }

  bool finished() const { return !(x_.t < t_end_ - tiny_); }
  const SystemCoordinates& end() const { return x_; }
  double t_start() const { return t_start_; }
  double t_end() const { return x_.t; }
  /// The last step's length: the h it was taken with.
  double step_length() const { return step_h_; }
  IntegratorStats stats() const {
    return {step_, 0,
            integrator_->evaluations_counted().value_or(step_ * integrator_->evaluations_per_step())};
  }

  /// Full steps that end before the sample time need nothing between them: they go together
  /// (Integrator::steps, bit for bit the same), so fused integrators keep each block of bodies in cache
  /// across them; at most kChunk, so that Ctrl-C is still answered promptly. The number taken: none
  /// when fewer than two would be.
  long chunk(double t_sample) {
    if (!chunks_) return 0;
    long count = 0;
    for (double t = x_.t; count < kChunk && t_sample - t > h_ + tiny_ && t + h_ < t_sample - tiny_; t += h_)
      ++count;
    if (count <= 1) return 0;
    t_start_ = x_.t;
    integrator_->steps(model_, F_, x_, h_, count);
    step_ += count;
    steps_since_sample_ += count;
    x_.t = t_last_sample_ + static_cast<double>(steps_since_sample_) * h_;  // the clock on its grid
    return count;
  }

  void step(double t_sample) {
    // The step that reaches the sample time (or comes within `tiny` of it, by the rounding of the
    // accumulated time) is the remaining interval: x.t + (t_sample − x.t) is t_sample exactly when
    // x.t ≥ t_sample / 2 (Sterbenz), so the state is computed at the sample time itself.
    const double remaining = t_sample - x_.t;
    step_h_ = remaining <= h_ + tiny_ ? remaining : h_;
    if (events_) x_prev_ = x_;  // reuses the storage
    t_start_ = x_.t;
    integrator_->step(model_, F_, x_, step_h_);
    ++step_;
    // The clock on the grid t_sample_prev + n h (one rounding), not a running sum whose roundings add
    // up (1e-12 s per 1e3 steps): the remaining interval before a sample, and the times integrators
    // that keep a flow across steps evaluate it at, stay exact.
    ++steps_since_sample_;
    x_.t = x_.t >= t_sample - tiny_ ? t_sample
                                    : t_last_sample_ + static_cast<double>(steps_since_sample_) * h_;
  }

  /// The variables of `run` at τ into the last step: one step of τ from its start by a second integrator
  /// of the method, the run's own (the run's integrator itself is never handed a state it did not
  /// produce, so locating a crossing does not change the run: splitting keeps its flows, exact its anchor).
  void in_step(const RunInStep& run, double tau, SystemCoordinates& y) {
    if (batch_) {
      copy_bodies(x_prev_, run.first, run.n, y);
    } else {
      y = x_prev_;
    }
    if (!run.probe) {
      run.probe = make_integrator(settings_.integrator);
      run.probe->set_threads(batch_ ? 1 : settings_.threads);
    }
    run.probe->step(run.model, F_, y, tau);
  }

  /// A sample at t, which is the step's end (a fixed step lands on the grid).
  const SystemCoordinates& sample(double) const { return x_; }
  void sampled(double t, double) {
    t_last_sample_ = t;
    steps_since_sample_ = 0;
  }

  void keep(RunPoint& p) const {
    p.x = x_;
    p.t_last_sample = t_last_sample_;
    p.steps_since_sample = steps_since_sample_;
    p.finished = finished();
    p.stats = stats();
    p.integrator = integrator_->save_state();
  }

  /// The state the run ends in: `last_sample` when it was converted from the end itself.
  SystemState final_state(SystemState&& last_sample, bool last_sample_is_end, Formulation) const {
    return last_sample_is_end ? std::move(last_sample) : to_state(F_, x_);
  }

 private:
  const Model& model_;
  Formulation F_;
  const RunSettings& settings_;
  SystemCoordinates& x_;
  double h_, tiny_;  ///< a step shorter than tiny is rounding of the sample grid, not a real step
  double t_end_, t_last_sample_, t_start_ = 0.0, step_h_ = 0.0;
  long step_ = 0, steps_since_sample_ = 0;
  std::unique_ptr<Integrator> integrator_;
  SystemCoordinates x_prev_;
  bool batch_, events_, chunks_ = false;
};

/// An adaptive integrator's way through a run: its own accepted steps, each end clipped to t_end;
/// samples and states inside a step from its dense output.
class AdaptiveSteps {
 public:
  AdaptiveSteps(const Model& model, Formulation F, const RunSettings& settings, const SystemCoordinates& x,
                double t_end, const RunPoint* from)
      : integrator_(make_adaptive_integrator(settings.integrator, settings.tolerances)),
        t_end_(t_end),
        finished_(t_end <= x.t),
        x_b_(x) {
    integrator_->start(model, F, x,
                       std::min(settings.timestep, std::max(settings.duration, settings.timestep)));
    if (from) {
      integrator_->load_state(from->integrator);
      finished_ = from->finished;  // a point after the final sample: x is that sample's state
      resumed_at_end_ = finished_;
    }
  }

  bool finished() const { return finished_; }
  const SystemCoordinates& end() const { return x_b_; }
  double t_start() const { return t_a_; }
  double t_end() const { return t_b_; }
  double step_length() const { return t_b_ - t_a_; }
  IntegratorStats stats() const { return integrator_->stats(); }
  long chunk(double) { return 0; }

  void step(double) {
    t_a_ = integrator_->current_time();
    integrator_->step();
    t_b_ = std::min(integrator_->current_time(), t_end_);
    x_b_ = integrator_->interpolate(t_b_);
  }
  void in_step(const RunInStep&, double tau, SystemCoordinates& y) const {
    y = integrator_->interpolate(t_a_ + tau);
  }
  const SystemCoordinates& sample(double t) {
    x_ = integrator_->interpolate(t);
    return x_;
  }
  void sampled(double t, double t_end) { finished_ = t >= t_end; }

  /// A run point after a step that held samples: its end, where the next step starts.
  void keep(RunPoint& p) const {
    p.x = x_b_;
    p.steps_since_sample = 0;
    p.finished = finished_;
    p.stats = integrator_->stats();
    p.integrator = integrator_->save_state();
  }

  /// The state the run ends in: its last sample, which is at the end, unless it resumed there.
  SystemState final_state(SystemState&& last_sample, bool, Formulation F) const {
    return resumed_at_end_ ? to_state(F, x_b_) : std::move(last_sample);
  }

 private:
  std::unique_ptr<AdaptiveIntegrator> integrator_;
  double t_end_, t_a_ = 0.0, t_b_ = 0.0;
  bool finished_, resumed_at_end_ = false;
  SystemCoordinates x_b_, x_;
};

}  // namespace tumble::steppers
