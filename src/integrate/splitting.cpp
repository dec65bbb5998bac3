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
// The loads at the end of a step are the loads at the start of the next: they are kept (with a copy of
// the state they belong to, to notice a state changed between steps), so a step costs one force
// evaluation (three for splitting4). The kick and the drift of a body follow its loads in the same
// pass over the block. The exact flow is per body (its regimes branch on values); it allocates nothing.
//
// A body that feels no torque keeps its flow. When neither half kick changes ω (a free body, uniform
// gravity, forces through the centre of mass), L_w is unchanged and consecutive drifts compose into one
// torque-free motion from the state entering the first of them. Each body's FreeFlight keeps that
// EulerPoinsot, the time τ along it and the q, ω the last drift left (in the formulation's variables); a
// drift whose entering q, ω equal those bit for bit, with the same Λ, evaluates the kept flow at τ + h
// instead of setting up a new one. Anything else (a torque in either half kick, a state changed by the
// caller between steps, other moments, another formulation) sets up a fresh flow, and the step is then
// what it was when every drift set one up, bit for bit (tests/integrate/splitting_reuse_test.cpp).
// splitting4's substeps add signed lengths to τ (the middle one is negative); nothing else changes.
//  - Cost: the set-up (0.7 µs) is saved, and q and ω_b share one evaluation of sn, cn, dn
//    (EulerPoinsot::state costs what q(t) alone did, 0.4–0.5 µs, where q(t) and ω_b(t) took 0.6–0.7):
//    build/release/bin/euler_poinsot_bench. A torque-free body-step went from 1.5 µs to 0.6 µs
//    (80× an RK4 body-step → 30×): `build/release/bin/batch_throughput out.csv 3 1000000
//    splitting,splitting4,rk4 1,2`, free boxes under gravity, 1 thread, N = 10⁴: 6.8e5 → 1.7e6
//    body-steps/s (splitting4 2.3e5 → 5.8e5), best median of four interleaved runs on a shared machine
//    (docs/performance.md, bench/results/amd-epyc-avx512/splitting_reuse.txt).
//  - Accuracy: nothing is rounded between steps. A fresh flow every step rounds q and ω every step, and
//    the flips of a tumbling body amplify it: 2e-10 rad after 1e5 steps of the T-handle, against 0 for
//    the kept flow, which is the exact flow from the first state evaluated at the summed time. Its own
//    error at τ is the rounding of its phases, ≤ 1.4 ε|ω|τ measured up to τ = 1e4 s against a long-double
//    reference: the attitude error that rounding τ itself to a double makes (euler_poinsot_test.cpp).
//  - No periodic re-anchoring: a new flow from the state every 10 s was 35× less accurate at 1e4 s. Each
//    anchor rounds the state; E and |L|, so the frequencies, then random-walk, and the phase error grows
//    faster than the rounding of τ, which is all one flow commits.
//  - τ is summed with compensation (TwoSum): a plain τ += h carries the rounding of every addition,
//    3.7e-10 rad after 2e4 steps of 5 ms in the tests, more than setting up a flow every step.
//  - Memory: one FreeFlight per body, ~1 KB (an EulerPoinsot holds its flow by value, no heap), sized on
//    the first step of a run.
#include <cmath>
#include <cstring>
#include <optional>
#include <vector>

#include "engine.hpp"
#include "methods.hpp"
#include "saved_state.hpp"
#include "tumble/integrate/euler_poinsot.hpp"

