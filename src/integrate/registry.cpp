// Integrators by name.
#include <fmt/format.h>

#include <cmath>
#include <functional>
#include <map>

#include "methods.hpp"
#include "tumble/error.hpp"

namespace tumble {
namespace {

const std::map<std::string, std::function<std::unique_ptr<Integrator>()>>& fixed_step() {
  static const std::map<std::string, std::function<std::unique_ptr<Integrator>()>> r = {
      {"euler", methods::explicit_euler},
      {"semi_implicit_euler", methods::semi_implicit_euler},
      {"rk4", methods::rk4},
      {"lie_rk4", methods::lie_rk4},
      {"implicit_gyro", methods::implicit_gyro},
      {"splitting", methods::splitting},
      {"splitting4", methods::splitting4},
      {"midpoint", methods::implicit_midpoint},
      {"exact", methods::exact},
  };
  return r;
}

const std::map<std::string, std::function<std::unique_ptr<AdaptiveIntegrator>(const Tolerances&)>>&
adaptive() {
  static const std::map<std::string, std::function<std::unique_ptr<AdaptiveIntegrator>(const Tolerances&)>>
      r = {
          {"dopri45", methods::dopri45},
      };
  return r;
}

std::string unknown(const std::string& name) {
  return fmt::format("unknown integrator '{}'; choose one of: {}", name, fmt::join(integrator_names(), ", "));
}

}  // namespace

void Integrator::load_state(const Model& /*model*/, Formulation /*formulation*/,
                            const std::vector<double>& state) {
  if (!state.empty()) {
    throw InvalidArgument(fmt::format(
        "integrator '{}' keeps nothing between steps, but was given a saved state of {} values (saved by "
        "another integrator)",
        name(), state.size()));
  }
}

namespace {
[[noreturn]] void refuse_tangent(const std::string& name) {
  throw InvalidArgument(
      fmt::format("integrator '{}' does not differentiate its steps yet: sensitivities are given by {}", name,
                  fmt::join(differentiating_integrators(), ", ")));
}
}  // namespace

void AdaptiveIntegrator::start_tangent(const Model&, Formulation, const TangentCoordinates&) {
  refuse_tangent(name());
}
void AdaptiveIntegrator::step_tangent() { refuse_tangent(name()); }
TangentCoordinates AdaptiveIntegrator::interpolate_tangent(double) const { refuse_tangent(name()); }

std::vector<std::string> differentiating_integrators() {
  // Those that override step_tangent (tests/sim/sensitivities_test.cpp runs each, and checks that the
  // others refuse).
  return {"dopri45",   "euler",     "exact", "implicit_gyro",
          "lie_rk4",   "midpoint",  "rk4",   "semi_implicit_euler",
          "splitting", "splitting4"};
}

void Integrator::step_tangent(const Model& /*model*/, Formulation /*formulation*/, TangentCoordinates& /*x*/,
                              double /*h*/) {
  refuse_tangent(name());
}

std::vector<std::string> integrator_names() {
  std::vector<std::string> names;
  for (const auto& entry : fixed_step()) names.push_back(entry.first);
  for (const auto& entry : adaptive()) names.push_back(entry.first);
  std::sort(names.begin(), names.end());
  return names;
}

bool is_adaptive(const std::string& name) { return adaptive().count(name) > 0; }

std::unique_ptr<Integrator> make_integrator(const std::string& name) {
  const auto it = fixed_step().find(name);
  if (it != fixed_step().end()) return it->second();
  if (is_adaptive(name)) {
    throw InvalidArgument(
        fmt::format("integrator '{}' is adaptive: it takes tolerances, not a fixed step", name));
  }
  throw InvalidArgument(unknown(name));
}

std::unique_ptr<AdaptiveIntegrator> make_adaptive_integrator(const std::string& name, const Tolerances& tol) {
  const auto it = adaptive().find(name);
  if (it == adaptive().end()) throw InvalidArgument(unknown(name));
  if (!(std::isfinite(tol.relative) && tol.relative > 0 && std::isfinite(tol.absolute) && tol.absolute > 0)) {
    throw InvalidArgument(fmt::format(
        "tolerances relative = {}, absolute = {} are invalid: give positive numbers, e.g. 1e-9 and 1e-12",
        tol.relative, tol.absolute));
  }
  return it->second(tol);
}

Formulation parse_formulation(const std::string& name) {
  if (name == "world") return Formulation::world;
  if (name == "mixed") return Formulation::mixed;
  if (name == "body") return Formulation::body;
  throw InvalidArgument(fmt::format("unknown formulation '{}'; choose world, mixed or body", name));
}

std::string formulation_name(Formulation formulation) {
  switch (formulation) {
    case Formulation::world:
      return "world";
    case Formulation::mixed:
      return "mixed";
    case Formulation::body:
      return "body";
  }
  return "?";
}

}  // namespace tumble
