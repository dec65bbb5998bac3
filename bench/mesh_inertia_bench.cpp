// Throughput of mesh mass properties on a torus of 2·10⁶ triangles (in memory and from binary STL).
//
// Run from a release build (machine info and min/median over 5 repetitions are printed):
//   build/release/bin/mesh_inertia_bench
// Any --benchmark_* flag overrides the defaults, e.g. --benchmark_repetitions=10.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <filesystem>
#include <fmt/format.h>
#include <fstream>
#include <string>
#include <thread>
#include <unistd.h>
#include <vector>

#include "machine.hpp"
#include "tumble/mass/mesh_io.hpp"
#include "tumble/mass/mesh_mass.hpp"
#include "tumble/mass/tessellate.hpp"

namespace {

using namespace tumble;

// A torus with 1000 × 1000 segments: 2 000 000 triangles, 1 000 000 vertices.
const TriangleMesh& torus() {
  static const TriangleMesh mesh = tessellate(Torus{1.0, 0.3}, 1000);
  return mesh;
}

double minimum(const std::vector<double>& v) { return *std::min_element(v.begin(), v.end()); }

void report(benchmark::State& state) {
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()) *
                          static_cast<std::int64_t>(torus().triangles.size()));
  state.counters["triangles"] = static_cast<double>(torus().triangles.size());
}

void BM_IntegrateSolidMesh(benchmark::State& state) {
  const TriangleMesh& mesh = torus();
  for (auto _ : state) benchmark::DoNotOptimize(integrate_solid_mesh(mesh));
  report(state);
}
BENCHMARK(BM_IntegrateSolidMesh)->Unit(benchmark::kMillisecond)->ComputeStatistics("min", minimum);

void BM_SolidMassProperties(benchmark::State& state) {  // topology checks + integration
  const TriangleMesh& mesh = torus();
  const MassSpec spec = MassSpec::density(7850.0);
  for (auto _ : state) benchmark::DoNotOptimize(solid_mass_properties(mesh, spec));
  report(state);
}
BENCHMARK(BM_SolidMassProperties)->Unit(benchmark::kMillisecond)->ComputeStatistics("min", minimum);

void BM_ShellMassProperties(benchmark::State& state) {
  const TriangleMesh& mesh = torus();
  const MassSpec spec = MassSpec::density(7850.0);
  for (auto _ : state) benchmark::DoNotOptimize(shell_mass_properties(mesh, 0.001, spec));
  report(state);
}
BENCHMARK(BM_ShellMassProperties)->Unit(benchmark::kMillisecond)->ComputeStatistics("min", minimum);

void BM_LoadStlAndSolidMassProperties(benchmark::State& state) {
  const auto path = std::filesystem::temp_directory_path() /
                    fmt::format("tumble_bench_torus_{}.stl", ::getpid());
  write_binary_stl(torus(), path);
  const MassSpec spec = MassSpec::density(7850.0);
  for (auto _ : state) {
    benchmark::DoNotOptimize(solid_mass_properties(load_mesh(path).mesh, spec));
  }
  std::filesystem::remove(path);
  report(state);
}
BENCHMARK(BM_LoadStlAndSolidMassProperties)->Unit(benchmark::kMillisecond)->ComputeStatistics("min", minimum);

}  // namespace

int main(int argc, char** argv) {
  // Defaults: 5 repetitions, only the min/median aggregates (plus mean/stddev Google Benchmark adds).
  std::vector<char*> args(argv, argv + argc);
  std::string reps = "--benchmark_repetitions=5", only = "--benchmark_report_aggregates_only=true";
  bool has_reps = false;
  for (int i = 1; i < argc; ++i) has_reps |= std::string(argv[i]).rfind("--benchmark_repetitions", 0) == 0;
  if (!has_reps) {
    args.push_back(reps.data());
    args.push_back(only.data());
  }
  int n = static_cast<int>(args.size());
  benchmark::AddCustomContext("cpu_model", bench::cpu_model());
  benchmark::AddCustomContext("hardware_threads", std::to_string(std::thread::hardware_concurrency()));
  benchmark::AddCustomContext("mesh", "torus R=1 r=0.3, 1000x1000 segments, 2e6 triangles");
  benchmark::Initialize(&n, args.data());
  if (benchmark::ReportUnrecognizedArguments(n, args.data())) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
