#include "tumble/sim/event_specs.hpp"

#include <algorithm>
#include <cmath>

#include "tumble/dynamics/quantities.hpp"

namespace tumble {

Event make_event(const Model& model, const EventSpec& spec) {
  Event e{spec.name, {}, spec.direction, spec.stop};
  const size_t r = spec.row;
  const bool body = r < model.bodies.size();
  if (spec.kind == EventSpec::Kind::column) {
    e.g = [&model, r, field = spec.field, k = spec.component, value = spec.value](const SystemState& s) {
      double x[4];
      field_of_row(*field, model, s, r, x);
      return x[k] - value;  // g = x_k − value
    };
    if (!body) return e;
    // Every step, from the body's own variables (VariableColumn: ^bω is the mixed formulation's ω).
    e.body = r;
    const VariableColumn column(*spec.field, spec.component);
    e.g_variables = [&b = model.bodies[r], column, value = spec.value](
                        const BodyColumns& x, size_t i, Formulation F) { return column(b, x, i, F) - value; };
    Event::Variable v{.value = spec.value};
    for (const Formulation F : {Formulation::world, Formulation::mixed, Formulation::body})
      v.column[static_cast<size_t>(F)] = column.variable(F);
    if (std::any_of(v.column.begin(), v.column.end(), [](int c) { return c >= 0; })) e.variable = v;
    return e;
  }
  const Vec3 d = spec.toward.normalized();
  e.g = [&model, r, a = spec.axis.normalized(), d, angle = spec.angle](const SystemState& s) {
    // R_ref a = R Uᵀ a; a particle has the identity orientation, its axis stays as given.
    const Vec3 a_w = r < model.bodies.size() ? Vec3(s.bodies[r].q * Vec3(model.bodies[r].U().transpose() * a))
                                             : a;
    return std::atan2(a_w.cross(d).norm(), a_w.dot(d)) - angle;  // g = ∠(R_ref a, d) − θ
  };
  if (!body) return e;
  e.body = r;
  e.g_variables = [a_b = Vec3(model.bodies[r].U().transpose() * spec.axis.normalized()), d,
                   angle = spec.angle](const BodyColumns& x, size_t i, Formulation) {
    const Quat q(x[BodyColumns::q][i], x[BodyColumns::q + 1][i], x[BodyColumns::q + 2][i],
                 x[BodyColumns::q + 3][i]);
    const Vec3 a_w = rotate<double>(q, a_b);  // the same bits as q * (Uᵀ a) on the state
    return std::atan2(a_w.cross(d).norm(), a_w.dot(d)) - angle;
  };
  return e;
}

std::vector<Event> make_events(const Model& model, const std::vector<EventSpec>& specs) {
  std::vector<Event> events;
  events.reserve(specs.size());
  for (const EventSpec& s : specs) events.push_back(make_event(model, s));
  return events;
}

}  // namespace tumble
