#include "tumble/sim/diagnostics.hpp"

#include "tumble/dynamics/quantities.hpp"

namespace tumble {

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
