// exact: the analytic motion, evaluated at each step's end from one anchor; no stepping.
//
// When every force is a uniform field g (none, or uniform gravity) no torque acts about any centre of
// mass, so each body's rotation is the Euler–Poinsot motion from its initial state (EulerPoinsot) —
// or, for a body whose rotors' motors hold their speeds (constant h), the torque-free gyrostat's
// (GyrostatFlow) — and its centre of mass, like each particle, follows the parabola
//   o(t) = o₀ + v₀ τ + ½ g τ²,  v(t) = v₀ + g τ,  τ = t − t₀.
// Every state is evaluated from the anchor (t₀ and the state there), so a sample at 100 s carries the
// rounding of one evaluation, not of 10⁵ steps: the timestep only sets where a run may stop. A state
// that is not the one this integrator produced last (an event located by restarting inside a step, a
// user changing the state) becomes the new anchor.
#include <fmt/format.h>

#include <cmath>
#include <cstring>
#include <map>
#include <vector>

#include "engine.hpp"
#include "free_flow_tangent.hpp"
#include "gyrostat_flow.hpp"
#include "methods.hpp"
#include "saved_state.hpp"
#include "tumble/error.hpp"
#include "tumble/forces/rotors.hpp"
#include "tumble/integrate/euler_poinsot.hpp"

namespace tumble {
namespace {

class Exact final : public Integrator {
 public:
  std::string name() const override { return "exact"; }
  int order() const override { return 0; }  // no discretisation error to have an order
  int evaluations_per_step() const override { return 0; }

  /// The same evaluation on dual numbers: the parabola, and each body's rotation from its anchor by the
  /// exact flow differentiated (FreeFlowTangent) — in closed form at τ from the anchor where it is
  /// differentiable, else by its Taylor series over this step from the last state (the values still the
  /// anchor's flow at τ).
  void step_tangent(const Model& model, Formulation F, TangentCoordinates& x, double h) override {
    using T = TangentScalar;
    check(model);
    if (rotors_of(model) != nullptr) {
      throw InvalidArgument(
          "integrator 'exact' has no derivatives through rotors (the gyrostat's exact flow is not "
          "differentiated); use 'splitting' or 'rk4' for sensitivities of a body with rotors");
    }
    const size_t n = x.bodies.size();
    if (tangent_model_ != &model || F != tangent_formulation_ || tangent_flows_.size() != n ||
        !(std::abs(x.t - tangent_t_) <= 1e-9 * std::abs(h))) {
      tangent_model_ = &model;
      tangent_formulation_ = F;
      tangent_t0_ = x.t;
      g_.setZero();
      for (const auto& force : model.forces) g_ += *force->uniform_acceleration();
      tangent_flows_.clear();
      tangent_o0_.clear();
      tangent_v0_.clear();
      for (size_t i = 0; i < n; ++i) {
        const Coordinates<T>& c = x.bodies[i];
        tangent_flows_.emplace_back(x.Lambda[i], c.q,
                                    F == Formulation::world ? rotate_inverse<T>(c.q, c.omega) : c.omega);
        tangent_o0_.push_back(c.o);
        tangent_v0_.push_back(F == Formulation::body ? rotate<T>(c.q, c.v) : c.v);
      }
    }
    const double t = x.t + h, tau = t - tangent_t0_;
    const Vec3T<T> g = g_.cast<T>();
    for (size_t i = 0; i < n; ++i) {
      Coordinates<T>& c = x.bodies[i];
      const FreeFlowTangent& flow = tangent_flows_[i];
      detail::FlowState<T> s;
      if (flow.closed_form()) {
        s = flow.at(tau);
      } else {
        s = FreeFlowTangent(x.Lambda[i], c.q,
                            F == Formulation::world ? rotate_inverse<T>(c.q, c.omega) : c.omega)
                .at(h);
        set_values(s, flow.values().state(tau));
      }
      const Vec3T<T> v_w = tangent_v0_[i] + T(tau) * g;
      c.o = tangent_o0_[i] + T(tau) * tangent_v0_[i] + T(0.5 * tau * tau) * g;
      c.q = s.q;
      c.v = F == Formulation::body ? rotate_inverse<T>(c.q, v_w) : v_w;
      c.omega = F == Formulation::world ? rotate<T>(c.q, s.omega_b) : s.omega_b;
    }
    x.t = t;
    tangent_t_ = t;
  }
  void check(const Model& model) const override {
    for (const auto& force : model.forces) {
      if (const auto* rotors = dynamic_cast<const Rotors*>(force.get())) {
        if (rotors->motors_work() || rotors->input_interval() > 0) {
          throw InvalidArgument(
              "integrator 'exact' solves a body with rotors only while their motors hold their speeds "
              "(constant h: no motor torque, table or controller); with motors working use "
              "'splitting' (second order, total angular momentum kept to rounding) or 'rk4'");
        }
        continue;
      }
      if (!force->uniform_acceleration()) {
        throw InvalidArgument(fmt::format(
            "integrator 'exact' solves torque-free motion only (no forces, or uniform gravity), but the "
            "scene has {}; use 'splitting', which is exact for the free motion and second order in the "
            "forces (or 'splitting4' for fourth order)",
            force->describe(model.bodies)));
      }
    }
  }

