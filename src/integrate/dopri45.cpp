// dopri45: the adaptive Dormand–Prince 5(4) pair with its continuous extension, from Boost.Odeint
// (runge_kutta_dopri5 in a controlled, dense-output stepper): error control per component, step
// rejection, and dense output so samples land exactly on the requested times.
//
// The state is packed as (o, q, v, ω) per body in the formulation's frames, (x, v) per particle.
// q is renormalised before each right-hand-side evaluation; q̇ = ½ q ⊗ (0, ω) keeps |q| constant in
// exact arithmetic, so |q| − 1 stays at the size of the local error tolerance and is removed at output.
#include <boost/numeric/odeint.hpp>

#include "methods.hpp"

namespace tumble {
namespace {

namespace odeint = boost::numeric::odeint;
using Packed = std::vector<double>;
constexpr size_t kBody = 13, kParticle = 6;

void put(double* d, const Vec3& v) { d[0] = v.x(), d[1] = v.y(), d[2] = v.z(); }

Packed pack(const SystemCoordinates& x) {
  Packed p(x.bodies.size() * kBody + x.particles.size() * kParticle);
  double* d = p.data();
  for (const auto& c : x.bodies) {
    put(d, c.o);
    d[3] = c.q.w(), d[4] = c.q.x(), d[5] = c.q.y(), d[6] = c.q.z();
    put(d + 7, c.v);
    put(d + 10, c.omega);
    d += kBody;
  }
  for (const auto& s : x.particles) {
    put(d, s.x);
    put(d + 3, s.v);
    d += kParticle;
  }
  return p;
}

SystemCoordinates unpack(const Packed& p, double t, size_t n_bodies, size_t n_particles) {
  SystemCoordinates x;
  x.t = t;
  const double* d = p.data();
  for (size_t i = 0; i < n_bodies; ++i, d += kBody) {
    x.bodies.push_back({Vec3(d[0], d[1], d[2]), Quat(d[3], d[4], d[5], d[6]).normalized(), Vec3(d[7], d[8], d[9]),
                        Vec3(d[10], d[11], d[12])});
  }
  for (size_t i = 0; i < n_particles; ++i, d += kParticle) {
    x.particles.push_back({Vec3(d[0], d[1], d[2]), Vec3(d[3], d[4], d[5])});
  }
  return x;
}

Packed pack_rates(const SystemRates& k) {
  SystemCoordinates as_coordinates;  // the same layout: (ȯ, q̇, v̇, ω̇) and (ẋ, v̇)
  for (const auto& r : k.bodies) as_coordinates.bodies.push_back({r.o_dot, r.q_dot, r.v_dot, r.omega_dot});
  as_coordinates.particles = k.particles;
  return pack(as_coordinates);
}

class DormandPrince45 final : public AdaptiveIntegrator {
 public:
  explicit DormandPrince45(const Tolerances& tol)
      : stepper_(odeint::make_dense_output(tol.absolute, tol.relative, odeint::runge_kutta_dopri5<Packed>())) {}

  std::string name() const override { return "dopri45"; }

  void start(const Model& model, Formulation F, const SystemCoordinates& x0, double initial_step) override {
    model_ = &model;
    formulation_ = F;
    n_bodies_ = x0.bodies.size();
    n_particles_ = x0.particles.size();
    stats_ = {};
    stepper_.initialize(pack(x0), x0.t, initial_step);
  }

  double step() override {
    auto rhs = [this](const Packed& p, Packed& dpdt, double time) {
      ++stats_.evaluations;
      dpdt = pack_rates(system_rates(*model_, formulation_, unpack(p, time, n_bodies_, n_particles_)));
    };
    stepper_.do_step(rhs);
    ++stats_.steps;
    return stepper_.current_time();
  }

  double previous_time() const override { return stats_.steps == 0 ? stepper_.current_time() : stepper_.previous_time(); }
  double current_time() const override { return stepper_.current_time(); }

  SystemCoordinates interpolate(double t) const override {
    if (stats_.steps == 0) return unpack(stepper_.current_state(), t, n_bodies_, n_particles_);
    Packed p(stepper_.current_state().size());
    stepper_.calc_state(t, p);
    return unpack(p, t, n_bodies_, n_particles_);
  }

  IntegratorStats stats() const override {
    IntegratorStats s = stats_;
    // Each attempt costs 6 new evaluations (the 7th stage is the next step's first: FSAL), plus one
    // to start; attempts beyond the accepted steps were rejected.
    s.rejected = std::max(0L, (s.evaluations - 1) / 6 - s.steps);
    return s;
  }

 private:
  decltype(odeint::make_dense_output(1.0, 1.0, odeint::runge_kutta_dopri5<Packed>())) stepper_;
  const Model* model_ = nullptr;
  Formulation formulation_ = Formulation::mixed;
  size_t n_bodies_ = 0, n_particles_ = 0;
  IntegratorStats stats_;
};

}  // namespace

namespace methods {
std::unique_ptr<AdaptiveIntegrator> dopri45(const Tolerances& tolerances) {
  return std::make_unique<DormandPrince45>(tolerances);
}
}  // namespace methods

}  // namespace tumble
