// What tangents cost on packs of bodies (issue 25's cost target, for the dual path not written yet):
// one rk4 step of free bodies under gravity (mixed formulation) by the engine's own templates —
// newton_euler<T>, rk4::stage<T> — on T = Pack (the state step) and on Dual<Pack, k>, a pack of bodies
// each carrying k tangent directions, k = 1, 2, 4, 8, 16. A study of the representation: the cost per
// direction, t(Dual<Pack, k>) / (k · t(Pack)), against the target of 2 state steps.
//
//   build/release/bin/tangent_pack_bench [--benchmark_repetitions=5]
//
// 1024 bodies (128 packs of 8 on AVX-512) stepped in place; the time is per body-step.
#include <benchmark/benchmark.h>

#include <tuple>
#include <type_traits>
#include <vector>

#include "integrate/rk4_steps.hpp"
#include "tumble/math/dual.hpp"

namespace {

using tumble::CoordinateRates;
using tumble::Coordinates;
using tumble::Formulation;
using tumble::QuatT;
using tumble::Vec3T;
using Pack = tumble::engine::Pack;
constexpr int kBodies = 1024;
constexpr int kPacks = kBodies / static_cast<int>(Pack::size);

template <class T>
T seeded(double value, int component) {
  if constexpr (std::is_same_v<T, Pack>) {
    (void)component;
    return Pack(value);
  } else {
    constexpr int k = static_cast<int>(std::tuple_size_v<decltype(T{}.d)>);
    return T::variable(Pack(value), component % k);
  }
}

template <class T>
void BM_Rk4Step(benchmark::State& state) {
  std::vector<Coordinates<T>> x(kPacks);
  for (auto& c : x) {
    c.o = Vec3T<T>(seeded<T>(0.1, 0), seeded<T>(-0.2, 1), seeded<T>(1.0, 2));
    c.q = tumble::normalized<T>(
        QuatT<T>(seeded<T>(0.9, 3), seeded<T>(0.1, 4), seeded<T>(-0.3, 5), seeded<T>(0.2, 6)));
    c.v = Vec3T<T>(seeded<T>(1.0, 7), seeded<T>(0.0, 8), seeded<T>(2.0, 9));
    c.omega = Vec3T<T>(seeded<T>(0.3, 10), seeded<T>(5.0, 11), seeded<T>(0.1, 12));
  }
  const T m(2.0);
  const tumble::MassConstants<T> mass = tumble::mass_constants<T>(m, Vec3T<T>(T(0.02), T(0.05), T(0.06)));
  const Vec3T<T> f = m * Vec3T<T>(T(0.0), T(0.0), T(-9.81));
  const Vec3T<T> tau(T(0.0), T(0.0), T(0.0));
  const double h = 1e-3;
  for (auto _ : state) {
    for (auto& c : x) {
      Coordinates<T> y = c;
      CoordinateRates<T> A;
      for (int s = 0; s < 4; ++s) {
        const CoordinateRates<T> k = tumble::newton_euler<T>(Formulation::mixed, mass, y, f, tau);
        const Coordinates<T> next = tumble::rk4::stage<T>(s, T(tumble::rk4::stage_length(s, h)), c, k, A);
        (s < 3 ? y : c) = next;
      }
    }
    benchmark::DoNotOptimize(x.data());
  }
  state.counters["ns/body-step"] =
      benchmark::Counter(static_cast<double>(kBodies),
                         benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

template <int K>
using DualPack = tumble::Dual<Pack, K>;

BENCHMARK(BM_Rk4Step<Pack>);
BENCHMARK(BM_Rk4Step<DualPack<1>>);
BENCHMARK(BM_Rk4Step<DualPack<2>>);
BENCHMARK(BM_Rk4Step<DualPack<4>>);
BENCHMARK(BM_Rk4Step<DualPack<8>>);
BENCHMARK(BM_Rk4Step<DualPack<16>>);

}  // namespace

BENCHMARK_MAIN();
