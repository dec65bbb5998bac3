// Rotors' cost (issue 26's target: a body with three wheels at ≥ 1e7 body-steps/s with rk4): N boxes
// under gravity (bench/boxes.hpp) stepped by simulate() with rk4 at h = 1e-3, one thread, without
// rotors and with three orthogonal wheels on every body (J = 1e-3 kg m², 100 rad/s, motor torque
// 1e-4 N m), interleaved; the min and median of the repetitions, and their ratio. Another integrator and
// motor torque may be given: `splitting 0` times the splittings' drift by the gyrostat's own flow (the
// wheels' speeds held), `splitting 1e-4` their G D₁ G (a motor working).
//
//   build/release/bin/rotor_throughput [N = 10000] [repetitions = 5] [integrator = rk4] [torque = 1e-4]
#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <string>
#include <thread>
#include <vector>

#include "boxes.hpp"
#include "machine.hpp"
#include "tumble/forces/rotors.hpp"
#include "tumble/sim/simulate.hpp"

using namespace tumble;

int main(int argc, char** argv) {
  const long n = argc > 1 ? std::atol(argv[1]) : 10000;
  const int repetitions = argc > 2 ? std::max(1, std::atoi(argv[2])) : 5;
  const std::string integrator = argc > 3 ? argv[3] : "rk4";
  const double torque = argc > 4 ? std::atof(argv[4]) : 1e-4;
  Model plain;
  const SystemState s0 = bench::boxes(n, plain);
  Model wheels = plain;
  std::vector<Rotor> rotors;
  for (long i = 0; i < n; ++i) {
    for (int k = 0; k < 3; ++k) {
      rotors.push_back({fmt::format("w{}_{}", i, k),
                        static_cast<size_t>(i),
                        Vec3::Unit(k),
                        1e-3,
                        100.0,
                        torque,
                        0.0,
                        0.0,
                        {}});
    }
  }
  wheels.forces.push_back(std::make_shared<const Rotors>(std::move(rotors), wheels.bodies));
  RunSettings rs;
  rs.integrator = integrator;
  rs.timestep = 1e-3;
  rs.duration = 0.1;
  rs.output_interval = rs.duration;
  rs.threads = 1;
  rs.drift_threshold = 0.0;
  const double body_steps = static_cast<double>(n) * 100.0;
  auto seconds = [&](const Model& m) {
    const auto t0 = std::chrono::steady_clock::now();
    (void)simulate(m, s0, rs);
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  };
  (void)seconds(plain);
  (void)seconds(wheels);
  std::vector<double> a, b;
  for (int r = 0; r < repetitions; ++r) {
    a.push_back(seconds(plain));
    b.push_back(seconds(wheels));
  }
  std::sort(a.begin(), a.end());
  std::sort(b.begin(), b.end());
  const auto median = [](const std::vector<double>& v) { return v[v.size() / 2]; };
  fmt::print(
      "rotor_throughput: {} boxes, {}, motor torque {} N m, h = 1e-3 s, 100 steps, one thread; {}; {} "
      "hardware threads\n",
      n, integrator, torque, bench::cpu_model(), std::thread::hardware_concurrency());
  fmt::print("  no rotors:       {:.4g} body-steps/s (median), {:.4g} (best)\n", body_steps / median(a),
             body_steps / a.front());
  fmt::print("  three wheels:    {:.4g} body-steps/s (median), {:.4g} (best){}\n", body_steps / median(b),
             body_steps / b.front(), integrator == "rk4" ? "   target >= 1e7" : "");
  fmt::print("  cost of the wheels: {:.2f}x (median/median)\n", median(b) / median(a));
}
