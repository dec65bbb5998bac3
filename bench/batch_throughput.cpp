// Throughput of the batched engine: body-steps per second of N free boxes tumbling under gravity, for
// each fixed-step integrator, N from 1 to 10⁶, and 1 or more threads, with the engine's memory per body.
//
//   build/release/bin/batch_throughput [out.csv] [repetitions] [max_N] [integrators,...] [threads,...]
//                                      [steps_per_call,...]
//
// The scenario is the one of bench/peers (boxes 0.1 × 0.2 × 0.3 m, 6 kg, |ω| = 10 rad/s in random
// directions, random attitudes, g = 9.81 m/s², h = 1e-3 s, mixed formulation). Each measurement steps
// the system directly for at least 0.3 s of wall time, `steps_per_call` steps per call of
// Integrator::steps (1: step by step; 16: the chunks simulate() hands over between samples, which fused
// integrators take through each block in cache); repetitions are interleaved
// (every configuration once, then again), and min and median are printed. Memory is what the
// integrator's workspace and the state allocate (tests/support/allocation_counter), per body.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "../tests/support/allocation_counter.hpp"
#include "boxes.hpp"
#include "machine.hpp"
#include "tumble/forces/forces.hpp"
#include "tumble/integrate/integrator.hpp"

using namespace tumble;

namespace {

std::vector<std::string> split(const std::string& s) {
  std::vector<std::string> out;
  std::stringstream in(s);
  for (std::string item; std::getline(in, item, ',');) out.push_back(item);
  return out;
}

struct Config {
  std::string integrator;
  long n;
  int threads;
  long steps_per_call;
  std::vector<double> rates;  // body-steps per second, one per repetition
  double bytes_per_body = 0;
};

using bench::boxes;

void measure(Config& c, const Model& model, const SystemState& s0) {
  const Formulation F = Formulation::mixed;
  const double h = 1e-3;
  test::CountAllocations counting;
  SystemCoordinates x = to_coordinates(F, s0);
  auto integrator = make_integrator(c.integrator);
  integrator->set_threads(c.threads);
  integrator->step(model, F, x, h);  // binds and sizes the workspace
  c.bytes_per_body = static_cast<double>(counting.bytes()) / static_cast<double>(c.n);
  long steps = 0;
  const auto t0 = std::chrono::steady_clock::now();
  double elapsed = 0;
  do {
    integrator->steps(model, F, x, h, c.steps_per_call);
    steps += c.steps_per_call;
    elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  } while (elapsed < 0.3);
  c.rates.push_back(static_cast<double>(steps) * static_cast<double>(c.n) / elapsed);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc > 1 && (std::string(argv[1]) == "--help" || std::string(argv[1]) == "-h")) {
    std::printf(
        "usage: batch_throughput [out.csv] [repetitions] [max_N] [integrators,...] [threads,...] "
        "[steps_per_call,...]\n"
        "  body-steps per second of N free boxes under gravity (h = 1e-3 s, mixed), N = 1, 100, ... max_N;\n"
        "  defaults: batch_throughput.csv 3 1000000 rk4,semi_implicit_euler,euler,lie_rk4,midpoint,"
        "implicit_gyro,splitting 1,2 1,16\n");
    return 0;
  }
  const std::string csv_path = argc > 1 ? argv[1] : "batch_throughput.csv";
  const int repetitions = argc > 2 ? std::max(1, std::atoi(argv[2])) : 3;
  const long max_n = argc > 3 ? std::atol(argv[3]) : 1000000;
  const std::vector<std::string> integrators =
      split(argc > 4 ? argv[4] : "rk4,semi_implicit_euler,euler,lie_rk4,midpoint,implicit_gyro,splitting");
  std::vector<int> thread_counts;
  for (const std::string& t : split(argc > 5 ? argv[5] : "1,2"))
    thread_counts.push_back(std::atoi(t.c_str()));
  std::vector<long> chunks;
  for (const std::string& k : split(argc > 6 ? argv[6] : "1,16"))
    chunks.push_back(std::max(1L, std::atol(k.c_str())));

  std::printf(
      "batched engine throughput: free boxes under gravity, h = 1e-3 s, mixed formulation, %d interleaved "
      "repetitions of >= 0.3 s\nmachine: %s, %u hardware threads; engine built for %s (%d doubles per "
      "pack)\n\n",
      repetitions, bench::cpu_model().c_str(), std::thread::hardware_concurrency(),
      engine_info().instruction_set.c_str(), engine_info().lanes);
  std::vector<long> sizes;
  for (long n : {1L, 100L, 10000L, 100000L, 1000000L}) {
    if (n <= max_n) sizes.push_back(n);
  }
  std::vector<Config> configs;
  for (long n : sizes) {
    for (const std::string& name : integrators) {
      for (int t : thread_counts) {
        for (long k : chunks) configs.push_back({name, n, t, k, {}, 0});
      }
    }
  }
  for (long n : sizes) {
    Model model;
    const SystemState s0 = boxes(n, model);
    for (int r = 0; r < repetitions; ++r) {
      for (Config& c : configs) {
        if (c.n == n) measure(c, model, s0);
      }
    }
  }
  std::ofstream csv(csv_path);
  csv << "integrator,N,threads,steps_per_call,repetitions,rate_min,rate_median,bytes_per_body\n";
  std::printf("%-20s %8s %7s %6s %14s %14s %10s\n", "integrator", "N", "threads", "steps", "min /s",
              "median /s", "B/body");
  for (Config& c : configs) {
    std::sort(c.rates.begin(), c.rates.end());
    const double med = c.rates[c.rates.size() / 2];
    std::printf("%-20s %8ld %7d %6ld %14.4g %14.4g %10.0f\n", c.integrator.c_str(), c.n, c.threads,
                c.steps_per_call, c.rates.front(), med, c.bytes_per_body);
    csv << c.integrator << ',' << c.n << ',' << c.threads << ',' << c.steps_per_call << ',' << repetitions
        << ',' << c.rates.front() << ',' << med << ',' << c.bytes_per_body << '\n';
  }
  std::printf("\nCSV: %s\n", csv_path.c_str());
}
