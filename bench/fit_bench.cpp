// `tumble fit` on 10 minutes of 10 Hz gyro data (6001 samples) of a tumbling satellite (the telemetry of
// examples/fit/make_telemetry.py: exact torque-free motion, noise 1e-4 rad/s, a bias), timed in process:
// read the CSV, fit (bias estimated: 11 unknowns), write the JSON. Beside it, one Jacobian of the 18003
// residuals by dual numbers (the fit's way) against central finite differences (2·11 + 1 runs of the
// model on doubles), to show what forward mode saves.
//
//   build/release/bin/fit_bench [MINUTES [RATE_HZ [REPETITIONS]]]     (defaults 10 10 7)
//
// Prints the machine, the settings, and min/median of the repetitions. Target (issue 25): < 1 s.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include <fmt/format.h>

#include "fit/fit_parts.hpp"
#include "machine.hpp"
#include "tumble/fit/gyro_fit.hpp"
#include "tumble/integrate/euler_poinsot.hpp"

namespace {

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

std::string min_median(std::vector<double> s, double unit, const char* suffix) {
  std::sort(s.begin(), s.end());
  return fmt::format("min {:.4g} {}, median {:.4g} {}", s.front() * unit, suffix, s[s.size() / 2] * unit,
                     suffix);
}

}  // namespace

int main(int argc, char** argv) {
  using namespace tumble;
  const double minutes = argc > 1 ? std::atof(argv[1]) : 10.0;
  const double rate = argc > 2 ? std::atof(argv[2]) : 10.0;
  const int repetitions = argc > 3 ? std::atoi(argv[3]) : 7;
  const double sigma = 1e-4;

  // The satellite of examples/fit/make_telemetry.py.
  const Vec3 Lambda(12.5, 17.0, 21.0), omega_b0(0.03, -0.02, 0.06), bias(3e-4, -2e-4, 1e-4);
  const Mat3 U = (Eigen::AngleAxisd(0.7, Vec3(1, 2, 3).normalized()) * Eigen::AngleAxisd(-0.4, Vec3::UnitX()))
                     .toRotationMatrix();
  const EulerPoinsot motion(Lambda, Quat::Identity(), omega_b0);
  std::mt19937_64 engine(25);
  std::normal_distribution<double> gauss;
  const long n = std::lround(minutes * 60 * rate) + 1;
  std::string csv = "t,wx,wy,wz\n";
  for (long k = 0; k < n; ++k) {
    const double t = static_cast<double>(k) / rate;
    const Vec3 y = U * motion.omega_b(t) + bias + sigma * Vec3(gauss(engine), gauss(engine), gauss(engine));
    csv += fmt::format("{:.10g},{:.10g},{:.10g},{:.10g}\n", t, y.x(), y.y(), y.z());
  }
  const std::filesystem::path path = std::filesystem::temp_directory_path() / "tumble_fit_bench.csv";
  std::ofstream(path) << csv;

  fmt::print(
      "tumble fit: {} min of {} Hz gyro data ({} samples), sigma {} rad/s, bias estimated (11 unknowns)\n",
      minutes, rate, n, sigma);
  fmt::print("machine: {}, {} hardware threads\n", bench::cpu_model(), std::thread::hardware_concurrency());

  std::vector<double> whole;
  fit::FitResult last;
  for (int r = 0; r < repetitions; ++r) {
    const auto start = std::chrono::steady_clock::now();
    const fit::Telemetry d = fit::read_telemetry(path);
    fit::FitOptions options;
    options.sigma = sigma;
    options.bias = true;
    last = fit::fit_gyro(d, options);
    const std::string json = fit::fit_json(last);
    whole.push_back(seconds_since(start));
    if (json.empty()) return 1;
  }
  fmt::print("result: {}, {} iterations from {} start(s), substep {:.3g} s, residual RMS {:.4f} sigma\n",
             last.determined ? "determined" : "not determined", last.iterations, last.starts, last.substep,
             last.rms_sigma);
  fmt::print("        principal moments / trace {:.6f} {:.6f} {:.6f} (truth {:.6f} {:.6f} {:.6f})\n",
             last.principal_moments.value[0], last.principal_moments.value[1],
             last.principal_moments.value[2], Lambda[0] / Lambda.sum(), Lambda[1] / Lambda.sum(),
             Lambda[2] / Lambda.sum());
  fmt::print("read + fit + JSON: {} over {} repetitions (target: < 1 s)\n", min_median(whole, 1.0, "s"),
             repetitions);

  // One Jacobian at the solution: dual numbers against central differences of the double model.
  const fit::Telemetry d = fit::read_telemetry(path);
  const fit::Layout layout{.absolute = false, .bias = true};
  const fit::Steps steps = fit::steps_of_at_most(d, last.substep * (1 + 1e-9));
  const Eigen::VectorXd p = last.parameters;
  const std::size_t m = 3 * d.t.size();
  const int P = layout.size();
  std::vector<double> r(m), jac(m * static_cast<std::size_t>(P)), rp(m), rm(m);
  std::vector<double> dual_times, fd_times, double_times;
  for (int rep = 0; rep < repetitions; ++rep) {
    auto start = std::chrono::steady_clock::now();
    (void)fit::whitened_residuals(d, steps, layout, sigma, p.data(), r.data(), nullptr);
    double_times.push_back(seconds_since(start));
    start = std::chrono::steady_clock::now();
    (void)fit::whitened_residuals(d, steps, layout, sigma, p.data(), r.data(), jac.data());
    dual_times.push_back(seconds_since(start));
    start = std::chrono::steady_clock::now();
    (void)fit::whitened_residuals(d, steps, layout, sigma, p.data(), r.data(), nullptr);
    for (int j = 0; j < P; ++j) {
      Eigen::VectorXd q = p;
      const double delta = 1e-6 * std::max(1.0, std::abs(p[j]));
      q[j] = p[j] + delta;
      (void)fit::whitened_residuals(d, steps, layout, sigma, q.data(), rp.data(), nullptr);
      q[j] = p[j] - delta;
      (void)fit::whitened_residuals(d, steps, layout, sigma, q.data(), rm.data(), nullptr);
    }
    fd_times.push_back(seconds_since(start));
  }
  fmt::print("model on doubles (residuals only):          {}\n", min_median(double_times, 1e3, "ms"));
  fmt::print("Jacobian, dual numbers (one run, N = {}):    {}\n", P, min_median(dual_times, 1e3, "ms"));
  fmt::print("Jacobian, central differences ({} runs):    {}\n", 2 * P + 1, min_median(fd_times, 1e3, "ms"));
  std::filesystem::remove(path);
  return 0;
}
