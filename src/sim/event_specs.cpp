#include "tumble/sim/event_specs.hpp"

#include <cmath>

#include "tumble/dynamics/quantities.hpp"

namespace tumble {

Event make_event(const Model& model, const EventSpec& spec) {
  Event e{spec.name, {}, spec.direction, spec.stop};
  const size_t r = spec.row;
  if (spec.kind == EventSpec::Kind::column) {
    e.g = [&model, r, field = spec.field, k = spec.component, value = spec.value](const SystemState& s) {
      double x[4];
      field_of_row(*field, model, s, r, x);
      return x[k] - value;  // g = x_k − value
    };
    return e;
  }
  const Vec3 d = spec.toward.normalized();
  e.g = [&model, r, a = spec.axis.normalized(), d, angle = spec.angle](const SystemState& s) {
    // R_ref a = R Uᵀ a; a particle has the identity orientation, its axis stays as given.
    const Vec3 a_w = r < model.bodies.size() ? Vec3(s.bodies[r].q * Vec3(model.bodies[r].U().transpose() * a))
                                             : a;
    return std::atan2(a_w.cross(d).norm(), a_w.dot(d)) - angle;  // g = ∠(R_ref a, d) − θ
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
