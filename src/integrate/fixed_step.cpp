// Fixed-step integrators of the dynamics issue: explicit Euler, semi-implicit Euler, classic RK4, on
// the batched engine: each stage is one pass over the bodies, a pack at a time.
#include "engine.hpp"
#include "methods.hpp"
#include "rk4_steps.hpp"
#include "tangent_packs.hpp"

namespace tumble {
namespace {

using engine::Block;
using engine::kWidth;
using engine::Pack;

/// `count` steps of a one-stage method whose bodies' part is kernel(const Block&), after the loads of
/// the block at the step's start; particle(p, state) steps particle p with the loads of its step.
template <class Kernel, class ParticleStep>
void one_stage_steps(engine::Engine& engine, SystemCoordinates& x, double h, long count, Kernel&& kernel,
                     ParticleStep&& particle) {
  if (engine.fused()) {
    const BodyColumnsRef xr = x.bodies.ref();
    engine.fused_steps(x, h, count,
                       [&](engine::Engine::FusedBlock& fb, double t) { kernel(fb.evaluate(xr, t)); });
    return;
  }
  for (long r = 0; r < count; ++r) {
    engine.evaluate(x, kernel);
    for (size_t p = 0; p < x.particles.size(); ++p) particle(p, x.particles[p]);
    x.t += h;
  }
}

/// x_{n+1} = x_n + h f(x_n). First order; gains energy on a free rotor (shown in the tests).
class ExplicitEuler final : public Integrator {
 public:
  std::string name() const override { return "euler"; }
  int order() const override { return 1; }
  int evaluations_per_step() const override { return 1; }
  void step(const Model& model, Formulation F, SystemCoordinates& x, double h) override {
    steps(model, F, x, h, 1);
  }
  void step_tangent(const Model& model, Formulation F, TangentCoordinates& x, double h) override {
    tangent_.rates(model, F, x, k_);
    for (size_t i = 0; i < x.bodies.size(); ++i) x.bodies[i] = advanced<TangentScalar>(x.bodies[i], h, k_[i]);
    x.t += h;
  }
  bool fuses_steps(const Model& model) const override { return engine::Engine::fusable(model); }
  void steps(const Model& model, Formulation F, SystemCoordinates& x, double h, long count) override {
    engine_.prepare(model, F, threads_);
    const BodyColumnsRef xr = x.bodies.ref();
    auto kernel = [&](const Block& b) {
      for (size_t i = b.begin; i < b.end; i += kWidth) {
        const Coordinates<Pack> c = xr.load<Pack>(i);
        xr.store(i, advanced<Pack>(c, Pack(h), engine_.rates<Pack>(b, i, c)));
      }
    };
    one_stage_steps(engine_, x, h, count, kernel,
                    [&](size_t p, ParticleState& s) { s = advanced(s, h, engine_.particle_rates(p, s)); });
  }

  bool step_tangents_packed(const Model& model, Formulation F, TangentCoordinates& x,
                            std::span<const double> lengths, int slots) override {
    return tangent_packs::steps(tangent_packs::Method::euler, model, F, x, lengths, slots);
  }

 private:
  engine::Engine engine_;
  TangentRates tangent_;
  std::vector<CoordinateRates<TangentScalar>> k_;
};

/// Semi-implicit (symplectic) Euler: velocities first, v_{n+1} = v_n + h v̇(x_n), then positions and
/// orientation with the new velocities, o_{n+1} = o_n + h ȯ(v_{n+1}), q_{n+1} = q_n + h q̇(ω_{n+1}).
class SemiImplicitEuler final : public Integrator {
 public:
  std::string name() const override { return "semi_implicit_euler"; }
  int order() const override { return 1; }
  int evaluations_per_step() const override { return 1; }
  void step(const Model& model, Formulation F, SystemCoordinates& x, double h) override {
    steps(model, F, x, h, 1);
  }
  bool fuses_steps(const Model& model) const override { return engine::Engine::fusable(model); }
  void steps(const Model& model, Formulation F, SystemCoordinates& x, double h, long count) override {
    engine_.prepare(model, F, threads_);
    const Pack hp(h);
    const BodyColumnsRef xr = x.bodies.ref();
    auto kernel = [&](const Block& b) {
      for (size_t i = b.begin; i < b.end; i += kWidth) {
        const Coordinates<Pack> c = xr.load<Pack>(i);
        xr.store(i, semi_implicit_euler_update<Pack>(F, c, hp, engine_.rates<Pack>(b, i, c)));
      }
    };
    one_stage_steps(engine_, x, h, count, kernel, [&](size_t p, ParticleState& s) {
      s.v += h * engine_.particle_rates(p, s).v;
      s.x += h * s.v;
    });
  }
  void step_tangent(const Model& model, Formulation F, TangentCoordinates& x, double h) override {
    tangent_.rates(model, F, x, k_);
    for (size_t i = 0; i < x.bodies.size(); ++i) {
      x.bodies[i] = semi_implicit_euler_update<TangentScalar>(F, x.bodies[i], h, k_[i]);
    }
    x.t += h;
  }

