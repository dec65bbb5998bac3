// Cost of one evaluation of the exact torque-free motion (EulerPoinsot) for a generic triaxial body:
// ω_b(t) (one sn/cn/dn), q(t) (sn/cn/dn + Carlson R_F, R_J + a few trigonometric functions) and both
// together (state(t), one sn/cn/dn), at moderate and large t (the argument is reduced modulo the
// period: the cost must not grow with t), and the set-up.
#include <benchmark/benchmark.h>

#include "tumble/integrate/euler_poinsot.hpp"

namespace {

const tumble::EulerPoinsot& generic_body() {
  static const tumble::EulerPoinsot ep(
      tumble::Vec3(1.5, 2.5, 4.0), tumble::Quat(Eigen::AngleAxisd(0.7, tumble::Vec3(1, 2, 3).normalized())),
      tumble::Vec3(1.0, 12.0, 2.0));
  return ep;
}

void BM_OmegaB(benchmark::State& state) {
  const auto& ep = generic_body();
  double t = static_cast<double>(state.range(0));
  for (auto _ : state) {
    benchmark::DoNotOptimize(ep.omega_b(t));
    t += 1e-3;
  }
}
BENCHMARK(BM_OmegaB)->Arg(1)->Arg(1000000);

void BM_Quaternion(benchmark::State& state) {
  const auto& ep = generic_body();
  double t = static_cast<double>(state.range(0));
  for (auto _ : state) {
    benchmark::DoNotOptimize(ep.q(t));
    t += 1e-3;
  }
}
BENCHMARK(BM_Quaternion)->Arg(1)->Arg(1000000);

// q(t) and ω_b(t) together, as splitting's drift takes them: one evaluation of sn, cn, dn for both.
void BM_State(benchmark::State& state) {
  const auto& ep = generic_body();
  double t = static_cast<double>(state.range(0));
  for (auto _ : state) {
    benchmark::DoNotOptimize(ep.state(t));
    t += 1e-3;
  }
}
BENCHMARK(BM_State)->Arg(1)->Arg(1000000);

void BM_Construct(benchmark::State& state) {
  for (auto _ : state) {
    tumble::EulerPoinsot ep(tumble::Vec3(1.5, 2.5, 4.0), tumble::Quat::Identity(),
                            tumble::Vec3(1.0, 12.0, 2.0));
    benchmark::DoNotOptimize(ep);
  }
}
BENCHMARK(BM_Construct);

}  // namespace

BENCHMARK_MAIN();
