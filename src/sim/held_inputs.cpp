#include "held_inputs.hpp"

#include <fmt/format.h>

#include <cmath>

#include "steppers.hpp"
#include "tumble/error.hpp"

namespace tumble {

double input_interval(const Model& model) {
  double interval = 0.0;
  for (const auto& f : model.forces) {
    const double d = f->input_interval();
    if (d <= 0.0) continue;
    if (interval > 0.0 && d != interval) {
      throw InvalidArgument(fmt::format(
          "two force models sample their inputs every {} s and every {} s: give them one interval", interval,
          d));
    }
    interval = d;
  }
  return interval;
}

SystemState simulate_held_inputs(const Model& model, SystemState state, const RunSettings& settings,
                                 const RunHooks& hooks, double interval) {
  if (!hooks.lanes.empty() || hooks.run_point || hooks.resume_from) {
    throw InvalidArgument(
        "a run whose inputs are held between samples (a rotor controller) cannot be stepped as lanes of a "
        "study, nor keep run points to resume from (checkpoints): the controller's state is not in them");
  }
  validate(settings);
  const double t0 = state.t;
  steppers::check_sample_times(settings, t0);
  const steppers::SampleTimes grid(settings, t0);
  const double t_end = grid.end();
  // Two times closer than this are one: the output grid and the inputs' samples may round apart.
  const double tiny = 1e-9 * settings.timestep;
  if (!(interval > tiny)) {
    throw InvalidArgument(
        fmt::format("inputs sampled every {} s: give an interval longer than 1e-9 of the "
                    "timestep ({} s)",
                    interval, settings.timestep));
  }

  // The run's samples and the inputs' samples, merged: each piece runs from one input sample to the next
  // (or the end) and samples the output grid's times inside it and its own end, which is handed on only
  // when it is on the grid (then the grid's time is kept, as the run without inputs would have it).
  long k_grid = 1, k_input = 1;
  bool stopped = false;
  IntegratorStats total;
  if (hooks.stats) total = *hooks.stats;
  bool first = true;
  RunSettings piece = settings;
  while (true) {
    const SystemView view{state.t, model.bodies, state.bodies, model.particles, state.particles};
    for (const auto& f : model.forces) {
      if (f->input_interval() <= 0.0) continue;
      if (first) f->restart_inputs();
      f->sample_inputs(view);
    }
    // The piece's end: the next input sample, or the run's end.
    double t_next = t0 + static_cast<double>(k_input) * interval;
    if (t_next >= t_end - tiny) t_next = t_end;
    piece.sample_times.clear();
    bool end_on_grid = false;
    while (true) {
      const double g = grid(k_grid);
      if (g > t_next + tiny) break;
      ++k_grid;
      if (g >= t_next - tiny) {  // the grid's time ends the piece
        t_next = g;
        end_on_grid = true;
        break;
      }
      piece.sample_times.push_back(g);
    }
    piece.sample_times.push_back(t_next);
    piece.duration = piece.sample_times.back() - state.t;
    const double t_start = state.t;
    const auto handed_on = [&](double t) {
      if (t == t_start) return first;  // a piece's start is the last one's end, already handed on
      return t != t_next || end_on_grid || stopped;
    };
    RunHooks h;
    if (hooks.on_sample) {
      h.on_sample = [&](const SystemState& s) {
        if (!handed_on(s.t)) return true;
        if (hooks.on_sample(s)) return true;
        stopped = true;
        return false;
      };
    }
    if (hooks.on_variables) {
      h.on_variables = [&](const SystemCoordinates& x, size_t row) {
        if (!handed_on(x.t)) return true;
        if (hooks.on_variables(x, row)) return true;
        stopped = true;
        return false;
      };
    }
    h.events = hooks.events;
    h.on_event = [&](const EventHit& hit) {
      if (hooks.events[hit.index].stop) stopped = true;
      if (hooks.on_event) hooks.on_event(hit);
    };
    if (hooks.stop_requested) {
      h.stop_requested = [&] { return stopped = stopped || hooks.stop_requested(); };
    }
    IntegratorStats stats;
    h.stats = &stats;
    state = simulate_steps(model, std::move(state), piece, h);
    total.steps += stats.steps;
    total.rejected += stats.rejected;
    total.evaluations += stats.evaluations;
    if (hooks.stats) *hooks.stats = total;
    first = false;
    if (stopped || t_next == t_end) return state;
    if (state.t != t_next) return state;  // ended early by a sample sink's answer
    ++k_input;
  }
}

}  // namespace tumble
