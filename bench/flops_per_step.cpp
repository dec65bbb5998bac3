// Floating-point operations per body-step of each batched integrator, counted by running the same
// equation templates the kernels run (newton_euler.hpp, quaternion.hpp, src/integrate/stages.hpp) on a
// number type that counts what it does, composed stage by stage as the kernels compose them
// (src/integrate/fixed_step.cpp, lie_rk4.cpp). The force is uniform gravity (f = m g: 3 multiplies a
// stage). Prints adds (incl. subtractions and negations), multiplies, divisions and square roots, and
// the bytes a fused step moves per body (docs/performance.md).
//
//   build/release/bin/flops_per_step
#include <cmath>
#include <cstdio>
#include <utility>

#include "integrate/stages.hpp"
#include "tumble/math/simd.hpp"

namespace {

struct Counts {
  long add = 0, mul = 0, div = 0, sqrt = 0, trig = 0;
  long total() const { return add + mul + div + sqrt; }
};
Counts g;

/// A double that counts its arithmetic.
struct F {
  double v = 0;
  F() = default;
  F(double x) : v(x) {}  // NOLINT: implicit, as constants in the templates are
  friend F operator+(F a, F b) { return ++g.add, F(a.v + b.v); }
  friend F operator-(F a, F b) { return ++g.add, F(a.v - b.v); }
  friend F operator*(F a, F b) { return ++g.mul, F(a.v * b.v); }
  friend F operator/(F a, F b) { return ++g.div, F(a.v / b.v); }
  friend F operator-(F a) { return ++g.add, F(-a.v); }
  F& operator+=(F b) { return *this = *this + b; }
  F& operator-=(F b) { return *this = *this - b; }
  F& operator*=(F b) { return *this = *this * b; }
  F& operator/=(F b) { return *this = *this / b; }
  friend bool operator<(F a, F b) { return a.v < b.v; }
  friend F select(bool c, F a, F b) { return c ? a : b; }
  friend F sqrt(F a) { return ++g.sqrt, F(std::sqrt(a.v)); }
  friend F sin(F a) { return ++g.trig, F(std::sin(a.v)); }
  friend F cos(F a) { return ++g.trig, F(std::cos(a.v)); }
  friend std::pair<F, F> sincos(F a) { return {sin(a), cos(a)}; }  // counted as both
};

}  // namespace

namespace Eigen {
template <>
struct NumTraits<F> : tumble::PackNumTraits<F> {};
}  // namespace Eigen

using namespace tumble;

namespace {

Coordinates<F> x0() {
  return {Vec3T<F>(F(1), F(2), F(3)), QuatT<F>(F(0.5), F(0.5), F(0.5), F(0.5)), Vec3T<F>(F(1), F(0), F(0)),
          Vec3T<F>(F(3), F(-2), F(1))};
}
/// The box's constants, with the reciprocals the engine takes once per run (not counted: each count
/// starts after this is initialised).
const F kMass(6);
const MassConstants<F> kBox = mass_constants<F>(kMass, Vec3T<F>(F(0.025), F(0.05), F(0.065)));

/// One stage's loads (gravity, f = m g) and rates.
CoordinateRates<F> rates(Formulation formulation, const Coordinates<F>& y) {
  const F g_z(-9.81);
  const Vec3T<F> f(kMass * F(0), kMass * F(0), kMass * g_z);
  return newton_euler<F>(formulation, kBox, y, f, Vec3T<F>(F(0), F(0), F(0)));
}

Counts rk4(Formulation formulation) {
  g = {};
  const Coordinates<F> x = x0();
  CoordinateRates<F> A;
  Coordinates<F> y = x;
  for (int s = 0; s < 4; ++s) {
    const CoordinateRates<F> k = rates(formulation, y);
    if (s < 3) {
      A = s == 0 ? k : axpy<F>(A, F(2), k);
      y = advanced<F>(x, F(0.5e-3), k);
    } else {
      y = advanced<F>(x, F(1e-3 / 6), axpy<F>(A, F(1), k));
    }
  }
  return g;
}

Counts lie_rk4(Formulation formulation) {
  g = {};
  const Coordinates<F> x = x0();
  CoordinateRates<F> A;
  Vec3T<F> theta(F(0), F(0), F(0)), sum;
  Coordinates<F> y = x;
  for (int s = 0; s < 4; ++s) {
    const CoordinateRates<F> k = rates(formulation, y);
    const Vec3T<F> half = F(0.5) * theta.cross(y.omega);
    const Vec3T<F> Fs = Vec3T<F>(y.omega + half) + theta.cross(theta.cross(y.omega)) / F(12);  // dexp⁻¹
    if (s < 3) {
      A = s == 0 ? k : axpy<F>(A, F(2), k);
      sum = s == 0 ? Fs : Vec3T<F>(sum + F(2) * Fs);
      theta = F(0.5e-3) * Fs;
      y = advanced<F>(x, F(0.5e-3), k);
      y.q = quat_mul<F>(x.q, quat_exp<F>(theta));
    } else {
      y = advanced<F>(x, F(1e-3 / 6), axpy<F>(A, F(1), k));
      y.q = quat_mul<F>(x.q, quat_exp<F>(Vec3T<F>(F(1e-3 / 6) * (sum + Fs))));
    }
  }
  return g;
}

Counts euler(Formulation formulation) {
  g = {};
  const Coordinates<F> x = x0();
  advanced<F>(x, F(1e-3), rates(formulation, x));
  return g;
}

Counts semi_implicit_euler(Formulation formulation) {
  g = {};
  Coordinates<F> c = x0();
  const CoordinateRates<F> k = rates(formulation, c);
  const F h(1e-3);
  c.v += h * k.v_dot;
  c.omega += h * k.omega_dot;
  const auto [o_dot, q_dot] = kinematics<F>(formulation, c);
  c.o += h * o_dot;
  c.q = normalized<F>(QuatT<F>(c.q.coeffs() + h * q_dot.coeffs()));
  return g;
}

}  // namespace

int main() {
  std::printf("%-20s %-6s %6s %6s %6s %6s %6s %6s\n", "integrator", "frame", "add", "mul", "div", "sqrt",
              "trig", "total");
  for (const Formulation formulation : {Formulation::world, Formulation::mixed, Formulation::body}) {
    const char* frame = formulation == Formulation::world   ? "world"
                        : formulation == Formulation::mixed ? "mixed"
                                                            : "body";
    const std::pair<const char*, Counts> rows[] = {{"euler", euler(formulation)},
                                                   {"semi_implicit_euler", semi_implicit_euler(formulation)},
                                                   {"rk4", rk4(formulation)},
                                                   {"lie_rk4", lie_rk4(formulation)}};
    for (const auto& [name, c] : rows) {
      std::printf("%-20s %-6s %6ld %6ld %6ld %6ld %6ld %6ld\n", name, frame, c.add, c.mul, c.div, c.sqrt,
                  c.trig, c.total());
    }
  }
  std::printf(
      "\nbytes per body-step, fused steps: state read and written (2 x 13 doubles) + constants m, 1/m, "
      "Lambda, 1/Lambda (8 doubles) = %d\n",
      (2 * 13 + 8) * 8);
}
