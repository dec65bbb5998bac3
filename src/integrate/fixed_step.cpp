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
/// low-storage form in which each stage can finish a body before the next body starts:
///   stage s = 1…4:  k_s = f(t + c_s h, y_s),  A += b_s k_s,  y_{s+1} = x + c_{s+1} h k_s,
///   x_{n+1} = x + (h/6) A,  with c = (0, ½, ½, 1), b = (1, 2, 2, 1), y_1 = x.
/// Fused (engine.hpp), a block's y and A live in cache and the step reads and writes x once.
class RungeKutta4 final : public Integrator {
 public:
  std::string name() const override { return "rk4"; }
  int order() const override { return 4; }
  int evaluations_per_step() const override { return 4; }
  void step(const Model& model, Formulation F, SystemCoordinates& x, double h) override {
    static constexpr double c[4] = {0.0, 0.5, 0.5, 1.0}, b[4] = {1.0, 2.0, 2.0, 1.0};
    engine_.prepare(model, F, threads_, 2);
    const size_t n = x.bodies.size(), np = x.particles.size();
    const BodyColumnsRef xr = x.bodies.ref();
    // Stage s of the bodies of one block, from the stage state `in`, with y, A in the block's work.
    auto stage = [&](int s, const Block& blk, const BodyColumnsRef& in) {
      const BodyColumnsRef &y = blk.work[0], &A = blk.work[1];
      if (s < 3) {
        const Pack step_next(c[s + 1] * h), weight(b[s]);
        for (size_t i = blk.begin; i < blk.end; i += kWidth) {
          const CoordinateRates<Pack> k = engine_.rates<Pack>(blk, i, in.load<Pack>(i));
          A.store(i, s == 0 ? k : axpy<Pack>(A.load_rates<Pack>(i), weight, k));
          y.store(i, advanced<Pack>(xr.load<Pack>(i), step_next, k));
        }
      } else {
        const Pack h6(h / 6), one(1.0);
        for (size_t i = blk.begin; i < blk.end; i += kWidth) {
          const CoordinateRates<Pack> k = engine_.rates<Pack>(blk, i, in.load<Pack>(i));
          xr.store(i, advanced<Pack>(xr.load<Pack>(i), h6, axpy<Pack>(A.load_rates<Pack>(i), one, k)));
        }
      }
    };
    if (engine_.fused()) {
      engine_.for_each_fused_block(n, [&](engine::Engine::FusedBlock& fb) {
        for (int s = 0; s < 4; ++s) {
          const BodyColumnsRef in = s == 0 ? xr : fb.work(0);
          stage(s, fb.evaluate(in, x.t + c[s] * h), in);
        }
      });
    } else {
      y_.bodies.ensure(n);
      A_.ensure(n);
      y_.particles.resize(np);
      A_particles_.resize(np);
      for (int s = 0; s < 4; ++s) {
        const SystemCoordinates& in = s == 0 ? x : y_;
        const BodyColumnsRef in_ref = in.bodies.ref();
        engine_.evaluate(in, [&](const Block& blk) { stage(s, blk, in_ref); }, {&y_.bodies, &A_});
        for (size_t p = 0; p < np; ++p) {
          const ParticleState k = engine_.particle_rates(p, in.particles[p]);
          if (s < 3) {
            A_particles_[p] = s == 0 ? k : axpy(A_particles_[p], b[s], k);
            y_.particles[p] = advanced(x.particles[p], c[s + 1] * h, k);
          } else {
            x.particles[p] = advanced(x.particles[p], h / 6, axpy(A_particles_[p], 1.0, k));
          }
        }
        y_.t = x.t + (s < 3 ? c[s + 1] : 1.0) * h;
      }
    }
    x.t += h;
  }

 private:
  engine::Engine engine_;
  SystemCoordinates y_;  // staged steps only: the stage state and A as whole-system columns
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
