// Fixed-step integrators of the dynamics issue: explicit Euler, semi-implicit Euler, classic RK4.
#include "methods.hpp"

namespace tumble {
namespace {

/// x_{n+1} = x_n + h f(x_n). First order; gains energy on a free rotor (shown in the tests).
class ExplicitEuler final : public Integrator {
 public:
  std::string name() const override { return "euler"; }
  int order() const override { return 1; }
  int evaluations_per_step() const override { return 1; }
  void step(const Model& model, Formulation F, SystemCoordinates& x, double h) const override {
    x = advance(x, h, system_rates(model, F, x));
  }
};

/// Semi-implicit (symplectic) Euler: velocities first, v_{n+1} = v_n + h v̇(x_n), then positions and
/// orientation with the new velocities, o_{n+1} = o_n + h ȯ(v_{n+1}), q_{n+1} = q_n + h q̇(ω_{n+1}).
class SemiImplicitEuler final : public Integrator {
 public:
  std::string name() const override { return "semi_implicit_euler"; }
  int order() const override { return 1; }
  int evaluations_per_step() const override { return 1; }
  void step(const Model& model, Formulation F, SystemCoordinates& x, double h) const override {
    const SystemRates k = system_rates(model, F, x);
    for (size_t i = 0; i < x.bodies.size(); ++i) {
      auto& c = x.bodies[i];
      c.v += h * k.bodies[i].v_dot;
      c.omega += h * k.bodies[i].omega_dot;
      const auto [o_dot, q_dot] = kinematics<double>(F, c);  // with the updated velocities
      c.o += h * o_dot;
      c.q.coeffs() += h * q_dot.coeffs();
      c.q.normalize();
    }
    for (size_t i = 0; i < x.particles.size(); ++i) {
      x.particles[i].v += h * k.particles[i].v;
      x.particles[i].x += h * x.particles[i].v;
    }
    x.t += h;
  }
};

/// The classic fourth-order Runge–Kutta method; stage quaternions are renormalised.
class RungeKutta4 final : public Integrator {
 public:
  std::string name() const override { return "rk4"; }
  int order() const override { return 4; }
  int evaluations_per_step() const override { return 4; }
  void step(const Model& model, Formulation F, SystemCoordinates& x, double h) const override {
    const SystemRates k1 = system_rates(model, F, x);
    const SystemRates k2 = system_rates(model, F, advance(x, h / 2, k1));
    const SystemRates k3 = system_rates(model, F, advance(x, h / 2, k2));
    const SystemRates k4 = system_rates(model, F, advance(x, h, k3));
    const SystemRates k = combine({{1.0 / 6, &k1}, {2.0 / 6, &k2}, {2.0 / 6, &k3}, {1.0 / 6, &k4}});
    x = advance(x, h, k);
  }
};

}  // namespace

namespace methods {
std::unique_ptr<Integrator> explicit_euler() { return std::make_unique<ExplicitEuler>(); }
std::unique_ptr<Integrator> semi_implicit_euler() { return std::make_unique<SemiImplicitEuler>(); }
std::unique_ptr<Integrator> rk4() { return std::make_unique<RungeKutta4>(); }
}  // namespace methods

}  // namespace tumble