  /// A run hands many steps at once: the end state is evaluated once.
  bool fuses_steps(const Model&) const override { return true; }

  void step(const Model& model, Formulation F, SystemCoordinates& x, double h) override {
    steps(model, F, x, h, 1);
  }

  void steps(const Model& model, Formulation F, SystemCoordinates& x, double h, long count) override {
    check(model);
    engine_.prepare(model, F, threads_);
    if (!on_trajectory(model, F, x, h)) anchor(model, F, x);
    double t = x.t;
    for (long r = 0; r < count; ++r) t += h;  // the times step-by-step calls would reach
    evaluate(model, F, t, x);
    last_ = x.bodies;  // same shape after the first step: a copy, no allocation
    last_particles_ = x.particles;
    last_t_ = x.t;
    last_h_ = h;
  }

  /// The anchor as the state it was taken from (anchoring there again gives the same flows, bit for
  /// bit) and the last state produced.
  std::vector<double> save_state() const override {
    std::vector<double> out;
    saved::Writer w(out);
    w.put(model_ != nullptr ? 1.0 : 0.0);
    if (model_ == nullptr) return out;
    w.put(static_cast<double>(formulation_));
    w.put(anchor_);
    w.put(last_), w.put(last_particles_);
    w.put(last_t_), w.put(last_h_);
    return out;
  }
  void load_state(const Model& model, Formulation, const std::vector<double>& state) override {
    saved::Reader r(state, name());
    model_ = nullptr;
    if (r.flag()) {
      const auto F = static_cast<Formulation>(r.count(2));
      const size_t n = model.bodies.size(), np = model.particles.size();
      const SystemCoordinates anchor_state = r.coordinates(n, np);
      if (anchor_state.bodies.size() != n) r.fail();
      anchor(model, F, anchor_state);
      r.columns(last_, BodyColumns::kCount, n);
      last_particles_ = r.particles(np);
      last_t_ = r.get(), last_h_ = r.get();
    }
    r.done();
  }

 private:
  /// Whether x is the state this integrator produced last, for this model and formulation. Its time
  /// may have been moved by rounding (simulate() snaps the time of a sample onto its grid).
  bool on_trajectory(const Model& model, Formulation F, const SystemCoordinates& x, double h) const {
    if (model_ != &model || F != formulation_ || flows_.size() != model.bodies.size() ||
        !(std::abs(x.t - last_t_) <= 1e-9 * std::max(std::abs(h), std::abs(last_h_)))) {
      return false;
    }
    return same_variables(x, last_, last_particles_);
  }

