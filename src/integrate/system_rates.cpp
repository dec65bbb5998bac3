#include "tumble/integrate/system_rates.hpp"

namespace tumble {

SystemCoordinates to_coordinates(Formulation formulation, const SystemState& state) {
  SystemCoordinates x;
  x.t = state.t;
  x.bodies.reserve(state.bodies.size());
  for (const BodyState& s : state.bodies) x.bodies.push_back(to_coordinates(formulation, s));
  x.particles = state.particles;
  return x;
}

SystemState to_state(Formulation formulation, const SystemCoordinates& x) {
  SystemState s;
  s.t = x.t;
  s.bodies.reserve(x.bodies.size());
  for (const auto& c : x.bodies) s.bodies.push_back(to_state(formulation, c));
  s.particles = x.particles;
  return s;
}

SystemRates system_rates(const Model& model, Formulation formulation, const SystemCoordinates& x) {
  const Loads loads = evaluate_loads(model, to_state(formulation, x));
  SystemRates k;
  k.bodies.reserve(x.bodies.size());
  for (size_t i = 0; i < x.bodies.size(); ++i) {
    const RigidBody& b = model.bodies[i];
    k.bodies.push_back(newton_euler<double>(formulation, b.mass(), b.Lambda(), x.bodies[i],
                                            loads.bodies[i].force, loads.bodies[i].torque));
  }
  k.particles.reserve(x.particles.size());
  for (size_t i = 0; i < x.particles.size(); ++i) {
    // Newton's second law for a particle: ẋ = v, v̇ = f/m (tutorial, section I).
    k.particles.push_back({x.particles[i].v, loads.particles[i] / model.particles[i].mass});
  }
  return k;
}

SystemCoordinates advance(const SystemCoordinates& x, double h, const SystemRates& k) {
  SystemCoordinates y = x;
  y.t = x.t + h;
  for (size_t i = 0; i < y.bodies.size(); ++i) {
    auto& c = y.bodies[i];
    const auto& r = k.bodies[i];
    c.o += h * r.o_dot;
    c.q.coeffs() += h * r.q_dot.coeffs();
    c.q.normalize();
    c.v += h * r.v_dot;
    c.omega += h * r.omega_dot;
  }
  for (size_t i = 0; i < y.particles.size(); ++i) {
    y.particles[i].x += h * k.particles[i].x;
    y.particles[i].v += h * k.particles[i].v;
  }
  return y;
}

SystemRates combine(std::initializer_list<std::pair<double, const SystemRates*>> terms) {
  SystemRates sum = *terms.begin()->second;
  for (auto& r : sum.bodies) {
    r.o_dot.setZero();
    r.q_dot.coeffs().setZero();
    r.v_dot.setZero();
    r.omega_dot.setZero();
  }
  for (auto& p : sum.particles) p = {Vec3::Zero(), Vec3::Zero()};
  for (const auto& [w, k] : terms) {
    for (size_t i = 0; i < sum.bodies.size(); ++i) {
      sum.bodies[i].o_dot += w * k->bodies[i].o_dot;
      sum.bodies[i].q_dot.coeffs() += w * k->bodies[i].q_dot.coeffs();
      sum.bodies[i].v_dot += w * k->bodies[i].v_dot;
      sum.bodies[i].omega_dot += w * k->bodies[i].omega_dot;
    }
    for (size_t i = 0; i < sum.particles.size(); ++i) {
      sum.particles[i].x += w * k->particles[i].x;
      sum.particles[i].v += w * k->particles[i].v;
    }
  }
  return sum;
}

}  // namespace tumble