namespace tumble {
namespace {

class Strang {
 public:
  void step(const Model& model, Formulation F, SystemCoordinates& x, double h, int threads) {
    engine_.prepare(model, F, threads);
    const size_t n = x.bodies.size();
    loads_.ensure(n, 6);
    if (flights_.size() != n || F != flights_formulation_) {  // the first step of a run: allocates
      flights_.assign(n, FreeFlight{});
      flights_formulation_ = F;
    }
    const bool reuse = cached_ && same(x);
    // K(h/2) with the loads at the start, then D(h), body by body.
    auto kick_drift = [&](const engine::Block& blk, bool fresh) {
      for (size_t i = blk.begin; i < std::min(blk.end, n); ++i) {
        Coordinates<double> c = x.bodies.load(i);
        const Vec3 f = fresh ? blk.force<double>(i) : cached(0, i),
                   tau = fresh ? blk.torque<double>(i) : cached(3, i);
        kick(F, c, 0.5 * h, f, tau, engine_.m<double>(i), engine_.Lambda<double>(i));
        drift(F, c, h, engine_.Lambda<double>(i), flights_[i]);
        x.bodies.store(i, c);
      }
    };
    if (reuse) {
      engine_.for_each_block(n, [&](const engine::Block& blk) { kick_drift(blk, false); });
      for (size_t p = 0; p < x.particles.size(); ++p)
        x.particles[p].v += 0.5 * h * particle_loads_[p] / model.particles[p].mass;
    } else {
      engine_.evaluate(x, [&](const engine::Block& blk) { kick_drift(blk, true); });
      for (size_t p = 0; p < x.particles.size(); ++p)
        x.particles[p].v += 0.5 * h * engine_.particle_rates(p, x.particles[p]).v;
    }
    for (auto& p : x.particles) p.x += h * p.v;
    x.t += h;
    // K(h/2) with the loads at the end, which are kept for the next step.
    engine_.evaluate(x, [&](const engine::Block& blk) {
      for (size_t i = blk.begin; i < std::min(blk.end, n); ++i) {
        Coordinates<double> c = x.bodies.load(i);
        const Vec3 f = blk.force<double>(i), tau = blk.torque<double>(i);
        for (size_t k = 0; k < 3; ++k) {
          loads_[k][i] = f(static_cast<Eigen::Index>(k));
          loads_[3 + k][i] = tau(static_cast<Eigen::Index>(k));
        }
        kick(F, c, 0.5 * h, f, tau, engine_.m<double>(i), engine_.Lambda<double>(i));
        x.bodies.store(i, c);
      }
    });
    particle_loads_.assign(engine_.particle_forces().begin(), engine_.particle_forces().end());
    for (size_t p = 0; p < x.particles.size(); ++p)
      x.particles[p].v += 0.5 * h * particle_loads_[p] / model.particles[p].mass;
    remember(x);
  }

  /// The kept flows (each as the state it was set up from: setting it up again gives the same flow,
  /// bit for bit), the end loads and the state they belong to.
  void save(std::vector<double>& out) const {
    saved::Writer w(out);
    w.put(static_cast<double>(flights_.size()));
    w.put(static_cast<double>(flights_formulation_));
    for (const FreeFlight& ff : flights_) {
      w.put(ff.flow ? 1.0 : 0.0);
      w.put(ff.q0), w.put(ff.w0);
      w.put(ff.tau), w.put(ff.tau_lo);
      w.put(ff.q), w.put(ff.omega);
    }
    w.put(cached_ ? 1.0 : 0.0);
    if (!cached_) return;
    w.put(loads_);
    w.put(particle_loads_);
    w.put(state_);
    w.put(particles_);
    w.put(t_);
  }

  void load(const Model& model, saved::Reader& r) {
    const size_t n = model.bodies.size(), np = model.particles.size();
    const size_t count = r.count(n);
    if (count != n && count != 0) r.fail();
    flights_formulation_ = static_cast<Formulation>(r.count(2));
    flights_.assign(count, FreeFlight{});
    for (size_t i = 0; i < count; ++i) {
      FreeFlight& ff = flights_[i];
      const bool has_flow = r.flag();
      ff.q0 = r.quat(), ff.w0 = r.vec3();
      ff.tau = r.get(), ff.tau_lo = r.get();
      ff.q = r.quat(), ff.omega = r.vec3();
      if (has_flow) ff.flow.emplace(model.bodies[i].Lambda(), ff.q0, ff.w0);
    }
    cached_ = r.flag();
    if (!cached_) return;
    r.columns(loads_, 6, n);
    particle_loads_ = r.vec3s(np);
    r.columns(state_, BodyColumns::kCount, n);
    particles_ = r.particles(np);
    t_ = r.get();
  }

 private:
  Vec3 cached(size_t first, size_t i) const {
    return {loads_[first][i], loads_[first + 1][i], loads_[first + 2][i]};
  }

  void remember(const SystemCoordinates& x) {
    state_ = x.bodies;  // same shape from the second step on: a copy, no allocation
    particles_ = x.particles;
    t_ = x.t;
    cached_ = true;
  }
  bool same(const SystemCoordinates& x) const { return x.t == t_ && same_variables(x, state_, particles_); }

  /// K(τ): v += τ f/m and L_w += τ τ_w with the pose frozen, in the formulation's variables.
  static void kick(Formulation F, Coordinates<double>& c, double tau, const Vec3& f_w, const Vec3& tau_w,
                   double m, const Vec3& Lambda) {
    const Quat q_inv = c.q.conjugate();
    const Vec3 dv_w = tau * f_w / m;
    const Vec3 dw_b = tau * (q_inv * tau_w).cwiseQuotient(Lambda);  // Λ⁻¹ Rᵀ Δl
    c.v += F == Formulation::body ? Vec3(q_inv * dv_w) : dv_w;
    c.omega += F == Formulation::world ? Vec3(c.q * dw_b) : dw_b;
  }

