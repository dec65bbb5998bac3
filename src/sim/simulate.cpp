#include "tumble/sim/simulate.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>

#include "held_inputs.hpp"
#include "steppers.hpp"
#include "tumble/error.hpp"
#include "tumble/sim/run_plan.hpp"

namespace tumble {
namespace {

void require(bool ok, const std::string& message) {
  if (!ok) throw InvalidArgument(message);
}

/// A run's variables at one moment (its bodies first … first + n − 1 of y, or all of y), and its state,
/// converted from them only when an event needs more than one body's variables (Event::g_variables).
struct Moment {
  Formulation F;
  const SystemCoordinates& y;
  size_t first, n;
  SystemState& state;
  bool converted = false;
};

/// g, of event e at time t, checked: a NaN or infinity would hide every crossing, so it is an error.
double finite_g(const Event& e, double g, double t) {
  if (!std::isfinite(g)) {
    throw InvalidArgument(
        fmt::format("event '{}' returned {} at t = {} s; an event function must return a "
                    "finite number whose sign changes at the event",
                    e.name, g, t));
  }
  return g;
}

/// The column of the variables an event's g reads as it is in formulation F (Event::variable), or −1.
int variable_of(const Event& e, Formulation F) {
  return e.variable ? e.variable->column[static_cast<size_t>(F)] : -1;
}

/// g of an event at a moment.
double evaluate(const Event& e, Moment& m) {
  double g;
  if (const int c = variable_of(e, m.F); c >= 0) {
    g = m.y.bodies[static_cast<size_t>(c)][m.first + e.body] - e.variable->value;  // as g_variables gives it
  } else if (e.g_variables) {
    g = e.g_variables(m.y.bodies, m.first + e.body, m.F);
  } else {
    if (!m.converted) {
      if (m.first == 0 && m.n == m.y.bodies.size()) {
        to_state(m.F, m.y, m.state);  // the whole system, particles too (reusing the storage)
      } else {
        to_state(m.F, m.y, m.first, m.n, m.state);
      }
      m.converted = true;
    }
    g = e.g(m.state);
  }
  return finite_g(e, g, m.y.t);
}

bool crosses(const Event& e, double g0, double g1) {
  const bool rising = g0 < 0 && g1 >= 0, falling = g0 > 0 && g1 <= 0;
  return (rising && e.direction >= 0) || (falling && e.direction <= 0);
}

struct Hit {
  double tau;
  size_t event;
  SystemCoordinates x;
};

/// One event of one run, as the loop over every run's events at every step reads it: its g at the
/// step's start, and the column g reads (Event::variable in this formulation; −1: call evaluate).
struct Watch {
  size_t run, event;
  const Event* e;
  int column;
  size_t row;    ///< the watched body's row in the system
  double value;  ///< Event::variable's, when column ≥ 0
  double g_prev;
};

/// A sign change of g in the step.
struct Crossing {
  size_t watch;
  double g0, g1;
};

/// The τ ∈ (0, h] where g, of sign g0 ≠ 0 at τ = 0 and of the other sign (or zero) at h, changes sign,
/// to `resolution`: the Illinois variant of regula falsi on a bracket [lo, hi] that always holds the
/// change (g has g0's sign at lo, the other sign or zero at hi), with a bisection whenever two
/// iterations have not halved the bracket. A handful of evaluations where bisection to 4 ulp took ~50,
/// which matters when every run of a study locates its crossings. Returns hi and the variables there.
/// `state_at(τ, y)` puts the run's variables at an offset τ ∈ (0, h] into the step in y: one step of
/// length τ from the step's start (fixed-step methods) or the dense output (adaptive ones). y and
/// scratch are storage (reused: a study locates every run's crossings).
template <class StateInStep>
double locate(const Event& e, Formulation F, double g0, double g1, double h, double resolution,
              const StateInStep& state_at, SystemCoordinates& at_hi, SystemCoordinates& y,
              SystemState& scratch) {
  double lo = 0.0, hi = h, g_lo = g0, g_hi = g1;
  int kept_side = 0;            // +1: lo moved last time, −1: hi moved (Illinois halves the other g)
  double width_before = 2 * h;  // the bracket two iterations ago
  for (int k = 0; k < 200 && hi - lo > resolution && g_hi != 0; ++k) {
    double tau = hi - g_hi * (hi - lo) / (g_hi - g_lo);
    if (k % 2 == 0) {
      if (hi - lo > 0.5 * width_before) tau = 0.5 * (lo + hi);
      width_before = hi - lo;
    }
    // Never on an end of the bracket: at least a quarter of the resolution inside.
    tau = std::clamp(tau, lo + 0.25 * resolution, hi - 0.25 * resolution);
    if (!(tau > lo && tau < hi)) tau = 0.5 * (lo + hi);
    state_at(tau, y);
    Moment m{F, y, 0, y.bodies.size(), scratch};
    const double g = evaluate(e, m);
    if ((g0 < 0) == (g < 0) && g != 0) {
      lo = tau;
      g_lo = g;
      if (kept_side == 1) g_hi *= 0.5;
      kept_side = 1;
    } else {
      hi = tau;
      g_hi = g;
      std::swap(at_hi, y);
      if (kept_side == -1) g_lo *= 0.5;
      kept_side = -1;
    }
  }
  return hi;
}

}  // namespace
void require_thread_count(int threads) {
  if (threads < 0 || threads > 4096) {
    throw InvalidArgument(
        fmt::format("threads = {} is invalid: give a count from 1 to 4096, or 0 for one per core", threads));
  }
}

void validate(const RunSettings& s) {
  require(std::isfinite(s.duration) && s.duration >= 0,
          fmt::format("duration {} s is invalid: give a finite time >= 0", s.duration));
  require(std::isfinite(s.timestep) && s.timestep > 0,
          fmt::format("timestep {} s is invalid: give a positive step, e.g. 1e-3", s.timestep));
  require(std::isfinite(s.output_interval) && s.output_interval >= 0,
          fmt::format("output interval {} s is invalid: give a time >= 0 (0 = every step)",
                      s.output_interval));
  // The clock is t₀ + n·h and samples are t₀ + k·Δ: past 2⁵³ steps or samples n·h no longer advances
  // (e.g. timestep = 5e-324, or duration = 1e300), and the run would never end.
  const double dt_out = s.output_interval > 0 ? s.output_interval : s.timestep;
  require(
      s.duration / s.timestep <= kMaxCount,
      fmt::format("timestep {} s is too small for duration {} s: {:.3g} steps, more than 2^53, where a step "
                  "no longer advances the clock; give a larger timestep or a shorter duration",
                  s.timestep, s.duration, s.duration / s.timestep));
  require(s.duration / dt_out <= kMaxCount,
          fmt::format("output interval {} s is too small for duration {} s: {:.3g} samples, more than 2^53; "
                      "give a larger output interval (0 = every step)",
                      s.output_interval, s.duration, s.duration / dt_out));
  require(std::isfinite(s.drift_threshold) && s.drift_threshold >= 0,
          fmt::format("drift threshold {} is invalid: give a number >= 0 (0 turns the warning off)",
                      s.drift_threshold));
  require_thread_count(s.threads);
  if (is_adaptive(s.integrator)) {
    make_adaptive_integrator(s.integrator, s.tolerances);  // validates the tolerances
  } else {
    (void)make_integrator(s.integrator);  // throws, listing the names, if unknown
  }
}

namespace steppers {

void check_sample_times(const RunSettings& s, double t0) {
  const std::vector<double>& times = s.sample_times;
  if (times.empty()) return;
  const double tiny = 1e-9 * s.timestep;
  double before = t0;
  for (size_t k = 0; k < times.size(); ++k) {
    require(std::isfinite(times[k]), fmt::format("sample time #{} is {}: give finite times", k, times[k]));
    require(times[k] - before > tiny,
            fmt::format("sample time #{} ({} s) is not after {} ({} s): give times in increasing order, "
                        "after the start, more than 1e-9 of a timestep apart",
                        k, times[k],
                        k == 0 ? std::string("the start") : fmt::format("sample time #{}", k - 1), before));
    before = times[k];
  }
  // The end is t₀ + duration as the settings say it: to rounding of that sum, the last time.
  const double end = t0 + s.duration,
               slack = 4 * 2.220446049250313e-16 * std::max(std::abs(t0), std::abs(end));
  require(std::abs(end - times.back()) <= slack,
          fmt::format("the last sample time ({} s) is not where the run ends (start {} s + duration {} s); "
                      "give duration = the last sample time minus the start",
                      times.back(), t0, s.duration));
}

SampleTimes::SampleTimes(const RunSettings& s, double t0)
    : t0_(t0),
      t_end_(s.sample_times.empty() ? t0 + s.duration : s.sample_times.back()),
      dt_out_(s.output_interval > 0 ? s.output_interval : s.timestep),
      times_(&s.sample_times) {}

double SampleTimes::operator()(long k) const {
  if (k == 0) return t0_;
  if (!times_->empty())
    return (*times_)[static_cast<size_t>(std::min<long>(k, static_cast<long>(times_->size()))) - 1];
  return std::min(t0_ + static_cast<double>(k) * dt_out_, t_end_);
}

}  // namespace steppers

SystemState simulate(const Model& model, SystemState state, const RunSettings& settings,
                     const SampleSink& on_sample, IntegratorStats* stats,
                     const std::function<bool()>& stop_requested) {
  RunHooks hooks;
  hooks.on_sample = on_sample;
  hooks.stats = stats;
  hooks.stop_requested = stop_requested;
  return simulate(model, std::move(state), settings, hooks);
}

namespace {

/// What simulate keeps of each run it steps: one covering the whole system, or each lane of a batch.
struct RunInBatch {
  const Model* model = nullptr;
  const std::vector<Event>* events = nullptr;
  const SampleSink* on_sample = nullptr;  ///< the lane's own (a single run's is the system's)
  const VariablesSink* on_variables = nullptr;
  const std::function<void(const EventHit&)>* on_event = nullptr;
  const std::function<std::string()>* label = nullptr;
  size_t first = 0, n = 0;          ///< its bodies in the system
  bool done = false;                ///< a lane that stopped or needs no more samples
  SystemState state;                ///< a lane's state, copied out of the system's (reused storage)
  SystemCoordinates at_hi, inside;  ///< the variables where a crossing was located, and in its step
  SystemState scratch;              ///< the state there, when an event's g needs it
  EventHit event_hit;               ///< the crossing reported (storage reused)
  std::vector<Hit> hits;  ///< the crossings of the step: the first hit_count (the storage is reused)
  size_t hit_count = 0;
  size_t next_hit = 0;  ///< the first of hits not reported yet
};

/// The runs of a simulate call: the system alone, or its lanes (checked against the system).
std::vector<RunInBatch> runs_of(const Model& model, const RunHooks& hooks, const RunSettings& settings) {
  std::vector<RunInBatch> runs;
  if (hooks.lanes.empty()) {
    RunInBatch& r = runs.emplace_back();
    r.model = &model;
    r.events = &hooks.events;
    r.on_event = &hooks.on_event;
    r.n = model.bodies.size();
    return runs;
  }
  require(hooks.events.empty() && !hooks.on_event,
          "a batch of runs (RunHooks::lanes) watches each lane's events: leave RunHooks::events empty");
  require(!hooks.run_point && !hooks.resume_from,
          "a batch of runs (RunHooks::lanes) has no run points: resume a study by its runs");
  require(!is_adaptive(settings.integrator),
          fmt::format("{} cannot step a batch of runs (its step size would depend on every run's error): "
                      "run them one at a time",
                      settings.integrator));
  const size_t L = hooks.lanes.size(), n = model.bodies.size() / L;
  require(n * L == model.bodies.size() && model.particles.empty(),
          fmt::format("a batch of {} runs needs the same number of bodies in each and no particles; the "
                      "system has {} bodies and {} particles",
                      L, model.bodies.size(), model.particles.size()));
  for (size_t r = 0; r < L; ++r) {
    const Lane& lane = hooks.lanes[r];
    if (!lane.model || lane.model->bodies.size() != n || !lane.model->particles.empty()) {
      throw InvalidArgument(fmt::format("lane {} ({}) needs its own model of the {} bodies it holds", r,
                                        lane.label ? lane.label() : "", n));  // the label formatted only here
    }
    RunInBatch& run = runs.emplace_back();
    run.model = lane.model;
    run.events = &lane.events;
    run.on_sample = &lane.on_sample;
    run.on_variables = &lane.on_variables;
    run.on_event = &lane.on_event;
    run.label = &lane.label;
    run.first = r * n;
    run.n = n;
  }
  return runs;
}

}  // namespace

SystemState simulate(const Model& model, SystemState state, const RunSettings& settings,
                     const RunHooks& hooks) {
  if (const double interval = input_interval(model); interval > 0.0)
    return simulate_held_inputs(model, std::move(state), settings, hooks, interval);
  return simulate_steps(model, std::move(state), settings, hooks);
}

SystemState simulate_steps(const Model& model, SystemState state, const RunSettings& settings,
                           const RunHooks& hooks) {
  const SampleSink& on_sample = hooks.on_sample;
  IntegratorStats* stats = hooks.stats;
  const std::function<bool()>& stop_requested = hooks.stop_requested;
  validate(settings);
  if (state.bodies.size() != model.bodies.size() || state.particles.size() != model.particles.size()) {
    throw InvalidArgument(fmt::format("state has {} bodies and {} particles, the model {} and {}",
                                      state.bodies.size(), state.particles.size(), model.bodies.size(),
                                      model.particles.size()));
  }
  if (!is_adaptive(settings.integrator)) make_integrator(settings.integrator)->check(model);
  const bool batch = !hooks.lanes.empty();
  std::vector<RunInBatch> runs = runs_of(model, hooks, settings);
  const Formulation F = settings.formulation;
  const RunPoint* const from = hooks.resume_from;
  SystemCoordinates x = from ? from->x : to_coordinates(F, state);
  if (from) {
    if (from->t0 != state.t || x.bodies.size() != model.bodies.size() ||
        x.particles.size() != model.particles.size() || from->event_values.size() != hooks.events.size() ||
        from->next_sample < 1 || from->samples < 1) {
      throw InvalidArgument(
          "the run point to resume from does not belong to this run (another initial state, model or set "
          "of events)");
    }
  }
  // A body named for messages, with its run in a batch: "body 'box' of run 17".
  const auto body_named = [&](const SystemCoordinates& y) -> std::string {
    if (!batch) return first_non_finite(model, y);
    const size_t i = first_non_finite_body(y);
    if (i == y.bodies.size()) return {};
    const RunInBatch& run = runs[i / runs[0].n];
    return fmt::format("body '{}' of {}", model.bodies[i].name(),
                       *run.label ? (*run.label)() : fmt::format("lane {}", i / runs[0].n));
  };
  if (const std::string bad = body_named(x); !bad.empty()) {
    throw InvalidArgument(fmt::format("{} state of {} is not finite", from ? "the resumed" : "initial", bad));
  }
  const double t0 = state.t;
  steppers::check_sample_times(settings, t0);
  const steppers::SampleTimes sample_time(settings, t0);
  const double t_end = sample_time.end();
  long k_out = from ? from->next_sample : 1;
  // Samples handed over, counted for run points (a resumed run continues the count).
  long samples = from ? from->samples : 0;

  // A run's view of a state of the system: the system's itself, or a lane's bodies copied out.
  const auto view = [&](RunInBatch& run, const SystemState& s) -> const SystemState& {
    if (!batch) return s;
    run.state.t = s.t;
    run.state.bodies.assign(s.bodies.begin() + static_cast<std::ptrdiff_t>(run.first),
                            s.bodies.begin() + static_cast<std::ptrdiff_t>(run.first + run.n));
    return run.state;
  };
  size_t runs_done = 0;
  std::vector<unsigned char> run_done(runs.size(), 0);  // run.done, in a row: read at every step
  const auto set_done = [&](RunInBatch& run) {
    if (!run.done) ++runs_done;
    run.done = true;
    run_done[static_cast<size_t>(&run - runs.data())] = 1;
  };
  const auto all_done = [&] { return runs_done == runs.size(); };
  // Whether any lane takes samples of its own (a study's lanes are reduced by hooks.on_variables).
  const bool lanes_sample = std::any_of(runs.begin(), runs.end(), [](const RunInBatch& r) {
    return r.on_sample && (*r.on_sample || *r.on_variables);
  });
  // A sample at the variables y, to every run that still wants them; false ends the run. `ready`: the
  // state there, when the caller has it (the initial state as given; a crossing's); else it is
  // converted from y: the whole system for a run alone (into `state`), each lane's own bodies.
  // Which variables `state` was last converted from, and at what time: the run's end state is that
  // sample when they are the stepper's end at its time, and is then handed back without a conversion
  // (a copy of 112 bytes a body).
  const SystemCoordinates* state_of = nullptr;
  double state_t = 0.0;
  auto emit = [&](const SystemCoordinates& y, const SystemState* ready) {
    ++samples;
    if (!batch) {
      if (ready != &state) {
        to_state(F, y, state);  // reuses the storage: no allocation per sample
        state_of = &y;
        state_t = y.t;
      }
      const bool go_on = !on_sample || on_sample(state);
      return (!hooks.on_variables || hooks.on_variables(y, 0)) && go_on;
    }
    bool go_on = true;
    if (on_sample) {
      if (!ready) to_state(F, y, state);
      go_on = on_sample(ready ? *ready : state);
    }
    if (hooks.on_variables) go_on = hooks.on_variables(y, 0) && go_on;
    for (RunInBatch& run : runs) {
      if (!lanes_sample) break;
      if (run.done) continue;
      bool more = true;
      if (*run.on_sample) {
        if (ready) {
          view(run, *ready);
        } else {
          to_state(F, y, run.first, run.n, run.state);
        }
        more = (*run.on_sample)(run.state);
      }
      if (*run.on_variables) more = (*run.on_variables)(y, run.first) && more;
      if (!more) set_done(run);
    }
    return go_on && !all_done();
  };
  if (!from && !emit(x, &state)) return state;
  // `steps` > 1: the last of several steps taken together from t_start, checked only after them.
  auto check = [&](const SystemCoordinates& y, long step, double step_h, long steps = 1,
                   double t_start = 0.0) {
    if (const std::string bad = body_named(y); !bad.empty()) {
      const std::string when = steps == 1 ? fmt::format("at t = {} s (step {}", y.t, step)
                                          : fmt::format("between t = {} s and t = {} s (steps {} to {}",
                                                        t_start, y.t, step - steps + 1, step);
      throw Error(
          fmt::format("the state of {} became non-finite {}, h = {} s, integrator {}); reduce "
                      "the timestep (or tolerances) or check the forces for singularities",
                      bad, when, step_h, settings.integrator));
    }
  };

  bool any_events = false;
  SystemState scratch;         // a run's state at a moment, when its events need it
  std::vector<Watch> watches;  // every run's events, run by run
  for (size_t r = 0; r < runs.size(); ++r) {
    RunInBatch& run = runs[r];
    Moment m{F, x, run.first, run.n, scratch};
    for (size_t i = 0; i < run.events->size(); ++i) {
      const Event& e = (*run.events)[i];
      if (!e.g && !e.g_variables) throw InvalidArgument(fmt::format("event '{}' has no function g", e.name));
      if ((e.g_variables || e.variable) && e.body >= run.n) {
        throw InvalidArgument(
            fmt::format("event '{}' watches body #{}, but the run has {} bodies", e.name, e.body, run.n));
      }
      const int column = variable_of(e, F);
      watches.push_back({r, i, &e, column, run.first + e.body, column >= 0 ? e.variable->value : 0.0,
                         from ? 0.0 : evaluate(e, m)});
    }
    any_events = any_events || !run.events->empty();
  }
  if (from) {
    for (size_t i = 0; i < watches.size(); ++i) watches[i].g_prev = from->event_values[i];
  }
  // The g of each watch at the step's end, and the sign changes in the step, in watch order.
  std::vector<Crossing> crossings;
  const auto find_crossings = [&](const SystemCoordinates& x_end) {
    crossings.clear();
    std::optional<Moment> end;  // the run of the last watch that needed evaluate
    size_t end_run = runs.size();
    for (size_t w = 0; w < watches.size(); ++w) {
      Watch& watch = watches[w];
      if (run_done[watch.run]) continue;
      const RunInBatch& run = runs[watch.run];
      double g1;
      if (watch.column >= 0) {
        g1 = x_end.bodies[static_cast<size_t>(watch.column)][watch.row] - watch.value;
        if (!std::isfinite(g1)) finite_g(*watch.e, g1, x_end.t);
      } else {
        if (end_run != watch.run)
          end.emplace(Moment{F, x_end, run.first, run.n, scratch}), end_run = watch.run;
        g1 = evaluate(*watch.e, *end);
      }
      const double g0 = watch.g_prev;
      watch.g_prev = g1;
      if (crosses(*watch.e, g0, g1)) crossings.push_back({w, g0, g1});
    }
  };
  std::vector<size_t> runs_hit;  // the runs with crossings in the step, in order
  // Steps inside a step to locate crossings (never the run's own integrator), for every run in turn.
  std::unique_ptr<Integrator> probe;
  // A run point, where nothing of a step is pending (after a step that held samples, or the start).
  const auto keep = [&](const auto& stepper) {
    if (!hooks.run_point) return;
    RunPoint& p = *hooks.run_point;
    p.t0 = t0;
    p.next_sample = k_out;
    p.t_last_sample = sample_time(k_out - 1);
    p.samples = samples;
    p.event_values.clear();
    for (const Watch& w : watches) p.event_values.push_back(w.g_prev);
    stepper.keep(p);
    if (hooks.on_run_point) hooks.on_run_point(p);
  };
  // The crossings of the step [t_start, t_start + step_h] that ended in x_end, located and put in time
  // order in their runs' hits; the runs with hits in runs_hit.
  const auto find_hits = [&](const SystemCoordinates& x_end, double t_start, double step_h,
                             const auto& state_at) {
    for (const size_t r : runs_hit) runs[r].hit_count = runs[r].next_hit = 0;
    runs_hit.clear();
    find_crossings(x_end);
    const double resolution = 4 * 2.220446049250313e-16 * std::max(std::abs(t_start), step_h);
    for (const Crossing& c : crossings) {
      const Watch& w = watches[c.watch];
      RunInBatch& run = runs[w.run];
      if (batch) {
        copy_bodies(x_end, run.first, run.n, run.at_hi);
      } else {
        run.at_hi = x_end;
      }
      const auto run_at = [&](double tau, SystemCoordinates& y) { state_at(run, tau, y); };
      const double tau =
          locate(*w.e, F, c.g0, c.g1, step_h, resolution, run_at, run.at_hi, run.inside, run.scratch);
      if (run.hit_count == run.hits.size()) run.hits.emplace_back();
      Hit& hit = run.hits[run.hit_count++];
      hit.tau = tau;
      hit.event = w.event;
      std::swap(hit.x, run.at_hi);  // at_hi takes the storage of an earlier hit
      if (runs_hit.empty() || runs_hit.back() != w.run) runs_hit.push_back(w.run);
    }
    for (const size_t r : runs_hit) {
      const auto first = runs[r].hits.begin();
      std::sort(first, first + static_cast<std::ptrdiff_t>(runs[r].hit_count),
                [](const Hit& a, const Hit& b) { return a.tau < b.tau; });
    }
  };
  // Reports a crossing; true when it stops its run (its state there is the run's last sample).
  const auto report = [&](RunInBatch& run, const Hit& hit) {
    const Event& e = (*run.events)[hit.event];
    EventHit& at = run.event_hit;
    at.name = e.name;
    at.index = hit.event;
    to_state(F, hit.x, at.state);
    if (*run.on_event) (*run.on_event)(at);
    if (!e.stop) return false;
    if (batch) {  // the lane's last sample; its variables are its own (first body 0)
      if (*run.on_sample) (*run.on_sample)(at.state);
      if (*run.on_variables) (*run.on_variables)(hit.x, 0);
      set_done(run);
      return all_done();
    }
    state = at.state;
    emit(hit.x, &state);
    return true;
  };

  const auto loop = [&](auto& stepper) -> SystemState {
    // The one time loop: a step, the crossings inside it, then the samples it reached, in time order;
    // run points after a step that held samples; a stop request answered after every step.
    const auto finish = [&] { return batch ? to_state(F, stepper.end()) : std::move(state); };
    if (!from) keep(stepper);
    while (!stepper.finished()) {
      const double t_sample = sample_time(k_out);
      if (const long n = stepper.chunk(t_sample); n > 0) {  // full steps between samples, taken together
        check(stepper.end(), stepper.stats().steps, settings.timestep, n, stepper.t_start());
        if (stats) *stats = stepper.stats();
        if (stop_requested && stop_requested()) {
          emit(stepper.end(), nullptr);
          return to_state(F, stepper.end());
        }
        continue;
      }
      stepper.step(t_sample);
      const double t_a = stepper.t_start(), t_b = stepper.t_end();
      check(stepper.end(), stepper.stats().steps, stepper.step_length());
      if (stats) *stats = stepper.stats();
      if (any_events) {
        find_hits(stepper.end(), t_a, stepper.step_length(),
                  [&](RunInBatch& run, double tau, SystemCoordinates& y) {
                    stepper.in_step({*run.model, run.first, run.n, probe}, tau, y);
                  });
      }
      bool sampled = false, ended_on_sample = false;
      while (true) {
        const double t_next = sample_time(k_out);
        const double limit = std::min(t_next, t_b);
        for (const size_t r : runs_hit) {
          RunInBatch& run = runs[r];
          // A crossing at τ into the step is at t_a + τ, which rounding may put past t_b: at most t_b.
          while (!run.done && run.next_hit < run.hit_count &&
                 std::min(t_a + run.hits[run.next_hit].tau, t_b) <= limit) {
            if (report(run, run.hits[run.next_hit++])) return finish();
          }
        }
        if (t_next > t_b) break;
        const SystemCoordinates& at = stepper.sample(t_next);
        ++k_out;
        sampled = true;
        ended_on_sample = t_next == t_b;
        stepper.sampled(t_next, t_end);
        if (!emit(at, nullptr)) return finish();
        if (stepper.finished()) break;
      }
      if (sampled) keep(stepper);
      if (!stepper.finished() && stop_requested && stop_requested()) {
        if (!ended_on_sample) emit(stepper.end(), nullptr);  // the state reached, off the grid
        return finish();
      }
    }
    const bool state_is_end = !batch && state_of == &stepper.end() && state_t == stepper.end().t;
    return stepper.final_state(std::move(state), state_is_end, F);
  };
  if (is_adaptive(settings.integrator)) {
    steppers::AdaptiveSteps stepper(model, F, settings, x, t_end, from);
    return loop(stepper);
  }
  steppers::FixedSteps stepper(model, F, settings, x, t0, t_end, from, batch, any_events);
  return loop(stepper);
}

}  // namespace tumble
