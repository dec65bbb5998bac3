#include "tumble/sim/simulate.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <tuple>

#include "tumble/error.hpp"
#include "tumble/sim/run_plan.hpp"

namespace tumble {
namespace {

/// At most this many steps are handed to Integrator::steps at once (between samples, no events).
constexpr long kChunk = 16;

void require(bool ok, const std::string& message) {
  if (!ok) throw InvalidArgument(message);
}

/// g of an event at a state; a NaN or infinity would hide every crossing, so it is an error.
double evaluate(const Event& e, const SystemState& s) {
  const double g = e.g(s);
  if (!std::isfinite(g)) {
    throw InvalidArgument(
        fmt::format("event '{}' returned {} at t = {} s; an event function must return a "
                    "finite number whose sign changes at the event",
                    e.name, g, s.t));
  }
  return g;
}

bool crosses(const Event& e, double g0, double g1) {
  const bool rising = g0 < 0 && g1 >= 0, falling = g0 > 0 && g1 <= 0;
  return (rising && e.direction >= 0) || (falling && e.direction <= 0);
}

/// The variables at an offset τ ∈ (0, h] into the current step: one step of length τ from the step's
/// start (fixed-step methods) or the dense output (adaptive ones).
using StateInStep = std::function<SystemCoordinates(double tau)>;

struct Hit {
  double tau;
  size_t event;
  SystemCoordinates x;
};

/// Every crossing in the step of length h whose end state is `after`, located by bisection on τ to
/// 4 ulp of the time and returned in time order; g_prev (the values at the step's start) is updated
/// to the values at its end.
std::vector<Hit> find_hits(const std::vector<Event>& events, std::vector<double>& g_prev, Formulation F,
                           const SystemCoordinates& after, double t_start, double h,
                           const StateInStep& state_at) {
  std::vector<Hit> hits;
  const SystemState end = to_state(F, after);
  const double resolution = 4 * 2.220446049250313e-16 * std::max(std::abs(t_start), h);
  for (size_t i = 0; i < events.size(); ++i) {
    const double g0 = g_prev[i], g1 = evaluate(events[i], end);
    g_prev[i] = g1;
    if (!crosses(events[i], g0, g1)) continue;
    double lo = 0.0, hi = h;
    SystemCoordinates at_hi = after;
    for (int k = 0; k < 200 && hi - lo > resolution; ++k) {
      const double mid = 0.5 * (lo + hi);
      SystemCoordinates y = state_at(mid);
      const double g = evaluate(events[i], to_state(F, y));
      if ((g0 < 0) == (g < 0) && g != 0) {
        lo = mid;
      } else {
        hi = mid;
        at_hi = std::move(y);
      }
    }
    hits.push_back({hi, i, std::move(at_hi)});
  }
  std::sort(hits.begin(), hits.end(), [](const Hit& a, const Hit& b) { return a.tau < b.tau; });
  return hits;
}

}  // namespace

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
  require(s.threads >= 0 && s.threads <= 4096,
          fmt::format("threads = {} is invalid: give a count from 1 to 4096, or 0 for one per core",
                      s.threads));
  if (is_adaptive(s.integrator)) {
    make_adaptive_integrator(s.integrator, s.tolerances);  // validates the tolerances
  } else {
    make_integrator(s.integrator);  // throws, listing the names, if unknown
  }
}

SystemState simulate(const Model& model, SystemState state, const RunSettings& settings,
                     const SampleSink& on_sample, IntegratorStats* stats,
                     const std::function<bool()>& stop_requested) {
  RunHooks hooks;
  hooks.on_sample = on_sample;
  hooks.stats = stats;
  hooks.stop_requested = stop_requested;
  return simulate(model, std::move(state), settings, hooks);
}