  /// A body's torque-free motion since the last torque (or change of its state), kept between steps.
  struct FreeFlight {
    std::optional<EulerPoinsot> flow;  // from the body's state at the start of the first drift of the run
    Quat q0{1.0, 0.0, 0.0, 0.0};       // that state: q and ^bω (a checkpoint stores these, not the flow)
    Vec3 w0 = Vec3::Zero();
    double tau = 0.0, tau_lo = 0.0;  // time along it: the drifts' h summed, compensated (τ + τ_lo)
    Quat q{1.0, 0.0, 0.0, 0.0};      // what the last drift left: q and ω in the formulation's variables
    Vec3 omega = Vec3::Zero();
  };

  /// D(h): the exact force-free, torque-free motion. When the rotational state entering the drift is,
  /// bit for bit, what the body's last drift left (no torque in the kicks since, nobody changed it) and
  /// Λ is the same, the motion continues the flow set up then: it is evaluated at τ + h.
  static void drift(Formulation F, Coordinates<double>& c, double h, const Vec3& Lambda, FreeFlight& ff) {
    const Vec3 v_w = F == Formulation::body ? Vec3(c.q * c.v) : c.v;
    c.o += h * v_w;
    if (ff.flow && c.q.coeffs() == ff.q.coeffs() && c.omega == ff.omega && ff.flow->Lambda() == Lambda) {
      // τ += h by Knuth's TwoSum: the rounding error of each addition is exact and kept in τ_lo.
      const double s = ff.tau + h, b = s - ff.tau;
      ff.tau_lo += (ff.tau - (s - b)) + (h - b);
      ff.tau = s;
    } else {
      const Vec3 w_b = F == Formulation::world ? Vec3(c.q.conjugate() * c.omega) : c.omega;
      ff.flow.emplace(Lambda, c.q, w_b);
      ff.q0 = c.q;
      ff.w0 = w_b;
      ff.tau = h;
      ff.tau_lo = 0.0;
    }
    const EulerPoinsot::State s = ff.flow->state(ff.tau + ff.tau_lo);
    c.q = s.q;
    c.omega = F == Formulation::world ? Vec3(c.q * s.omega_b) : s.omega_b;
    if (F == Formulation::body) c.v = c.q.conjugate() * v_w;
    ff.q = c.q;
    ff.omega = c.omega;
  }

  engine::Engine engine_;
  std::vector<FreeFlight> flights_;  // one per body
  Formulation flights_formulation_ = Formulation::mixed;
  Columns loads_;  // loads at the end of the last step: f (3), τ (3)
  std::vector<Vec3> particle_loads_;
  bool cached_ = false;
  BodyColumns state_;  // the state they belong to
  std::vector<ParticleState> particles_;
  double t_ = 0.0;
};

/// What the splitting methods share: the Strang step with its kept flows, and their saving for resume.
class StrangIntegrator : public Integrator {
 public:
  std::vector<double> save_state() const override {
    std::vector<double> out;
    strang_.save(out);
    return out;
  }
  void load_state(const Model& model, Formulation, const std::vector<double>& state) override {
    saved::Reader r(state, name());
    strang_.load(model, r);
    r.done();
  }

 protected:
  Strang strang_;
};

class Splitting2 final : public StrangIntegrator {
 public:
  std::string name() const override { return "splitting"; }
  int order() const override { return 2; }
  int evaluations_per_step() const override { return 1; }
  void step(const Model& model, Formulation F, SystemCoordinates& x, double h) override {
    strang_.step(model, F, x, h, threads_);
  }
};

class Splitting4 final : public StrangIntegrator {
 public:
  std::string name() const override { return "splitting4"; }
  int order() const override { return 4; }
  int evaluations_per_step() const override { return 3; }
  void step(const Model& model, Formulation F, SystemCoordinates& x, double h) override {
    static const double w1 = 1.0 / (2.0 - std::cbrt(2.0));
    static const double w0 = 1.0 - 2.0 * w1;
    const double t_end = x.t + h;
    strang_.step(model, F, x, w1 * h, threads_);
    strang_.step(model, F, x, w0 * h, threads_);
    strang_.step(model, F, x, w1 * h, threads_);
    x.t = t_end;  // the three substeps add to h up to rounding
  }
};

}  // namespace

namespace methods {
std::unique_ptr<Integrator> splitting() { return std::make_unique<Splitting2>(); }
std::unique_ptr<Integrator> splitting4() { return std::make_unique<Splitting4>(); }
}  // namespace methods

}  // namespace tumble
