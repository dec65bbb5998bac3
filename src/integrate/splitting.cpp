// splitting, splitting4: kick–drift–kick with the exact free flow.
//
// Strang splitting of the equations of motion into the applied wrench ("kick": velocities and angular
// momentum change by the impulse while the pose is frozen) and the torque-free, force-free motion
// ("drift": o moves uniformly, the orientation and ^bω follow the exact Euler–Poinsot solution):
//   S(h) = K(h/2) ∘ D(h) ∘ K(h/2).
// Second order for forces that depend on position and time; exact, at any step, for a free body, and for
// a body under uniform gravity (the kick of a constant force is exact and the translation is then the
// Störmer–Verlet parabola, exact for constant acceleration). Each drift is a rotation and each kick
// changes L_w by hτ, so L_w is conserved exactly (to rounding) when no torque acts, and the free-body
// energy is exact. Velocity-dependent forces (damping, drag) are kicked with the velocities at the
// start of the kick: first order in them.
// splitting4 is Yoshida's fourth-order composition S(w₁h) S(w₀h) S(w₁h), w₁ = 1/(2 − 2^⅓),
// w₀ = 1 − 2w₁ (the middle step runs backwards in time; the exact flow handles that).
//
// The loads at the end of a step are the loads at the start of the next: they are kept, so a step costs
// one force evaluation (three for splitting4). An instance is therefore not to be shared between
// threads (make_integrator gives each simulation its own).
#include <cmath>

#include "methods.hpp"
#include "tumble/integrate/euler_poinsot.hpp"

namespace tumble {
namespace {

class Strang {
 public:
  void step(const Model& model, Formulation F, SystemCoordinates& x, double h) const {
    kick(model, F, x, 0.5 * h, loads_at(model, F, x));
    drift(model, F, x, h);
    x.t += h;
    kick(model, F, x, 0.5 * h, loads_at(model, F, x));
  }

 private:
  const Loads& loads_at(const Model& model, Formulation F, const SystemCoordinates& x) const {
    if (!(cached_ && same(x, cached_x_))) {
      evaluate_loads(model, to_state(F, x), cached_loads_);
      cached_x_ = x;
      cached_ = true;
    }
    return cached_loads_;
  }

  static bool same(const SystemCoordinates& a, const SystemCoordinates& b) {
    if (a.t != b.t || a.bodies.size() != b.bodies.size() || a.particles.size() != b.particles.size()) return false;
    for (size_t i = 0; i < a.bodies.size(); ++i) {
      const auto &p = a.bodies[i], &q = b.bodies[i];
      if (p.o != q.o || p.q.coeffs() != q.q.coeffs() || p.v != q.v || p.omega != q.omega) return false;
    }
    for (size_t i = 0; i < a.particles.size(); ++i) {
      if (a.particles[i].x != b.particles[i].x || a.particles[i].v != b.particles[i].v) return false;
    }
    return true;
  }

  /// K(τ): v += τ f/m and L_w += τ τ_w with the pose frozen, in the formulation's variables.
  static void kick(const Model& model, Formulation F, SystemCoordinates& x, double tau, const Loads& loads) {
    for (size_t i = 0; i < x.bodies.size(); ++i) {
      auto& c = x.bodies[i];
      const RigidBody& b = model.bodies[i];
      const Quat q_inv = c.q.conjugate();
      const Vec3 dv_w = tau * loads.bodies[i].force / b.mass();
      const Vec3 dw_b = tau * (q_inv * loads.bodies[i].torque).cwiseQuotient(b.Lambda());  // Λ⁻¹ Rᵀ Δl
      c.v += F == Formulation::body ? Vec3(q_inv * dv_w) : dv_w;
      c.omega += F == Formulation::world ? Vec3(c.q * dw_b) : dw_b;
    }
    for (size_t i = 0; i < x.particles.size(); ++i) x.particles[i].v += tau * loads.particles[i] / model.particles[i].mass;
  }

  /// D(h): the exact force-free, torque-free motion.
  static void drift(const Model& model, Formulation F, SystemCoordinates& x, double h) {
    for (size_t i = 0; i < x.bodies.size(); ++i) {
      auto& c = x.bodies[i];
      const Vec3 v_w = F == Formulation::body ? Vec3(c.q * c.v) : c.v;
      const Vec3 w_b = F == Formulation::world ? Vec3(c.q.conjugate() * c.omega) : c.omega;
      const EulerPoinsot flow(model.bodies[i].Lambda(), c.q, w_b);
      c.o += h * v_w;
      c.q = flow.q(h);
      const Vec3 w_b_new = flow.omega_b(h);
      c.omega = F == Formulation::world ? Vec3(c.q * w_b_new) : w_b_new;
      if (F == Formulation::body) c.v = c.q.conjugate() * v_w;
    }
    for (auto& p : x.particles) p.x += h * p.v;
  }

  mutable bool cached_ = false;
  mutable SystemCoordinates cached_x_;
  mutable Loads cached_loads_;
};

class Splitting2 final : public Integrator {
 public:
  std::string name() const override { return "splitting"; }
  int order() const override { return 2; }
  int evaluations_per_step() const override { return 1; }
  void step(const Model& model, Formulation F, SystemCoordinates& x, double h) const override {
    strang_.step(model, F, x, h);
  }

 private:
  Strang strang_;
};

class Splitting4 final : public Integrator {
 public:
  std::string name() const override { return "splitting4"; }
  int order() const override { return 4; }
  int evaluations_per_step() const override { return 3; }
  void step(const Model& model, Formulation F, SystemCoordinates& x, double h) const override {
    static const double w1 = 1.0 / (2.0 - std::cbrt(2.0));
    static const double w0 = 1.0 - 2.0 * w1;
    const double t_end = x.t + h;
    strang_.step(model, F, x, w1 * h);
    strang_.step(model, F, x, w0 * h);
    strang_.step(model, F, x, w1 * h);
    x.t = t_end;  // the three substeps add to h up to rounding
  }

 private:
  Strang strang_;
};

}  // namespace

namespace methods {
std::unique_ptr<Integrator> splitting() { return std::make_unique<Splitting2>(); }
std::unique_ptr<Integrator> splitting4() { return std::make_unique<Splitting4>(); }
}  // namespace methods

}  // namespace tumble
