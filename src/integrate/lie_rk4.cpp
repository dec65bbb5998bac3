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
TUMBLE_INLINE Vec3T<T> dexpinv(const Vec3T<T>& theta, const Vec3T<T>& w, bool right) {
  const Vec3T<T> half = T(0.5) * theta.cross(w);
  return (right ? Vec3T<T>(w + half) : Vec3T<T>(w - half)) + theta.cross(theta.cross(w)) / T(12);
}

/// R_n exp([θ]×) (right) or exp([θ]×) R_n (left) as quaternions.
template <class T>
TUMBLE_INLINE QuatT<T> rotated(const QuatT<T>& q, const Vec3T<T>& theta, bool right) {
  const QuatT<T> e = quat_exp<T>(theta);
  return right ? quat_mul<T>(q, e) : quat_mul<T>(e, q);
}

/// Stage s of one body (or pack), `length` = rk4::stage_length(s, h): the RK4 tableau of rk4 (rk4_steps.hpp) in the same low-storage form,
/// with the rotation advanced through θ: at stage s the orientation is R_n·exp(θ_s) (right) or
/// exp(θ_s)·R_n (left), the other variables x + c_s h k_{s−1}; θ_{s+1} = c_{s+1} h F_s with
/// F_s = dexp⁻¹_{θ_s}(ω_s), and the step ends at θ = (h/6)(F₁ + 2F₂ + 2F₃ + F₄). Given the stage state y
/// and its rates k, updates A, θ (θ_s in, θ_{s+1} out) and ΣF, and returns y_{s+1} (the step's end at
/// s = 3). The batched kernel and step_tangent both call it.
template <class T>
TUMBLE_INLINE Coordinates<T> lie_stage(int s, const T& length, bool right, const Coordinates<T>& x,
                                       const Coordinates<T>& y, const CoordinateRates<T>& k,
                                       CoordinateRates<T>& A, Vec3T<T>& theta, Vec3T<T>& sum_F) {
  const T weight(rk4::b[s]);
  const Vec3T<T> Fs = dexpinv<T>(theta, y.omega, right);  // θ_s: zero at s = 0
  if (s < 3) {
    A = s == 0 ? k : axpy<T>(A, weight, k);
    sum_F = s == 0 ? Fs : Vec3T<T>(sum_F + weight * Fs);
    theta = length * Fs;
    Coordinates<T> next = advanced<T>(x, length, k);
    next.q = rotated<T>(x.q, theta, right);
    return next;
  }
  Coordinates<T> next = advanced<T>(x, length, axpy<T>(A, T(1.0), k));
  next.q = rotated<T>(x.q, Vec3T<T>(length * (sum_F + Fs)), right);
  return next;
}

/// Stage variables: y, A, and θ_s, ΣF in a third set's columns.
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
    auto stage = [&](int s, const Block& blk, const BodyColumnsRef& in) {
      const BodyColumnsRef &y = blk.work[0], &A = blk.work[1], &theta = blk.work[2];  // θ_s: 0–2, ΣF: 3–5
      const Pack length(rk4::stage_length(s, h));
      for (size_t i = blk.begin; i < blk.end; i += kWidth) {
        const Coordinates<Pack> yi = in.load<Pack>(i);
        const CoordinateRates<Pack> k = engine_.rates<Pack>(blk, i, yi);
        CoordinateRates<Pack> Ai = s == 0 ? k : A.load_rates<Pack>(i);
        Vec3T<Pack> th = s == 0 ? Vec3T<Pack>(Vec3T<Pack>::Zero()) : theta.vec3<Pack>(0, i);
        Vec3T<Pack> sum_F = s == 0 ? th : theta.vec3<Pack>(3, i);
        const Coordinates<Pack> next =
            lie_stage<Pack>(s, length, right, xr.load<Pack>(i), yi, k, Ai, th, sum_F);
        if (s < 3) {
          A.store(i, Ai);
          theta.store_vec3<Pack>(0, i, th);
          theta.store_vec3<Pack>(3, i, sum_F);
          y.store(i, next);
        } else {
          xr.store(i, next);
        }
      }
    };
    rk4::steps(engine_, x, h, count, y_, A_particles_, {&y_.bodies, &A_, &theta_}, stage);
  }

  void step_tangent(const Model& model, Formulation F, TangentCoordinates& x, double h) override {
    using T = TangentScalar;
    const bool right = F != Formulation::world;
    const size_t n = x.bodies.size();
    y_tangent_ = x;
    A_tangent_.resize(n);
    theta_tangent_.assign(n, Vec3T<T>::Zero());
    sum_F_tangent_.resize(n);
    for (int s = 0; s < 4; ++s) {
      y_tangent_.t = x.t + rk4::c[s] * h;
      tangent_.rates(model, F, y_tangent_, k_);
      for (size_t i = 0; i < n; ++i) {
        const Coordinates<T> next = lie_stage<T>(s, rk4::stage_length(s, h), right, x.bodies[i],
                                                 y_tangent_.bodies[i], k_[i], A_tangent_[i],
                                                 theta_tangent_[i], sum_F_tangent_[i]);
        (s < 3 ? y_tangent_.bodies[i] : x.bodies[i]) = next;
      }
    }
    x.t += h;
  }

 private:
  engine::Engine engine_;
  SystemCoordinates y_;  // staged steps only
  BodyColumns A_, theta_;
  TangentRates tangent_;
  TangentCoordinates y_tangent_;
  std::vector<CoordinateRates<TangentScalar>> k_, A_tangent_;
  std::vector<Vec3T<TangentScalar>> theta_tangent_, sum_F_tangent_;
  std::vector<ParticleState> A_particles_;
};

}  // namespace

namespace methods {
std::unique_ptr<Integrator> lie_rk4() { return std::make_unique<LieRungeKutta4>(); }
}  // namespace methods

}  // namespace tumble
