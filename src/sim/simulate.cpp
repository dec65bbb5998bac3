#include "tumble/sim/simulate.hpp"

#include <algorithm>
#include <cmath>
#include <tuple>
#include <fmt/format.h>

#include "tumble/error.hpp"

namespace tumble {
namespace {

void require(bool ok, const std::string& message) {
  if (!ok) throw InvalidArgument(message);
}

/// The first non-finite body or particle in `state`, as a message; empty if all is finite.
std::string non_finite(const Model& model, const SystemCoordinates& state) {
  for (size_t i = 0; i < state.bodies.size(); ++i) {
    const Coordinates<double>& s = state.bodies[i];
    if (!s.o.allFinite() || !s.q.coeffs().allFinite() || !s.v.allFinite() || !s.omega.allFinite()) {
      return fmt::format("body '{}'", model.bodies[i].name());
    }
  }
  for (size_t i = 0; i < state.particles.size(); ++i) {
    if (!state.particles[i].x.allFinite() || !state.particles[i].v.allFinite()) {
      return fmt::format("particle '{}'", model.particles[i].name);
    }
  }
  return {};
}

/// The earliest crossing of `event` inside the step of length h from x0 (where g = g0), located by
/// bisection on the length of a single step from x0 taken with the run's integrator.
std::pair<double, SystemCoordinates> locate(const Integrator& integrator, const Model& model, Formulation F,
                                            const SystemCoordinates& x0, double h, const Event& event,
                                            double g0) {
  double lo = 0.0, hi = h;
  SystemCoordinates at_hi;
  bool have_hi = false;
  const double resolution = 4 * 2.220446049250313e-16 * std::max(std::abs(x0.t), h);
  for (int i = 0; i < 200 && (hi - lo > resolution || !have_hi); ++i) {
    const double mid = have_hi ? 0.5 * (lo + hi) : hi;
    SystemCoordinates y = x0;
    integrator.step(model, F, y, mid);
    const double g = event.g(to_state(F, y));
    if ((g0 < 0) == (g < 0) && g != 0 && have_hi) {
      lo = mid;
    } else {
      hi = mid;
      at_hi = std::move(y);
      have_hi = true;
    }
  }
  return {hi, at_hi};
}

bool crosses(const Event& e, double g0, double g1) {
  const bool rising = g0 < 0 && g1 >= 0, falling = g0 > 0 && g1 <= 0;
  return (rising && e.direction >= 0) || (falling && e.direction <= 0);
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

SystemState simulate(const Model& model, SystemState state, const RunSettings& settings, const RunHooks& hooks) {
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
  SystemCoordinates x = to_coordinates(settings.formulation, state);
  if (const std::string bad = non_finite(model, x); !bad.empty()) {
    throw InvalidArgument(fmt::format("initial state of {} is not finite", bad));
  }
  const double t0 = state.t;
  const double t_end = t0 + settings.duration;
  const double h = settings.timestep;
  // Sample times are t₀ + k·Δ, computed from k (not accumulated) so they do not drift.
  const double dt_out = settings.output_interval > 0 ? settings.output_interval : h;
  long k_out = 1;
  if (on_sample && !on_sample(state)) return state;
  auto check = [&](const SystemCoordinates& y, long step, double step_h) {
    if (const std::string bad = non_finite(model, y); !bad.empty()) {
      throw Error(fmt::format(
          "the state of {} became non-finite at t = {} s (step {}, h = {} s, integrator {}); reduce "
          "the timestep (or tolerances) or check the forces for singularities",
          bad, y.t, step, step_h, settings.integrator));
    }
  };

  if (is_adaptive(settings.integrator)) {
    if (!events.empty()) {
      throw InvalidArgument(fmt::format(
          "events need a fixed-step integrator (they re-step within a step to locate the crossing); "
          "'{}' is adaptive: use rk4, splitting or another fixed-step method",
          settings.integrator));
    }
    const auto integrator = make_adaptive_integrator(settings.integrator, settings.tolerances);
    integrator->start(model, settings.formulation, x, std::min(h, std::max(settings.duration, h)));
    while (true) {
      const double t_sample = std::min(t0 + static_cast<double>(k_out) * dt_out, t_end);
      if (t_sample <= x.t) break;
      x = integrator->at(t_sample);
      check(x, integrator->stats().steps, 0.0);
      ++k_out;
      state = to_state(settings.formulation, x);
      if (stats) *stats = integrator->stats();
      if (on_sample && !on_sample(state)) return state;
      if (stop_requested && stop_requested()) return state;
    }
    return to_state(settings.formulation, x);
  }

  const auto integrator = make_integrator(settings.integrator);
  long step = 0;
  // A step shorter than this fraction of h is rounding of the sample grid, not a real step.
  const double tiny = 1e-9 * h;
  std::vector<double> g_prev;
  for (const Event& e : events) g_prev.push_back(e.g(state));
  SystemCoordinates x_prev;
  while (x.t < t_end - tiny) {
    const double t_sample = std::min(t0 + static_cast<double>(k_out) * dt_out, t_end);
    const double step_h = std::min(h, t_sample - x.t);
    if (!events.empty()) x_prev = x;
    integrator->step(model, settings.formulation, x, step_h);
    ++step;
    if (stats) {
      *stats = {step, 0, integrator->evaluations_counted().value_or(step * integrator->evaluations_per_step())};
    }
    if (x.t >= t_sample - tiny) x.t = t_sample;  // remove the rounding of the accumulated time
    check(x, step, step_h);
    if (!events.empty()) {
      // Every crossing in this step, located and reported in time order; a stopping one ends the run.
      const SystemState after = to_state(settings.formulation, x);
      std::vector<std::tuple<double, size_t, SystemCoordinates>> hits;
      for (size_t i = 0; i < events.size(); ++i) {
        const double g1 = events[i].g(after);
        if (crosses(events[i], g_prev[i], g1)) {
          auto [tau, y] = locate(*integrator, model, settings.formulation, x_prev, step_h, events[i], g_prev[i]);
          hits.emplace_back(tau, i, std::move(y));
        }
        g_prev[i] = g1;
      }
      std::sort(hits.begin(), hits.end(), [](const auto& a, const auto& b) { return std::get<0>(a) < std::get<0>(b); });
      for (const auto& [tau, i, y] : hits) {
        const SystemState at = to_state(settings.formulation, y);
        if (hooks.on_event) hooks.on_event(EventHit{events[i].name, at});
        if (events[i].stop) {
          if (on_sample) on_sample(at);
          return at;
        }
      }
    }
    const bool stop = stop_requested && stop_requested();
    if (x.t == t_sample || stop) {
      if (x.t == t_sample) ++k_out;
      state = to_state(settings.formulation, x);
      if (on_sample && !on_sample(state)) return state;
      if (stop) return state;
    }
  }
  return to_state(settings.formulation, x);
}

}  // namespace tumble
