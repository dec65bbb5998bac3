// dopri45: the adaptive Dormand–Prince 5(4) pair with its continuous extension, from Boost.Odeint
// (runge_kutta_dopri5 in a controlled, dense-output stepper): error control per component, step
// rejection, and dense output so samples land exactly on the requested times.
//
// The state is packed as (o, q, v, ω) per body in the formulation's frames, (x, v) per particle.
// q is renormalised before each right-hand-side evaluation; q̇ = ½ q ⊗ (0, ω) keeps |q| constant in
// exact arithmetic, so |q| − 1 stays at the size of the local error tolerance and is removed at output.
#include <boost/numeric/odeint.hpp>

#include <stdexcept>

#include "engine.hpp"
#include "methods.hpp"
#include "saved_state.hpp"

namespace tumble {
namespace {

namespace odeint = boost::numeric::odeint;
using Packed = std::vector<double>;
constexpr size_t kBody = 13, kParticle = 6;

/// (o, q, v, ω) of every body, then (x, v) of every particle; `columns` holds either variables or rates.
void pack(const BodyColumns& columns, const std::vector<ParticleState>& particles, Packed& p) {
  const size_t n = columns.size();
  p.resize(n * kBody + particles.size() * kParticle);
  double* d = p.data();
  for (size_t i = 0; i < n; ++i, d += kBody) {
    for (size_t k = 0; k < kBody; ++k) d[k] = columns[k][i];
  }
  for (const auto& s : particles) {
    for (Eigen::Index k = 0; k < 3; ++k) d[k] = s.x(k), d[3 + k] = s.v(k);
    d += kParticle;
  }
}

void unpack(const Packed& p, double t, SystemCoordinates& x) {
  x.t = t;
  const double* d = p.data();
  for (size_t i = 0; i < x.bodies.size(); ++i, d += kBody) {
    for (size_t k = 0; k < kBody; ++k) x.bodies[k][i] = d[k];
    x.bodies.store_quat<double>(i, x.bodies.quat(i).normalized());
  }
  for (auto& s : x.particles) {
    s = {Vec3(d[0], d[1], d[2]), Vec3(d[3], d[4], d[5])};
    d += kParticle;
  }
}

// ---- The same steps on dual numbers (sensitivities, issue 25) ----
// Odeint's own Dormand–Prince stepper, instantiated on dual numbers, takes each accepted step again with
// its length held fixed, and its own continuous extension gives the samples: the tableau and the dense
// output have one source, Boost's, for the values and their derivatives alike.

using TangentPacked = std::vector<TangentScalar>;
using TangentStepper = odeint::runge_kutta_dopri5<TangentPacked, double, TangentPacked, double>;

/// Calls f on the 13 numbers of a body's variables (or their rates) in pack()'s order: o, q, v, ω.
template <class Vec, class Q, class F>
void for_each_number(Vec& o, Q& q, Vec& v, Vec& omega, F&& f) {
  for (int k = 0; k < 3; ++k) f(o(k));
  for (int k = 0; k < 4; ++k) f(q.coeffs()(k));
  for (int k = 0; k < 3; ++k) f(v(k));
  for (int k = 0; k < 3; ++k) f(omega(k));
}

void unpack(const TangentPacked& p, double t, TangentCoordinates& x) {
  x.t = t;
  const TangentScalar* d = p.data();
  for (auto& c : x.bodies) {
    for_each_number(c.o, c.q, c.v, c.omega, [&](TangentScalar& n) { n = *d++; });
    c.q = normalized<TangentScalar>(c.q);
  }
}

class DormandPrince45 final : public AdaptiveIntegrator {
 public:
  explicit DormandPrince45(const Tolerances& tol)
      : stepper_(
            odeint::make_dense_output(tol.absolute, tol.relative, odeint::runge_kutta_dopri5<Packed>())) {}

  std::string name() const override { return "dopri45"; }

  void start(const Model& model, Formulation F, const SystemCoordinates& x0, double initial_step) override {
    engine_.prepare(model, F, 1);
    y_ = x0;
    rates_.ensure(x0.bodies.size());
    particle_rates_.resize(x0.particles.size());
    stats_ = {};
    Packed p;
    pack(x0.bodies, x0.particles, p);
    stepper_.initialize(p, x0.t, initial_step);
  }

  double step() override {
    auto rhs = [this](const Packed& p, Packed& dpdt, double time) {
      ++stats_.evaluations;
      unpack(p, time, y_);
      engine_.evaluate(y_, [&](const engine::Block& blk) {
        for (size_t i = blk.begin; i < blk.end; i += engine::kWidth) {
          rates_.store(i, engine_.rates<engine::Pack>(blk, i, y_.bodies.load<engine::Pack>(i)));
        }
      });
      for (size_t i = 0; i < y_.particles.size(); ++i)
        particle_rates_[i] = engine_.particle_rates(i, y_.particles[i]);
      pack(rates_, particle_rates_, dpdt);
    };
    stepper_.do_step(rhs);
    ++stats_.steps;
    return stepper_.current_time();
  }

  double previous_time() const override {
    return stats_.steps == 0 ? stepper_.current_time() : stepper_.previous_time();
  }
  double current_time() const override { return stepper_.current_time(); }

  SystemCoordinates interpolate(double t) const override {
    SystemCoordinates x = y_;
    if (stats_.steps == 0) {
      unpack(stepper_.current_state(), t, x);
      return x;
    }
    Packed p(stepper_.current_state().size());
    stepper_.calc_state(t, p);
    unpack(p, t, x);
    return x;
  }

