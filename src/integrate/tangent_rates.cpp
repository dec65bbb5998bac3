#include "tumble/integrate/tangent_system.hpp"

namespace tumble {

std::span<const WrenchT<TangentScalar>> TangentRates::loads(const Model& model, Formulation formulation,
                                                            const TangentCoordinates& y) {
  const size_t n = y.bodies.size();
  states_.resize(n);
  loads_.assign(n, WrenchT<TangentScalar>{});
  // World velocities cost rotations on dual numbers (12 % of a step): formed only when a model reads them.
  bool velocities = false;
  for (const auto& force : model.forces) velocities = velocities || force->needs_velocity();
  for (size_t i = 0; i < n; ++i) {
    const Coordinates<TangentScalar>& c = y.bodies[i];
    states_[i] = velocities ? world_state<TangentScalar>(formulation, c, y.m[i], y.Lambda[i])
                            : BodyStateT<TangentScalar>{c.o, c.q, {}, {}, y.m[i], y.Lambda[i]};
  }
  TangentView view{y.t, model.bodies, states_, {}};
  for (size_t k = 0; k < model.forces.size(); ++k) {
    const ForceModel& force = *model.forces[k];
    if (k < y.force_parameters.size()) {
      view.parameters = y.force_parameters[k];
    } else {  // unseeded: the values
      unseeded_.clear();
      for (const ForceParameter& p : force.parameters()) unseeded_.emplace_back(p.value);
      view.parameters = unseeded_;
    }
    force.accumulate_tangent(view, loads_);
  }
  return loads_;
}

void TangentRates::rates(const Model& model, Formulation formulation, const TangentCoordinates& y,
                         std::vector<CoordinateRates<TangentScalar>>& rates) {
  using T = TangentScalar;
  loads(model, formulation, y);
  rates.resize(y.bodies.size());
  for (size_t i = 0; i < y.bodies.size(); ++i) {
    const MassConstants<T> c = mass_constants<T>(y.m[i], y.Lambda[i]);
    rates[i] = newton_euler<T>(formulation, c, y.bodies[i], loads_[i].force, loads_[i].torque);
  }
}

}  // namespace tumble
