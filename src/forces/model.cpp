#include "tumble/forces/model.hpp"

#include <fmt/format.h>

#include "tumble/error.hpp"

namespace tumble {

size_t Model::body_index(const std::string& name) const {
  for (size_t i = 0; i < bodies.size(); ++i) {
    if (bodies[i].name() == name) return i;
  }
  std::vector<std::string> names;  // for the message only
  for (const RigidBody& b : bodies) names.push_back("'" + b.name() + "'");
  throw InvalidArgument(fmt::format("no body named '{}'; the bodies are {}", name,
                                    names.empty() ? "none" : fmt::format("{}", fmt::join(names, ", "))));
}

void evaluate_loads(const Model& model, const SystemState& state, Loads& loads) {
  loads.reset(model.bodies.size(), model.particles.size());
  for (const auto& force : model.forces) force->check(model.bodies.size(), model.particles.size());
  const SystemView view = model.view(state);
  for (const auto& force : model.forces) force->accumulate(view, loads);
}

Loads evaluate_loads(const Model& model, const SystemState& state) {
  Loads loads;
  evaluate_loads(model, state, loads);
  return loads;
}

}  // namespace tumble
