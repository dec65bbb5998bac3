#include "tumble/sim/simulate.hpp"

#include <cmath>
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
  while (x.t < t_end - tiny) {
    const double t_sample = std::min(t0 + static_cast<double>(k_out) * dt_out, t_end);
    const double step_h = std::min(h, t_sample - x.t);
    integrator->step(model, settings.formulation, x, step_h);
    ++step;
    if (stats) {
      *stats = {step, 0, integrator->evaluations_counted().value_or(step * integrator->evaluations_per_step())};
    }
    if (x.t >= t_sample - tiny) x.t = t_sample;  // remove the rounding of the accumulated time
    check(x, step, step_h);
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
