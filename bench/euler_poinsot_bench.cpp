// Cost of one evaluation of the exact torque-free motion (EulerPoinsot) for a generic triaxial body:
// ω_b(t) (one sn/cn/dn), q(t) (sn/cn/dn + Carlson R_J + a few trigonometric functions) and both
// together (state(t), one sn/cn/dn), at moderate and large t (the argument is reduced modulo the
// period: the cost must not grow with t), and the set-up. The *Pack benchmarks evaluate the same
// templates on a SIMD pack (one body per lane, as splitting's batched drift does); their time is per
// pack, and the counter "per_lane" divides it by the pack width.
#include <benchmark/benchmark.h>

#include <vector>

#include "integrate/euler_poinsot_flows.hpp"
#include "tumble/integrate/euler_poinsot.hpp"
#include "tumble/math/pack_pair.hpp"
#include "tumble/math/simd.hpp"

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

using Pack = xsimd::batch<double>;

const tumble::detail::TriaxialConstants<Pack>& generic_pack() {
  static const tumble::detail::TriaxialConstants<Pack> k = [] {
    tumble::detail::TriaxialConstants<Pack> p;
    const tumble::detail::TriaxialRotation* flow = generic_body().free_rotation().triaxial();
    if (!flow) return p;  // the generic body is triaxial: 1.5 < 2.5 < 4
    // Every constant, in visit_constants' order (as the splitting drift's columns are filled).
    tumble::detail::TriaxialConstants<double> d = flow->constants();
    std::vector<double> values;
    tumble::detail::visit_constants(d, d.jacobi.steps, [&](double& v) { values.push_back(v); });
    size_t next = 0;
    tumble::detail::visit_constants(p, d.jacobi.steps, [&](Pack& v) { v = Pack(values[next++]); });
    p.jacobi.steps = d.jacobi.steps;
    p.pi.rj_max_steps = d.pi.rj_max_steps;
    return p;
  }();
  return k;
}

void per_lane(benchmark::State& state) {
  state.counters["per_lane"] = benchmark::Counter(static_cast<double>(state.iterations()) * Pack::size,
                                                  benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

void BM_StatePack(benchmark::State& state) {
  const auto& k = generic_pack();
  Pack t(1.0);
  for (auto _ : state) {
    benchmark::DoNotOptimize(tumble::detail::triaxial_state<Pack>(k, t));
    t += Pack(1e-3);
  }
  per_lane(state);
}
BENCHMARK(BM_StatePack);

void BM_StatePackPair(benchmark::State& state) {
  auto& single = const_cast<tumble::detail::TriaxialConstants<Pack>&>(generic_pack());
  tumble::detail::TriaxialConstants<tumble::PackPair> k;
  std::vector<Pack*> from;
  tumble::detail::visit_constants(single, single.jacobi.steps, [&](Pack& v) { from.push_back(&v); });
  size_t i = 0;
  tumble::detail::visit_constants(k, single.jacobi.steps, [&](tumble::PackPair& v) {
    v = {*from[i], *from[i]}, ++i;
  });
  k.jacobi.steps = single.jacobi.steps;
  k.pi.rj_max_steps = single.pi.rj_max_steps;
  tumble::PackPair t(1.0);
  for (auto _ : state) {
    benchmark::DoNotOptimize(tumble::detail::triaxial_state<tumble::PackPair>(k, t));
    t += tumble::PackPair(1e-3);
  }
  state.counters["per_lane"] = benchmark::Counter(static_cast<double>(state.iterations()) * 2 * Pack::size,
                                                  benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}
BENCHMARK(BM_StatePackPair);

/// Times f(x) on a pack whose argument moves a little each call (so that nothing is hoisted), per lane.
template <class F>
void time_on_pack(benchmark::State& state, double x0, double dx, F&& f) {
  Pack x(x0);
  for (auto _ : state) {
    benchmark::DoNotOptimize(f(x));
    x += Pack(dx);
  }
  per_lane(state);
}

// The parts of a flow evaluation: the Landen point (sn, cn, dn) and R_J with the 7 steps of the usual
// body (carlson_rj_steps: N ≤ 15, m₁ ≥ 0.1).
void BM_LandenPack(benchmark::State& state) {
  time_on_pack(state, 1.0, 1e-3,
               [](const Pack& u) { return tumble::landen_point<Pack>(generic_pack().jacobi, u); });
}
BENCHMARK(BM_LandenPack);
void BM_CarlsonRjPack(benchmark::State& state) {
  time_on_pack(state, 0.3, 1e-9, [](const Pack& x) {
    return tumble::carlson_rj<Pack>(x, Pack(0.7), Pack(1.0), Pack(3.0), Pack(7.0), 7);
  });
}
BENCHMARK(BM_CarlsonRjPack);

}  // namespace

BENCHMARK_MAIN();
