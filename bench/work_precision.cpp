// Work–precision of every integrator on the torque-free T-handle over 100 s: the error at the end
// against the exact Euler–Poinsot solution versus force evaluations and wall time.
//
//   build/release/bin/work_precision [out.csv] [repetitions]
//
// Prints the machine, the settings and a table (min and median wall time of the repetitions), and
// writes the same rows as CSV.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <string>
#include <thread>
#include <vector>

#include "machine.hpp"
#include "tumble/integrate/euler_poinsot.hpp"
#include "tumble/sim/simulate.hpp"

using namespace tumble;

namespace {

struct Row {
  std::string method;
  std::string setting;
  double attitude_error, omega_error;
  long evaluations, steps;
  double t_min, t_median;
};

}  // namespace

int main(int argc, char** argv) {
  if (argc > 1 && (std::string(argv[1]) == "--help" || std::string(argv[1]) == "-h")) {
    std::printf("usage: work_precision [out.csv] [repetitions]   (defaults: work_precision.csv 3)\n");
    return 0;
  }
  const std::string csv_path = argc > 1 ? argv[1] : "work_precision.csv";
  const int repetitions = argc > 2 ? std::max(1, std::atoi(argv[2])) : 3;
  const Vec3 Lambda(1.2e-5, 3.1e-5, 4.0e-5);  // T-handle, kg·m²
  const Vec3 omega_b0(2.0, 20.0, 2.0);        // rad/s, about the intermediate axis
  const double T = 100.0;
  const EulerPoinsot exact(Lambda, Quat::Identity(), omega_b0);
  Model model;
  model.add_body(RigidBody::from_principal_moments(0.1, Lambda, "t_handle"));
  const SystemState s0{0.0, {BodyState{Vec3::Zero(), Quat::Identity(), Vec3::Zero(), omega_b0}}, {}};

  std::printf(
      "work-precision: torque-free T-handle, Lambda = (%g, %g, %g) kg m^2, omega_b(0) = (%g, %g, %g) "
      "rad/s,\n",
      Lambda(0), Lambda(1), Lambda(2), omega_b0(0), omega_b0(1), omega_b0(2));
  std::printf(
      "T = %g s (%.0f flips), mixed formulation, %d repetitions; machine: %s, %u hardware threads\n\n", T,
      T / exact.flip_interval(), repetitions, bench::cpu_model().c_str(),
      std::thread::hardware_concurrency());

  std::vector<Row> rows;
  auto measure = [&](const std::string& method, const std::string& setting, RunSettings rs) {
    rs.duration = T;
    rs.output_interval = T;
    rs.integrator = method;
    rs.formulation = Formulation::mixed;
    std::vector<double> times;
    SystemState end;
    IntegratorStats stats;
    for (int r = 0; r < repetitions; ++r) {
      const auto t0 = std::chrono::steady_clock::now();
      end = simulate(model, s0, rs, {}, &stats);
      times.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
    }
    std::sort(times.begin(), times.end());
    const BodyState& b = end.bodies[0];
    rows.push_back({method, setting, rotation_angle_between(b.R(), exact.R(T)),
                    (b.omega_b() - exact.omega_b(T)).norm() / omega_b0.norm(), stats.evaluations, stats.steps,
                    times.front(), times[times.size() / 2]});
    const Row& row = rows.back();
    std::printf(
        "%-20s %-12s attitude %-9.2e omega %-9.2e evals %-9ld steps %-9ld wall min %.4f s median %.4f s\n",
        row.method.c_str(), row.setting.c_str(), row.attitude_error, row.omega_error, row.evaluations,
        row.steps, row.t_min, row.t_median);
    std::fflush(stdout);
  };

  for (const std::string method : {"exact", "splitting", "splitting4", "midpoint", "rk4", "lie_rk4",
                                   "implicit_gyro", "semi_implicit_euler", "euler"}) {
    for (double h : {0.1, 0.03, 0.01, 3e-3, 1e-3, 3e-4}) {
      RunSettings rs;
      rs.timestep = h;
      char setting[32];
      std::snprintf(setting, sizeof setting, "h=%g", h);
      try {
        measure(method, setting, rs);
      } catch (const std::exception& e) {
        std::printf("%-20s %-12s failed: %s\n", method.c_str(), setting, e.what());
      }
    }
  }
  for (double tol : {1e-4, 1e-6, 1e-8, 1e-10, 1e-12}) {
    RunSettings rs;
    rs.timestep = 1e-3;
    rs.tolerances = {tol, tol * 1e-3};
    char setting[32];
    std::snprintf(setting, sizeof setting, "rtol=%g", tol);
    measure("dopri45", setting, rs);
  }
  {
    // The exact solution itself, evaluated once at T.
    std::vector<double> times;
    for (int r = 0; r < repetitions; ++r) {
      const auto t0 = std::chrono::steady_clock::now();
      const EulerPoinsot flow(Lambda, Quat::Identity(), omega_b0);
      volatile double sink = flow.q(T).w();
      (void)sink;
      times.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
    }
    std::sort(times.begin(), times.end());
    rows.push_back({"euler_poinsot", "exact", 0.0, 0.0, 0, 0, times.front(), times[times.size() / 2]});
  }

  std::ofstream csv(csv_path);
  csv << "method,setting,attitude_error_rad,omega_rel_error,evaluations,steps,wall_min_s,wall_median_s\n";
  for (const Row& r : rows) {
    csv << r.method << ',' << r.setting << ',' << r.attitude_error << ',' << r.omega_error << ','
        << r.evaluations << ',' << r.steps << ',' << r.t_min << ',' << r.t_median << '\n';
  }
  std::printf("\nwrote %s\n", csv_path.c_str());
  return 0;
}
