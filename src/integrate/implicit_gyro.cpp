// implicit_gyro: what game engines do for stability at large steps (Catto, GDC 2015; Bullet's default
// since 2015; numerics.md §3). Euler's equation in the body frame is taken backward in time,
//   Λ(ω′ − ω) + h ω′ × Λω′ = h ^bτ,
// solved with ONE Newton step from ω′ = ω:
//   J = Λ + h([ω]×Λ − [Λω]×),   ω′ = ω − J⁻¹ h (ω × Λω − ^bτ);
// velocities then follow semi-implicit Euler and the orientation the exact exponential map
// q ← q ⊗ exp(h ^bω′). First order. Honest about energy: it is stable because it dissipates —
// on the HLW test body (numerics.md) E drops ~17 % in ten periods at h = 0.05 s and the body ends up
// spinning about its major axis; use it for games and controllers, not for physics that must conserve.
#include "methods.hpp"

namespace tumble {
namespace {

class ImplicitGyro final : public Integrator {
 public:
  std::string name() const override { return "implicit_gyro"; }
  int order() const override { return 1; }
  int evaluations_per_step() const override { return 1; }

  void step(const Model& model, Formulation F, SystemCoordinates& x, double h) const override {
    const Loads loads = evaluate_loads(model, to_state(F, x));
    for (size_t i = 0; i < x.bodies.size(); ++i) {
      auto& c = x.bodies[i];
      const RigidBody& b = model.bodies[i];
      const Vec3& Lambda = b.Lambda();
      const Quat q_inv = c.q.conjugate();
      const Vec3 w = F == Formulation::world ? Vec3(q_inv * c.omega) : c.omega;
      const Vec3 tau_b = q_inv * loads.bodies[i].torque;
      const Mat3 J = Mat3(Lambda.asDiagonal()) + h * (skew(w) * Lambda.asDiagonal() - skew<double>(Lambda.cwiseProduct(w)));
      const Vec3 w_new = w - J.partialPivLu().solve(h * (w.cross(Lambda.cwiseProduct(w)) - tau_b));
      const Vec3& f = loads.bodies[i].force;
      if (F == Formulation::body) {
        c.v += h * (q_inv * f / b.mass() - w_new.cross(c.v));
        c.o += h * (c.q * c.v);
      } else {
        c.v += h * f / b.mass();
        c.o += h * c.v;
      }
      c.q = (c.q * quat_exp<double>(h * w_new)).normalized();  // |q| = 1 keeps ω_w ↔ ^bω exact
      c.omega = F == Formulation::world ? Vec3(c.q * w_new) : w_new;
    }
    for (size_t i = 0; i < x.particles.size(); ++i) {
      x.particles[i].v += h * loads.particles[i] / model.particles[i].mass;
      x.particles[i].x += h * x.particles[i].v;
    }
    x.t += h;
  }
};

}  // namespace

namespace methods {
std::unique_ptr<Integrator> implicit_gyro() { return std::make_unique<ImplicitGyro>(); }
}  // namespace methods

}  // namespace tumble
