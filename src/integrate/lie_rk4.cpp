// lie_rk4: the Runge–Kutta–Munthe-Kaas method of order 4 (Munthe-Kaas, BIT 38:92, 1998).
//
// The orientation is advanced on SO(3) itself: R(t) = R_n exp([θ(t)]×) (body-frame ω, mixed and body
// formulations) or R(t) = exp([θ(t)]×) R_n (world ω), with θ̇ = dexp⁻¹_{∓θ}(ω), integrated by the
// classical RK4 tableau; every other variable takes the ordinary RK4 stages. Each orientation is a
// product of exact rotations, so R stays orthogonal to rounding without renormalisation.
#include "engine.hpp"
#include "methods.hpp"
#include "rk4_steps.hpp"

namespace tumble {
namespace {

using engine::Block;
using engine::kWidth;
using engine::Pack;

/// dexp⁻¹ truncated after the double commutator, enough for order 4:
///   left  (Ṙ = [ω]× R, R = exp(θ) R_n):   θ̇ = ω − ½ θ × ω + (1/12) θ × (θ × ω)
///   right (Ṙ = R [ω]×, R = R_n exp(θ)):   θ̇ = ω + ½ θ × ω + (1/12) θ × (θ × ω)
template <class T>
Vec3T<T> dexpinv(const Vec3T<T>& theta, const Vec3T<T>& w, bool right) {
  const Vec3T<T> half = T(0.5) * theta.cross(w);
  return (right ? Vec3T<T>(w + half) : Vec3T<T>(w - half)) + theta.cross(theta.cross(w)) / T(12);
}

/// The RK4 tableau of rk4 (fixed_step.cpp) in the same low-storage form, with the rotation advanced
/// through θ: at stage s the orientation is R_n·exp(θ_s) (right) or exp(θ_s)·R_n (left), the other
/// variables x + c_s h k_{s−1}; θ_{s+1} = c_{s+1} h F_s with F_s = dexp⁻¹_{θ_s}(ω_s), and the step ends
/// at θ = (h/6)(F₁ + 2F₂ + 2F₃ + F₄). Stage variables: y, A, and θ_s, ΣF in a third set's columns.
class LieRungeKutta4 final : public Integrator {
 public:
  std::string name() const override { return "lie_rk4"; }
  int order() const override { return 4; }
  int evaluations_per_step() const override { return 4; }

  void step(const Model& model, Formulation F, SystemCoordinates& x, double h) override {
    steps(model, F, x, h, 1);
  }
  bool fuses_steps(const Model& model) const override { return engine::Engine::fusable(model); }
  void steps(const Model& model, Formulation F, SystemCoordinates& x, double h, long count) override {
    const bool right = F != Formulation::world;  // mixed and body integrate ^bω
    engine_.prepare(model, F, threads_, 3);
    const BodyColumnsRef xr = x.bodies.ref();
    auto rotated = [right](const QuatT<Pack>& q, const Vec3T<Pack>& th) {
      const QuatT<Pack> e = quat_exp<Pack>(th);
      return right ? quat_mul<Pack>(q, e) : quat_mul<Pack>(e, q);
    };
    auto stage = [&](int s, const Block& blk, const BodyColumnsRef& in) {
      const BodyColumnsRef &y = blk.work[0], &A = blk.work[1], &theta = blk.work[2];  // θ_s: 0–2, ΣF: 3–5
      const Pack weight(rk4::b[s]);
      const Pack step_next(s < 3 ? rk4::c[s + 1] * h : h / 6);
      for (size_t i = blk.begin; i < blk.end; i += kWidth) {
        const Coordinates<Pack> yi = in.load<Pack>(i);
        const CoordinateRates<Pack> k = engine_.rates<Pack>(blk, i, yi);
        const Vec3T<Pack> th = s == 0 ? Vec3T<Pack>::Zero() : theta.vec3<Pack>(0, i);
        const Vec3T<Pack> Fs = dexpinv<Pack>(th, yi.omega, right);
        const Coordinates<Pack> xi = xr.load<Pack>(i);
        if (s < 3) {
          A.store(i, s == 0 ? k : axpy<Pack>(A.load_rates<Pack>(i), weight, k));
          theta.store_vec3<Pack>(3, i, s == 0 ? Fs : Vec3T<Pack>(theta.vec3<Pack>(3, i) + weight * Fs));
          const Vec3T<Pack> th_next = step_next * Fs;
          theta.store_vec3<Pack>(0, i, th_next);
          Coordinates<Pack> next = advanced<Pack>(xi, step_next, k);
          next.q = rotated(xi.q, th_next);
          y.store(i, next);
        } else {
          Coordinates<Pack> next =
              advanced<Pack>(xi, step_next, axpy<Pack>(A.load_rates<Pack>(i), Pack(1.0), k));
          next.q = rotated(xi.q, Vec3T<Pack>(step_next * (theta.vec3<Pack>(3, i) + Fs)));
          xr.store(i, next);
        }
      }
    };
    rk4::steps(engine_, x, h, count, y_, A_particles_, {&y_.bodies, &A_, &theta_}, stage);
  }

 private:
  engine::Engine engine_;
  SystemCoordinates y_;  // staged steps only
  BodyColumns A_, theta_;
  std::vector<ParticleState> A_particles_;
};

}  // namespace

namespace methods {
std::unique_ptr<Integrator> lie_rk4() { return std::make_unique<LieRungeKutta4>(); }
}  // namespace methods

}  // namespace tumble
