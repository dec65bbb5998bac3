// lie_rk4: the Runge–Kutta–Munthe-Kaas method of order 4 (Munthe-Kaas, BIT 38:92, 1998).
//
// The orientation is advanced on SO(3) itself: R(t) = R_n exp([θ(t)]×) (body-frame ω, mixed and body
// formulations) or R(t) = exp([θ(t)]×) R_n (world ω), with θ̇ = dexp⁻¹_{∓θ}(ω), integrated by the
// classical RK4 tableau; every other variable takes the ordinary RK4 stages. Each orientation is a
// product of exact rotations, so R stays orthogonal to rounding without renormalisation.
#include "methods.hpp"

namespace tumble {
namespace {

/// dexp⁻¹ truncated after the double commutator, enough for order 4:
///   left  (Ṙ = [ω]× R, R = exp(θ) R_n):   θ̇ = ω − ½ θ × ω + (1/12) θ × (θ × ω)
///   right (Ṙ = R [ω]×, R = R_n exp(θ)):   θ̇ = ω + ½ θ × ω + (1/12) θ × (θ × ω)
Vec3 dexpinv(const Vec3& theta, const Vec3& w, bool right) {
  const Vec3 half = 0.5 * theta.cross(w);
  return (right ? Vec3(w + half) : Vec3(w - half)) + theta.cross(theta.cross(w)) / 12.0;
}

class LieRungeKutta4 final : public Integrator {
 public:
  std::string name() const override { return "lie_rk4"; }
  int order() const override { return 4; }
  int evaluations_per_step() const override { return 4; }

  void step(const Model& model, Formulation F, SystemCoordinates& x, double h) const override {
    const bool right = F != Formulation::world;  // mixed and body integrate ^bω
    const size_t n = x.bodies.size();
    std::vector<Vec3> theta(n, Vec3::Zero());

    // Stage i: vector variables x + c·h·k_{i−1}; rotation R_n · exp(θ_i).
    auto stage = [&](double ch, const SystemRates* k, const std::vector<Vec3>& th) {
      SystemCoordinates y = k ? advance(x, ch, *k) : x;
      for (size_t b = 0; b < n; ++b) {
        const Quat e = quat_exp<double>(th[b]);
        y.bodies[b].q = right ? Quat(x.bodies[b].q * e) : Quat(e * x.bodies[b].q);
      }
      return y;
    };
    // F_i = dexp⁻¹_θᵢ(ω at stage i): the rotation generator at the stage.
    auto generator = [&](const SystemCoordinates& y, const std::vector<Vec3>& th) {
      std::vector<Vec3> g(n);
      for (size_t b = 0; b < n; ++b) g[b] = dexpinv(th[b], y.bodies[b].omega, right);
      return g;
    };
    auto scaled = [&](const std::vector<Vec3>& g, double s) {
      std::vector<Vec3> th(n);
      for (size_t b = 0; b < n; ++b) th[b] = s * g[b];
      return th;
    };

    const SystemCoordinates y1 = x;
    const SystemRates k1 = system_rates(model, F, y1);
    const std::vector<Vec3> F1 = generator(y1, theta);

    const std::vector<Vec3> th2 = scaled(F1, h / 2);
    const SystemCoordinates y2 = stage(h / 2, &k1, th2);
    const SystemRates k2 = system_rates(model, F, y2);
    const std::vector<Vec3> F2 = generator(y2, th2);

    const std::vector<Vec3> th3 = scaled(F2, h / 2);
    const SystemCoordinates y3 = stage(h / 2, &k2, th3);
    const SystemRates k3 = system_rates(model, F, y3);
    const std::vector<Vec3> F3 = generator(y3, th3);

    const std::vector<Vec3> th4 = scaled(F3, h);
    const SystemCoordinates y4 = stage(h, &k3, th4);
    const SystemRates k4 = system_rates(model, F, y4);
    const std::vector<Vec3> F4 = generator(y4, th4);

    for (size_t b = 0; b < n; ++b) theta[b] = h / 6.0 * (F1[b] + 2.0 * F2[b] + 2.0 * F3[b] + F4[b]);
    const SystemRates k = combine({{1.0 / 6, &k1}, {2.0 / 6, &k2}, {2.0 / 6, &k3}, {1.0 / 6, &k4}});
    x = stage(h, &k, theta);
  }
};

}  // namespace

namespace methods {
std::unique_ptr<Integrator> lie_rk4() { return std::make_unique<LieRungeKutta4>(); }
}  // namespace methods

}  // namespace tumble