  bool step_tangents_packed(const Model& model, Formulation F, TangentCoordinates& x,
                            std::span<const double> lengths, int slots) override {
    return tangent_packs::steps(tangent_packs::Method::semi_implicit_euler, model, F, x, lengths, slots);
  }

 private:
  engine::Engine engine_;
  TangentRates tangent_;
  std::vector<CoordinateRates<TangentScalar>> k_;
};

/// The classic fourth-order Runge–Kutta method; stage quaternions are renormalised. The tableau and
/// its low-storage stage loop are in rk4_steps.hpp; fused (engine.hpp), a block's y and A live in cache
/// and the step reads and writes x once.
class RungeKutta4 final : public Integrator {
 public:
  std::string name() const override { return "rk4"; }
  int order() const override { return 4; }
  int evaluations_per_step() const override { return 4; }
  void step(const Model& model, Formulation F, SystemCoordinates& x, double h) override {
    steps(model, F, x, h, 1);
  }
  bool fuses_steps(const Model& model) const override { return engine::Engine::fusable(model); }
  void steps(const Model& model, Formulation F, SystemCoordinates& x, double h, long count) override {
    engine_.prepare(model, F, threads_, 2);
    const BodyColumnsRef xr = x.bodies.ref();
    rk4::steps(engine_, x, h, count, y_, A_particles_, {&y_.bodies, &A_},
               [&](int s, const Block& blk, const BodyColumnsRef& in) {
                 const BodyColumnsRef &y = blk.work[0], &A = blk.work[1];
                 const Pack length(rk4::stage_length(s, h));
                 for (size_t i = blk.begin; i < blk.end; i += kWidth) {
                   const CoordinateRates<Pack> k = engine_.rates<Pack>(blk, i, in.load<Pack>(i));
                   CoordinateRates<Pack> Ai = s == 0 ? k : A.load_rates<Pack>(i);
                   const Coordinates<Pack> next = rk4::stage<Pack>(s, length, xr.load<Pack>(i), k, Ai);
                   if (s < 3) {
                     A.store(i, Ai);
                     y.store(i, next);
                   } else {
                     xr.store(i, next);
                   }
                 }
               });
  }
  void step_tangent(const Model& model, Formulation F, TangentCoordinates& x, double h) override {
    using T = TangentScalar;
    y_tangent_ = x;
    A_tangent_.resize(x.bodies.size());
    for (int s = 0; s < 4; ++s) {
      y_tangent_.t = x.t + rk4::c[s] * h;
      tangent_.rates(model, F, y_tangent_, k_);
      for (size_t i = 0; i < x.bodies.size(); ++i) {
        const Coordinates<T> next =
            rk4::stage<T>(s, rk4::stage_length(s, h), x.bodies[i], k_[i], A_tangent_[i]);
        (s < 3 ? y_tangent_.bodies[i] : x.bodies[i]) = next;
      }
    }
    x.t += h;
  }

  bool step_tangents_packed(const Model& model, Formulation F, TangentCoordinates& x,
                            std::span<const double> lengths, int slots) override {
    return tangent_packs::steps(tangent_packs::Method::rk4, model, F, x, lengths, slots);
  }

 private:
  engine::Engine engine_;
  TangentRates tangent_;
  TangentCoordinates y_tangent_;
  std::vector<CoordinateRates<TangentScalar>> k_, A_tangent_;
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
