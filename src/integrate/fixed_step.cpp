// Fixed-step integrators of the dynamics issue: explicit Euler, semi-implicit Euler, classic RK4, on
// the batched engine: each stage is one pass over the bodies, a pack at a time.
#include "engine.hpp"
#include "methods.hpp"

namespace tumble {
namespace {

using engine::Block;
using engine::kWidth;
using engine::Pack;

/// x_{n+1} = x_n + h f(x_n). First order; gains energy on a free rotor (shown in the tests).
class ExplicitEuler final : public Integrator {
 public:
  std::string name() const override { return "euler"; }
  int order() const override { return 1; }
  int evaluations_per_step() const override { return 1; }
  void step(const Model& model, Formulation F, SystemCoordinates& x, double h) override {
    engine_.prepare(model, F, threads_);
    engine_.evaluate(x, [&](const Block& b) {
      for (size_t i = b.begin; i < b.end; i += kWidth) {
        const Coordinates<Pack> c = x.bodies.load<Pack>(i);
        x.bodies.store(i, advanced<Pack>(c, Pack(h), engine_.rates<Pack>(b, i, c)));
      }
    });
    for (size_t p = 0; p < x.particles.size(); ++p) {
      x.particles[p] = advanced(x.particles[p], h, engine_.particle_rates(p, x.particles[p]));
    }
    x.t += h;
  }

 private:
  engine::Engine engine_;
};

/// Semi-implicit (symplectic) Euler: velocities first, v_{n+1} = v_n + h v̇(x_n), then positions and
/// orientation with the new velocities, o_{n+1} = o_n + h ȯ(v_{n+1}), q_{n+1} = q_n + h q̇(ω_{n+1}).
class SemiImplicitEuler final : public Integrator {
 public:
  std::string name() const override { return "semi_implicit_euler"; }
  int order() const override { return 1; }
  int evaluations_per_step() const override { return 1; }
  void step(const Model& model, Formulation F, SystemCoordinates& x, double h) override {
    engine_.prepare(model, F, threads_);
    const Pack hp(h);
    engine_.evaluate(x, [&](const Block& b) {
      for (size_t i = b.begin; i < b.end; i += kWidth) {
        Coordinates<Pack> c = x.bodies.load<Pack>(i);
        const CoordinateRates<Pack> k = engine_.rates<Pack>(b, i, c);
        c.v += hp * k.v_dot;
        c.omega += hp * k.omega_dot;
        const auto [o_dot, q_dot] = kinematics<Pack>(F, c);  // with the updated velocities
        c.o += hp * o_dot;
        c.q = normalized<Pack>(QuatT<Pack>(c.q.coeffs() + hp * q_dot.coeffs()));
        x.bodies.store(i, c);
      }
    });
    for (size_t p = 0; p < x.particles.size(); ++p) {
      ParticleState& s = x.particles[p];
      s.v += h * engine_.particle_rates(p, s).v;
      s.x += h * s.v;
    }
    x.t += h;
  }

 private:
  engine::Engine engine_;
};

/// The classic fourth-order Runge–Kutta method; stage quaternions are renormalised. Written in the
/// low-storage form each stage can finish a body before the next body starts:
///   stage s = 1…4:  k_s = f(t + c_s h, y_s),  A += b_s k_s,  y_{s+1} = x + c_{s+1} h k_s,
///   x_{n+1} = x + (h/6) A,  with c = (0, ½, ½, 1), b = (1, 2, 2, 1), y_1 = x.
/// The whole-system arrays are x, y and A: 39 doubles per body.
class RungeKutta4 final : public Integrator {
 public:
  std::string name() const override { return "rk4"; }
  int order() const override { return 4; }
  int evaluations_per_step() const override { return 4; }
  void step(const Model& model, Formulation F, SystemCoordinates& x, double h) override {
    static constexpr double c[4] = {0.0, 0.5, 0.5, 1.0}, b[4] = {1.0, 2.0, 2.0, 1.0};
    engine_.prepare(model, F, threads_);
    const size_t n = x.bodies.size(), np = x.particles.size();
    y_.bodies.ensure(n);
    A_.ensure(n);
    y_.particles.resize(np);
    A_particles_.resize(np);
    for (int s = 0; s < 4; ++s) {
      const SystemCoordinates& in = s == 0 ? x : y_;
      if (s < 3) {
        const Pack step_next(c[s + 1] * h), weight(b[s]);
        engine_.evaluate(in, [&](const Block& blk) {
          for (size_t i = blk.begin; i < blk.end; i += kWidth) {
            const CoordinateRates<Pack> k = engine_.rates<Pack>(blk, i, in.bodies.load<Pack>(i));
            A_.store(i, s == 0 ? k : axpy<Pack>(A_.load_rates<Pack>(i), weight, k));
            y_.bodies.store(i, advanced<Pack>(x.bodies.load<Pack>(i), step_next, k));
          }
        });
        for (size_t p = 0; p < np; ++p) {
          const ParticleState k = engine_.particle_rates(p, in.particles[p]);
          A_particles_[p] = s == 0 ? k : axpy(A_particles_[p], b[s], k);
          y_.particles[p] = advanced(x.particles[p], c[s + 1] * h, k);
        }
        y_.t = x.t + c[s + 1] * h;
      } else {
        const Pack h6(h / 6);
        engine_.evaluate(in, [&](const Block& blk) {
          for (size_t i = blk.begin; i < blk.end; i += kWidth) {
            const CoordinateRates<Pack> k = engine_.rates<Pack>(blk, i, in.bodies.load<Pack>(i));
            x.bodies.store(i, advanced<Pack>(x.bodies.load<Pack>(i), h6, axpy<Pack>(A_.load_rates<Pack>(i), Pack(1.0), k)));
          }
        });
        for (size_t p = 0; p < np; ++p) {
          const ParticleState k = engine_.particle_rates(p, in.particles[p]);
          x.particles[p] = advanced(x.particles[p], h / 6, axpy(A_particles_[p], 1.0, k));
        }
      }
    }
    x.t += h;
  }

 private:
  engine::Engine engine_;
  SystemCoordinates y_;
  BodyColumns A_;
  std::vector<ParticleState> A_particles_;
};

}  // namespace

namespace methods {
std::unique_ptr<Integrator> explicit_euler() { return std::make_unique<ExplicitEuler>(); }
std::unique_ptr<Integrator> semi_implicit_euler() { return std::make_unique<SemiImplicitEuler>(); }
std::unique_ptr<Integrator> rk4() { return std::make_unique<RungeKutta4>(); }
}  // namespace methods

}  // namespace tumble
