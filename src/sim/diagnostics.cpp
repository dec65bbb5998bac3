#include "tumble/sim/diagnostics.hpp"

#include "tumble/dynamics/quantities.hpp"

namespace tumble {

void add_body_invariants(const RigidBody& b, const Coordinates<double>& x, Formulation F, Invariants& inv) {
  BodySums<double> sum;
  add_body_sums<double>(b.mass(), b.Lambda(), x, F, sum);
  inv.kinetic_energy += sum.kinetic_energy;
  inv.linear_momentum += sum.linear_momentum;
  inv.angular_momentum += sum.angular_momentum;
}

namespace {

/// The particles' share of the invariants, and the potential energy of every force model at `view`
/// (nullopt when one has none).
void add_particles_and_potential(const Model& model, const std::vector<ParticleState>& particles,
                                 const SystemView& view, Invariants& inv) {
  for (size_t i = 0; i < model.particles.size(); ++i) {
    const Particle& p = model.particles[i];
    const ParticleState& s = particles[i];
    inv.kinetic_energy += 0.5 * p.mass * s.v.squaredNorm();
    inv.linear_momentum += momentum(p, s);
    inv.angular_momentum += angular_momentum(p, s);
  }
  // What the models' own parts carry (rotors' spin): L = Σ (o × p + R(Λω + h)) stays conserved.
  for (const auto& f : model.forces) inv.angular_momentum += f->internal_angular_momentum(view);
  double V = 0.0;
  for (const auto& f : model.forces) {
    const auto Vf = f->potential_energy(view);
    if (!Vf) return;  // a non-conservative model: no total energy
    V += *Vf;
  }
  inv.potential_energy = V;
}

}  // namespace

Invariants invariants(const Model& model, Formulation F, const SystemCoordinates& x, size_t first,
                      SystemState& scratch) {
  Invariants inv;
  const size_t n = model.bodies.size();
  for (size_t i = 0; i < n; ++i) add_body_invariants(model.bodies[i], x.bodies.load(first + i), F, inv);
  SystemView view;  // the potentials need the bodies' states: converted only when there are forces
  if (!model.forces.empty()) {
    to_state(F, x, first, n, scratch);
    scratch.particles = x.particles;
    view = model.view(scratch);
  }
  add_particles_and_potential(model, x.particles, view, inv);
  return inv;
}

Invariants invariants(const Model& model, const SystemState& state) {
  Invariants inv;
  for (size_t i = 0; i < model.bodies.size(); ++i) {
    const BodyState& s = state.bodies[i];
    add_body_invariants(model.bodies[i], Coordinates<double>{s.o, s.q, s.v, s.omega_b()}, Formulation::mixed,
                        inv);
  }
  add_particles_and_potential(model, state.particles, model.view(state), inv);
  return inv;
}

}  // namespace tumble
