// Cost of the torque-free gyrostat's exact flow (src/integrate/gyrostat_flow.hpp): its set-up from a
// state (the curve in long double, the lattice, the four poles of the precession rate with Newton
// steps, after a first pass over one polhode to place the pole) and one evaluation at t, for the
// rotor off the principal axes of tests/forces/rotors_test.cpp's ThreeWheels (h = (0.3, −0.4, 0.5)) and
// for the near-steady dual spin of tests/integrate/gyrostat_flow_test.cpp (a nearly degenerate lattice).
// Beside it, EulerPoinsot's set-up for the same body without rotors (euler_poinsot_bench has more).
#include <benchmark/benchmark.h>

#include "integrate/gyrostat_flow.hpp"
#include "tumble/integrate/euler_poinsot.hpp"

namespace {

using tumble::GyrostatFlow, tumble::Quat, tumble::Vec3;

const Vec3 kI(1.0, 2.0, 3.0);
const Quat kQ0(0.8, 0.2, -0.4, 0.4);
struct Body {
  Vec3 h, omega;
};
const Body kBodies[] = {{Vec3(0.3, -0.4, 0.5), Vec3(0.7, 0.2, -0.4)},
                        {Vec3(0.0, 1.5, 0.0), Vec3(0.01, 1.0, 0.02)}};

void BM_SetUp(benchmark::State& state) {
  const Body& b = kBodies[state.range(0)];
  for (auto _ : state) benchmark::DoNotOptimize(GyrostatFlow(kI, b.h, kQ0, b.omega));
}
BENCHMARK(BM_SetUp)->ArgNames({"body"})->Arg(0)->Arg(1);

void BM_State(benchmark::State& state) {
  const Body& b = kBodies[state.range(0)];
  const GyrostatFlow flow(kI, b.h, kQ0, b.omega);
  double t = 0.37;
  for (auto _ : state) {
    benchmark::DoNotOptimize(flow.state(t));
    t += 1.1e-3;
  }
}
BENCHMARK(BM_State)->ArgNames({"body"})->Arg(0)->Arg(1);

void BM_EulerPoinsotSetUp(benchmark::State& state) {
  for (auto _ : state) benchmark::DoNotOptimize(tumble::EulerPoinsot(kI, kQ0, kBodies[0].omega));
}
BENCHMARK(BM_EulerPoinsotSetUp);

}  // namespace

BENCHMARK_MAIN();