SystemState simulate(const Model& model, SystemState state, const RunSettings& settings,
                     const RunHooks& hooks) {
  const SampleSink& on_sample = hooks.on_sample;
  IntegratorStats* stats = hooks.stats;
  const std::function<bool()>& stop_requested = hooks.stop_requested;
  const std::vector<Event>& events = hooks.events;
  validate(settings);
  if (state.bodies.size() != model.bodies.size() || state.particles.size() != model.particles.size()) {
    throw InvalidArgument(fmt::format("state has {} bodies and {} particles, the model {} and {}",
                                      state.bodies.size(), state.particles.size(), model.bodies.size(),
                                      model.particles.size()));
  }
  if (!is_adaptive(settings.integrator)) make_integrator(settings.integrator)->check(model);
  const RunPoint* const from = hooks.resume_from;
  SystemCoordinates x = from ? from->x : to_coordinates(settings.formulation, state);
  if (from) {
    if (from->t0 != state.t || x.bodies.size() != model.bodies.size() ||
        x.particles.size() != model.particles.size() || from->event_values.size() != events.size() ||
        from->next_sample < 1 || from->samples < 1) {
      throw InvalidArgument(
          "the run point to resume from does not belong to this run (another initial state, model or set "
          "of events)");
    }
  }
  if (const std::string bad = first_non_finite(model, x); !bad.empty()) {
    throw InvalidArgument(fmt::format("{} state of {} is not finite", from ? "the resumed" : "initial", bad));
  }
  const double t0 = state.t;
  const double t_end = t0 + settings.duration;
  const double h = settings.timestep;
  // Sample times are t₀ + k·Δ, computed from k (not accumulated) so they do not drift.
  const double dt_out = settings.output_interval > 0 ? settings.output_interval : h;
  long k_out = from ? from->next_sample : 1;
  // Samples handed over, counted for run points (a resumed run continues the count).
  long samples = from ? from->samples : 0;
  auto emit = [&](const SystemState& s) {
    ++samples;
    return !on_sample || on_sample(s);
  };
  if (!from && !emit(state)) return state;
  // `steps` > 1: the last of several steps taken together from t_start, checked only after them.
  auto check = [&](const SystemCoordinates& y, long step, double step_h, long steps = 1,
                   double t_start = 0.0) {
    if (const std::string bad = first_non_finite(model, y); !bad.empty()) {
      const std::string when = steps == 1 ? fmt::format("at t = {} s (step {}", y.t, step)
                                          : fmt::format("between t = {} s and t = {} s (steps {} to {}",
                                                        t_start, y.t, step - steps + 1, step);
      throw Error(
          fmt::format("the state of {} became non-finite {}, h = {} s, integrator {}); reduce "
                      "the timestep (or tolerances) or check the forces for singularities",
                      bad, when, step_h, settings.integrator));
    }
  };

  std::vector<double> g_prev;
  for (const Event& e : events) {
    if (!e.g) throw InvalidArgument(fmt::format("event '{}' has no function g", e.name));
    if (!from) g_prev.push_back(evaluate(e, state));
  }
  if (from) g_prev = from->event_values;
  // Reports the crossings of one step in time order; the state of a stopping event ends the run.
  auto report = [&](const Hit& hit, SystemState& out) {
    out = to_state(settings.formulation, hit.x);
    if (hooks.on_event) hooks.on_event(EventHit{events[hit.event].name, hit.event, out});
    if (!events[hit.event].stop) return false;
    emit(out);
    return true;
  };

  if (is_adaptive(settings.integrator)) {
    const auto integrator = make_adaptive_integrator(settings.integrator, settings.tolerances);
    integrator->start(model, settings.formulation, x, std::min(h, std::max(settings.duration, h)));
    bool finished = t_end <= t0;
    if (from) {
      integrator->load_state(from->integrator);
      finished = from->finished;
      // A point after the final sample: x is that sample's state (the step's end is clipped to t_end).
      if (finished) return to_state(settings.formulation, x);
    }
    // A run point after a step that held samples: nothing of the step is pending then.
    auto keep = [&](const SystemCoordinates& at) {
      if (!hooks.run_point) return;
      RunPoint& p = *hooks.run_point;
      p.t0 = t0;
      p.x = at;
      p.next_sample = k_out;
      p.t_last_sample = std::min(t0 + static_cast<double>(k_out - 1) * dt_out, t_end);
      p.steps_since_sample = 0;
      p.samples = samples;
      p.finished = finished;
      p.stats = integrator->stats();
      p.event_values = g_prev;
      p.integrator = integrator->save_state();
      if (hooks.on_run_point) hooks.on_run_point(p);
    };
    if (!from) keep(x);
    while (!finished) {
      const double t_a = integrator->current_time();
      integrator->step();
      const double t_b = std::min(integrator->current_time(), t_end);
      const SystemCoordinates x_b = integrator->interpolate(t_b);
      check(x_b, integrator->stats().steps, t_b - t_a);
      if (stats) *stats = integrator->stats();
      const std::vector<Hit> hits =
          events.empty() ? std::vector<Hit>{}
                         : find_hits(events, g_prev, settings.formulation, x_b, t_a, t_b - t_a,
                                     [&](double tau) { return integrator->interpolate(t_a + tau); });
      // Samples and crossings inside this step, in time order.
      size_t next_hit = 0;
      bool sampled = false;
      while (true) {
        const double t_sample = std::min(t0 + static_cast<double>(k_out) * dt_out, t_end);
        const bool hit_first = next_hit < hits.size() && t_a + hits[next_hit].tau <= std::min(t_sample, t_b);
        if (hit_first) {
          if (report(hits[next_hit++], state)) return state;
          continue;
        }
        if (t_sample > t_b) break;
        x = integrator->interpolate(t_sample);
        ++k_out;
        to_state(settings.formulation, x, state);  // reuses the storage: no allocation per sample
        finished = t_sample >= t_end;
        sampled = true;
        if (!emit(state)) return state;
        if (finished) break;
      }
      if (sampled) keep(x_b);
      if (!finished && stop_requested && stop_requested()) {
        state = to_state(settings.formulation, x_b);
        emit(state);
        return state;
      }
    }
    return state;
  }

  const auto integrator = make_integrator(settings.integrator);
  integrator->set_threads(settings.threads);
  long step = 0;
  // A step shorter than this fraction of h is rounding of the sample grid, not a real step.
  const double tiny = 1e-9 * h;
  SystemCoordinates x_prev;
  const bool chunks = events.empty() && integrator->fuses_steps(model);
  double t_last_sample = t0;
  long steps_since_sample = 0;
  if (from) {
    integrator->load_state(model, settings.formulation, from->integrator);
    step = from->stats.steps;
    t_last_sample = from->t_last_sample;
    steps_since_sample = from->steps_since_sample;
  }
  // A run point right after a sample on the grid: nothing of the step is pending then.
  auto keep = [&] {
    if (!hooks.run_point) return;
    RunPoint& p = *hooks.run_point;
    p.t0 = t0;
    p.x = x;
    p.next_sample = k_out;
    p.t_last_sample = t_last_sample;
    p.steps_since_sample = steps_since_sample;
    p.samples = samples;
    p.finished = !(x.t < t_end - tiny);
    p.stats = {step, 0,
               integrator->evaluations_counted().value_or(step * integrator->evaluations_per_step())};
    p.event_values = g_prev;
    p.integrator = integrator->save_state();
    if (hooks.on_run_point) hooks.on_run_point(p);
  };
  if (!from) keep();
  while (x.t < t_end - tiny) {
    const double t_sample = std::min(t0 + static_cast<double>(k_out) * dt_out, t_end);
    if (chunks) {
      // Full steps that end before the sample time need nothing between them: hand them over together
      // (Integrator::steps, bit for bit the same), so fused integrators keep each block of bodies in
      // cache across them. The chunk is bounded so that Ctrl-C is still answered promptly.
      long count = 0;
      for (double t = x.t; count < kChunk && t_sample - t > h + tiny && t + h < t_sample - tiny; t += h) {
        ++count;
      }
      if (count > 1) {
        const double t_start = x.t;
        integrator->steps(model, settings.formulation, x, h, count);
        step += count;
        steps_since_sample += count;
        x.t = t_last_sample + static_cast<double>(steps_since_sample) * h;  // the clock on its grid
        if (stats) {
          *stats = {step, 0,
                    integrator->evaluations_counted().value_or(step * integrator->evaluations_per_step())};
        }
        check(x, step, h, count, t_start);
        if (stop_requested && stop_requested()) {
          to_state(settings.formulation, x, state);
          emit(state);
          return state;
        }
        continue;
      }
    }
    // The step that reaches the sample time (or comes within `tiny` of it, by the rounding of the
    // accumulated time) is the remaining interval: x.t + (t_sample − x.t) is t_sample exactly when
    // x.t ≥ t_sample / 2 (Sterbenz), so the state is computed at the sample time itself.
    const double remaining = t_sample - x.t;
    const double step_h = remaining <= h + tiny ? remaining : h;
    if (!events.empty()) x_prev = x;
    integrator->step(model, settings.formulation, x, step_h);
    ++step;
    if (stats) {
      *stats = {step, 0,
                integrator->evaluations_counted().value_or(step * integrator->evaluations_per_step())};
    }
    // The clock on the grid t_sample_prev + n h (one rounding), not a running sum whose roundings add
    // up (1e-12 s per 1e3 steps): the remaining interval before a sample, and the times integrators
    // that keep a flow across steps evaluate it at, stay exact.
    ++steps_since_sample;
    x.t = x.t >= t_sample - tiny ? t_sample : t_last_sample + static_cast<double>(steps_since_sample) * h;
    check(x, step, step_h);
    if (!events.empty()) {
      const auto hits = find_hits(events, g_prev, settings.formulation, x, x_prev.t, step_h, [&](double tau) {
        SystemCoordinates y = x_prev;
        integrator->step(model, settings.formulation, y, tau);
        return y;
      });
      for (const Hit& hit : hits) {
        if (report(hit, state)) return state;
      }
    }
    const bool stop = stop_requested && stop_requested();
    if (x.t == t_sample || stop) {
      const bool on_grid = x.t == t_sample;
      if (on_grid) {
        ++k_out;
        t_last_sample = t_sample;
        steps_since_sample = 0;
      }
      to_state(settings.formulation, x, state);  // reuses the storage: no allocation per sample
      const bool go_on = emit(state);
      if (on_grid) keep();
      if (!go_on || stop) return state;
    }
  }
  return to_state(settings.formulation, x);
}

}  // namespace tumble