  /// The current state, time and next trial step, and the work counted. Odeint's stepper also keeps
  /// the right-hand side at the current state (first same as last): it is rhs(state, time) of these very
  /// numbers, so the first step after load_state() evaluates it again, bit for bit the same, and its
  /// count is not added twice. The error controller keeps nothing else between steps (Boost's
  /// default_step_adjuster only caps the step).
  std::vector<double> save_state() const override {
    std::vector<double> out;
    saved::Writer w(out);
    w.put(stepper_.current_time());
    w.put(stepper_.current_time_step());
    w.put(static_cast<double>(stats_.steps));
    w.put(static_cast<double>(stats_.evaluations));
    const Packed& p = stepper_.current_state();
    w.put(static_cast<double>(p.size()));
    out.insert(out.end(), p.begin(), p.end());
    return out;
  }

  void load_state(const std::vector<double>& state) override {
    saved::Reader r(state, name());
    const double t = r.get(), dt = r.get();
    const auto steps = static_cast<long>(r.count(size_t{1} << 53));
    const auto evaluations = static_cast<long>(r.count(size_t{1} << 53));
    Packed p(r.count(stepper_.current_state().size()));
    if (p.size() != stepper_.current_state().size()) r.fail();
    for (double& v : p) v = r.get();
    r.done();
    stepper_.initialize(p, t, dt);
    stats_ = {steps, 0, steps > 0 ? evaluations - 1 : evaluations};
  }

  void start_tangent(const Model& model, Formulation F, const TangentCoordinates& x0) override {
    model_ = &model;
    F_ = F;
    y_tangent_ = x0;
    x_new_.clear();
    for (auto c : x0.bodies) {
      for_each_number(c.o, c.q, c.v, c.omega, [&](TangentScalar& n) { x_new_.push_back(n); });
    }
    dxdt_new_.resize(x_new_.size());
    t_new_ = x0.t;
    tangent_steps_ = 0;
    tangent_rhs(x_new_, dxdt_new_, t_new_);
  }

  void step_tangent() override {
    if (tangent_steps_ != stats_.steps - 1 || t_new_ != previous_time()) {
      throw std::logic_error("dopri45: step_tangent() must follow each step() once, after start_tangent()");
    }
    std::swap(x_old_, x_new_);
    std::swap(dxdt_old_, dxdt_new_);
    t_old_ = t_new_;
    t_new_ = current_time();
    x_new_.resize(x_old_.size());
    dxdt_new_.resize(x_old_.size());
    tangent_stepper_.do_step([this](const TangentPacked& p, TangentPacked& dpdt,
                                    double t) { tangent_rhs(p, dpdt, t); },
                             x_old_, dxdt_old_, t_old_, x_new_, dxdt_new_, t_new_ - t_old_);
    ++tangent_steps_;
  }

  TangentCoordinates interpolate_tangent(double t) const override {
    TangentCoordinates x = y_tangent_;
    if (tangent_steps_ == 0) {
      unpack(x_new_, t, x);
      return x;
    }
    TangentPacked p(x_new_.size());
    tangent_stepper_.calc_state(t, p, x_old_, dxdt_old_, t_old_, x_new_, dxdt_new_, t_new_);
    unpack(p, t, x);
    return x;
  }

  IntegratorStats stats() const override {
    IntegratorStats s = stats_;
    // Each attempt costs 6 new evaluations (the 7th stage is the next step's first: FSAL), plus one
    // to start; attempts beyond the accepted steps were rejected.
    s.rejected = std::max(0L, (s.evaluations - 1) / 6 - s.steps);
    return s;
  }

 private:
  /// The right-hand side on dual numbers, as rhs() in step() on double: q normalised, then the rates.
  void tangent_rhs(const TangentPacked& p, TangentPacked& dpdt, double t) {
    unpack(p, t, y_tangent_);
    tangent_rates_.rates(*model_, F_, y_tangent_, k_);
    TangentScalar* d = dpdt.data();
    for (auto& k : k_) {
      for_each_number(k.o_dot, k.q_dot, k.v_dot, k.omega_dot, [&](const TangentScalar& n) { *d++ = n; });
    }
  }

  decltype(odeint::make_dense_output(1.0, 1.0, odeint::runge_kutta_dopri5<Packed>())) stepper_;
  // The replay on dual numbers: the step's ends and their rates (first same as last), the stage state.
  const Model* model_ = nullptr;
  Formulation F_ = Formulation::world;
  TangentStepper tangent_stepper_;
  TangentPacked x_old_, dxdt_old_, x_new_, dxdt_new_;
  double t_old_ = 0.0, t_new_ = 0.0;
  long tangent_steps_ = 0;
  TangentCoordinates y_tangent_;
  TangentRates tangent_rates_;
  std::vector<CoordinateRates<TangentScalar>> k_;
  engine::Engine engine_;
  SystemCoordinates y_;  // the state handed to the right-hand side
  BodyColumns rates_;
  std::vector<ParticleState> particle_rates_;
  IntegratorStats stats_;
};

}  // namespace

namespace methods {
std::unique_ptr<AdaptiveIntegrator> dopri45(const Tolerances& tolerances) {
  return std::make_unique<DormandPrince45>(tolerances);
}
}  // namespace methods

}  // namespace tumble
