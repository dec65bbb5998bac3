#include "tumble/sim/diagnostics.hpp"

#include "tumble/dynamics/quantities.hpp"

namespace tumble {

Invariants invariants(const Model& model, const SystemState& state) {
  Invariants inv;
  for (size_t i = 0; i < model.bodies.size(); ++i) {
    const RigidBody& b = model.bodies[i];
    const BodyState& s = state.bodies[i];
    inv.kinetic_energy += kinetic_energy(b, s);
    inv.linear_momentum += linear_momentum(b, s);
    inv.angular_momentum += angular_momentum_about(b, s, Vec3::Zero());
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