  void anchor(const Model& model, Formulation F, const SystemCoordinates& x) {
    model_ = &model;
    formulation_ = F;
    t0_ = x.t;
    g_.setZero();
    for (const auto& force : model.forces)
      g_ += force->uniform_acceleration().value_or(Vec3::Zero());  // rotors: none
    flows_.clear();
    gyrostats_.clear();
    o0_.clear();
    v0_.clear();
    const Rotors* rotors = rotors_of(model);
    for (size_t i = 0; i < x.bodies.size(); ++i) {
      const Coordinates<double> c = x.bodies.load(i);
      // ^bω and world v in the formulation's own variables, without a rotation where they already are.
      const Vec3 w_b = F == Formulation::world ? Vec3(c.q.conjugate() * c.omega) : c.omega;
      const Vec3 h = rotors != nullptr ? rotors->momentum(i, x.t).first : Vec3::Zero();
      if (h != Vec3::Zero()) gyrostats_.emplace(i, GyrostatFlow(model.bodies[i].Lambda(), h, c.q, w_b));
      flows_.emplace_back(model.bodies[i].Lambda(), c.q, w_b);
      o0_.push_back(c.o);
      v0_.push_back(F == Formulation::body ? Vec3(c.q * c.v) : c.v);
    }
    particles0_ = x.particles;
    anchor_ = x;
  }

  void evaluate(const Model& model, Formulation F, double t, SystemCoordinates& x) {
    const double tau = t - t0_;
    const size_t n = model.bodies.size();
    engine_.for_each_block(n, [&](const engine::Block& blk) {
      for (size_t i = blk.begin; i < std::min(blk.end, n); ++i) {
        Coordinates<double> c;
        Vec3 w_b;
        if (const auto g = gyrostats_.find(i); g != gyrostats_.end()) {
          const GyrostatFlow::State s = g->second.state(tau);
          // q or −q, the one nearer the last state's: the output stays continuous.
          c.q = s.q.dot(x.bodies.load(i).q) < 0 ? Quat(-s.q.coeffs()) : s.q;
          w_b = s.omega_b;
        } else {
          c.q = flows_[i].q(tau);
          w_b = flows_[i].omega_b(tau);
        }
        const Vec3 v_w = v0_[i] + tau * g_;
        c.o = o0_[i] + tau * v0_[i] + (0.5 * tau * tau) * g_;
        c.v = F == Formulation::body ? Vec3(c.q.conjugate() * v_w) : v_w;
        c.omega = F == Formulation::world ? Vec3(c.q * w_b) : w_b;
        x.bodies.store(i, c);
      }
    });
    for (size_t p = 0; p < x.particles.size(); ++p) {
      const ParticleState& s0 = particles0_[p];
      x.particles[p] = {s0.x + tau * s0.v + (0.5 * tau * tau) * g_, s0.v + tau * g_};
    }
    x.t = t;
  }

  engine::Engine engine_;
  const Model* model_ = nullptr;
  Formulation formulation_ = Formulation::mixed;
  double t0_ = 0.0;
  Vec3 g_ = Vec3::Zero();
  std::vector<EulerPoinsot> flows_;           // per body, from the anchor
  std::map<size_t, GyrostatFlow> gyrostats_;  // the bodies with rotors (h ≠ 0), from the anchor
  std::vector<Vec3> o0_, v0_;                 // centre of mass and its velocity (world) at the anchor
  std::vector<ParticleState> particles0_;
  SystemCoordinates anchor_;  // the state anchored at
  BodyColumns last_;          // what the last step produced
  std::vector<ParticleState> last_particles_;
  double last_t_ = 0.0, last_h_ = 0.0;
  // step_tangent's anchor: its time, the flows on dual numbers, the centre of mass and its velocity.
  const Model* tangent_model_ = nullptr;
  Formulation tangent_formulation_ = Formulation::mixed;
  double tangent_t0_ = 0.0, tangent_t_ = 0.0;
  std::vector<FreeFlowTangent> tangent_flows_;
  std::vector<Vec3T<TangentScalar>> tangent_o0_, tangent_v0_;
};

}  // namespace

namespace methods {
std::unique_ptr<Integrator> exact() { return std::make_unique<Exact>(); }
}  // namespace methods

}  // namespace tumble
