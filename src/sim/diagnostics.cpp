#include "tumble/sim/diagnostics.hpp"

#include "tumble/dynamics/quantities.hpp"

namespace tumble {

void add_body_invariants(const RigidBody& b, const Coordinates<double>& x, Formulation F, Invariants& inv) {
  const Vec3 omega_b = F == Formulation::world ? rotate_inverse<double>(x.q, x.omega) : x.omega;
  const Vec3 v = F == Formulation::body ? rotate<double>(x.q, x.v) : x.v;
  const Vec3 p = b.mass() * v;  // p = m v
  // ½ m v·v + ½ ^bω·Λ^bω (the kinetic_energy of quantities.hpp, term by term)
  inv.kinetic_energy += 0.5 * b.mass() * v.squaredNorm() +
                        0.5 * omega_b.dot(b.Lambda().cwiseProduct(omega_b));
  inv.linear_momentum += p;
  inv.angular_momentum += x.o.cross(p) +
                          rotate<double>(x.q, Vec3(b.Lambda().cwiseProduct(omega_b)));  // o × p + Iω
}

Invariants invariants(const Model& model, Formulation F, const SystemCoordinates& x, size_t first,
                      SystemState& scratch) {
  Invariants inv;
  const size_t n = model.bodies.size();
  for (size_t i = 0; i < n; ++i) add_body_invariants(model.bodies[i], x.bodies.load(first + i), F, inv);
  for (size_t i = 0; i < model.particles.size(); ++i) {
    const Particle& p = model.particles[i];
    const ParticleState& s = x.particles[i];
    inv.kinetic_energy += 0.5 * p.mass * s.v.squaredNorm();
    inv.linear_momentum += momentum(p, s);
    inv.angular_momentum += angular_momentum(p, s);
  }
  if (model.forces.empty()) {
    inv.potential_energy = 0.0;
    return inv;
  }
  to_state(F, x, first, n, scratch);
  scratch.particles = x.particles;
  double V = 0.0;
  const SystemView view = model.view(scratch);
  for (const auto& f : model.forces) {
    const auto Vf = f->potential_energy(view);
    if (!Vf) return inv;  // a non-conservative model: no total energy
    V += *Vf;
  }
  inv.potential_energy = V;
  return inv;
}

Invariants invariants(const Model& model, const SystemState& state) {
  Invariants inv;
  for (size_t i = 0; i < model.bodies.size(); ++i) {
    const RigidBody& b = model.bodies[i];
    const BodyState& s = state.bodies[i];
    // kinetic_energy, linear_momentum and angular_momentum_about(b, s, 0) term by term, with ^bω and
    // m v formed once: the same operations, so the same bits (a study evaluates this every sample).
    const Vec3 omega_b = s.omega_b(), p = linear_momentum(b, s);
    inv.kinetic_energy += kinetic_energy_translational(b, s) +
                          0.5 * omega_b.dot(b.Lambda().cwiseProduct(omega_b));
    inv.linear_momentum += p;
    inv.angular_momentum += s.o.cross(p) + rotate<double>(s.q, Vec3(b.Lambda().cwiseProduct(omega_b)));
  }
  for (size_t i = 0; i < model.particles.size(); ++i) {
    const Particle& p = model.particles[i];
    const ParticleState& s = state.particles[i];
    inv.kinetic_energy += 0.5 * p.mass * s.v.squaredNorm();
    inv.linear_momentum += momentum(p, s);
    inv.angular_momentum += angular_momentum(p, s);
  }
  double V = 0.0;
  const SystemView view = model.view(state);
  for (const auto& f : model.forces) {
    const auto Vf = f->potential_energy(view);
    if (!Vf) return inv;  // a non-conservative model: no total energy
    V += *Vf;
  }
  inv.potential_energy = V;
  return inv;
}

}  // namespace tumble
