// Sensitivities (issue 25, its Targets): what the state transition matrix costs and how accurate it is,
// in one run.
//
//   build/release/bin/sensitivity_bench [repetitions] [t_handle.toml] [wait_minutes]
//
// 1. Cost per tangent direction: N free triaxial boxes under uniform gravity (rk4, h = 1e-3 s, mixed
//    formulation, one thread, samples only at the start and the end), timed by simulate() (the batched
//    SIMD engine) and by simulate_sensitivities() (dual numbers, 12 state + 3 moment directions per
//    body in one pass of 16 slots, on packs: integrate/tangent_packs.hpp) over the same run:
//    body-steps/s of each, their ratio, and the ratio per state direction (/12) in units of one state
//    step. Target: ≤ 2 per direction (≤ 25 for 12).
// 2. Finite differences beside it: the same STM by stm_by_central_differences (2·12·B runs of all B
//    bodies; the "+1", the nominal run, it does not need) for N = 1 and 10, its wall time
//    against simulate_sensitivities', and the largest difference between the two matrices.
// 3. Accuracy: the STM of rk4 at h = 1e-3 against a reference: (a) a triaxial body tumbling far from
//    its separatrix (target 1e-7), (b) the tutorial's T-handle (examples/t_handle.toml) through a flip
//    (target 1e-4). The reference is the same dual-number STM at h/128; rk4 from 8h down to h/128 shows
//    the h⁴ trend down to rounding (h/64 against h/128: converged), and central differences of the
//    closed-form Euler–Poinsot flow (integrator "exact", over a range of steps ε) cross-check it. The
//    STMs of exact and splitting (the exact flow differentiated) against the same reference: target for
//    exact 1e-10 on the well-conditioned case. Section 1 also times splitting's STM.
//
// Timings are the min and median of interleaved repetitions; the load average is printed beside them
// (before each timing the program waits, up to wait_minutes (5) minutes, for it to fall below 1.2).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include "boxes.hpp"
#include "machine.hpp"
#include "tumble/forces/forces.hpp"
#include "tumble/integrate/integrator.hpp"
#include "tumble/io/scene.hpp"
#include "tumble/sim/finite_difference_stm.hpp"
#include "tumble/sim/sensitivities.hpp"
#include "tumble/sim/simulate.hpp"

using namespace tumble;

namespace {

double load_average() {
  std::ifstream in("/proc/loadavg");
  double load = -1;
  in >> load;
  return load;
}

int g_wait_minutes = 5;

/// Waits (up to g_wait_minutes minutes) for the 1-minute load average to fall below 1.2; returns it.
double wait_for_quiet() {
  double load = load_average();
  for (int i = 0; i < g_wait_minutes && load > 1.2; ++i) {
    std::printf("  (load average %.2f > 1.2: waiting 60 s)\n", load);
    std::fflush(stdout);
    std::this_thread::sleep_for(std::chrono::seconds(60));
    load = load_average();
  }
  return load;
}

double seconds(const std::function<void()>& f) {
  const auto t0 = std::chrono::steady_clock::now();
  f();
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

struct Stats {
  double min, median;
};
Stats stats(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return {v.front(), v.size() % 2 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2])};
}

using bench::boxes;

RunSettings rk4_settings(double duration, double h) {
  RunSettings rs;
  rs.duration = duration;
  rs.timestep = h;
  rs.output_interval = duration;  // samples at the start and the end only
  rs.integrator = "rk4";
  rs.formulation = Formulation::mixed;
  rs.threads = 1;
  rs.drift_threshold = 0.0;
  return rs;
}

/// The sensitivities at the end of a run.
Sensitivities stm_at_end(const Model& model, const SystemState& s0, const RunSettings& rs) {
  Sensitivities last;
  (void)simulate_sensitivities(model, s0, rs, SensitivityParameters::inertia,
                               [&](const SystemState&, const Sensitivities& s) {
                                 last = s;
                                 return true;
                               });
  return last;
}

double max_abs(const Eigen::MatrixXd& m) { return m.cwiseAbs().maxCoeff(); }

std::string fmt_e(double x) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.2e", x);
  return buffer;
}

// ---- 1. cost per tangent direction ----

void cost_per_direction(long n, double duration, int repetitions, const std::string& integrator = "rk4") {
  Model model;
  const SystemState s0 = boxes(n, model);
  RunSettings rs = rk4_settings(duration, 1e-3);
  rs.integrator = integrator;
  const double body_steps = static_cast<double>(n) * std::round(duration / rs.timestep);
  // One untimed run of each first (page faults, caches).
  (void)simulate(model, s0, rs);
  (void)stm_at_end(model, s0, rs);
  // simulate() is timed over `inner` back-to-back runs (≥ ~50 ms), per run.
  const double once = seconds([&] { (void)simulate(model, s0, rs); });
  const int inner = std::max(1, static_cast<int>(std::ceil(0.05 / std::max(once, 1e-6))));
  const double load = wait_for_quiet();
  std::vector<double> t_state, t_tangent;
  for (int r = 0; r < repetitions; ++r) {
    t_state.push_back(seconds([&] {
                        for (int i = 0; i < inner; ++i) (void)simulate(model, s0, rs);
                      }) /
                      inner);
    t_tangent.push_back(seconds([&] {
      (void)simulate_sensitivities(model, s0, rs, SensitivityParameters::inertia,
                                   [](const SystemState&, const Sensitivities&) { return true; });
    }));
  }
  const Stats a = stats(t_state), b = stats(t_tangent);
  std::vector<double> ratios;
  for (int r = 0; r < repetitions; ++r) ratios.push_back(t_tangent[r] / t_state[r]);
  const Stats q = stats(ratios);
  std::printf(
      "N = %-5ld %6.0f steps of %s  simulate               %9.5f s min %9.5f s median  %10.4g body-steps/s "
      "(median; each repetition %d runs)\n",
      n, std::round(duration / rs.timestep), integrator.c_str(), a.min, a.median, body_steps / a.median,
      inner);
  std::printf(
      "                      simulate_sensitivities %9.5f s min %9.5f s median  %10.4g body-steps/s "
      "(median)\n",
      b.min, b.median, body_steps / b.median);
  std::printf(
      "                      ratio (sensitivities / simulate): %.1f (min/min), %.1f (median/median), %.1f "
      "(median of the paired ratios)\n",
      b.min / a.min, b.median / a.median, q.median);
  std::printf(
      "                      per state direction (ratio / 12): %.2f state steps (min/min), %.2f (median); "
      "per carried direction (ratio / 15): %.2f; %.2f us per body-step with tangents; load %.2f\n\n",
      b.min / a.min / 12, b.median / a.median / 12, b.median / a.median / 15, 1e6 * b.median / body_steps,
      load);
}

// ---- 2. finite differences beside it ----

void finite_differences(long n, double duration, int repetitions) {
  Model model;
  const SystemState s0 = boxes(n, model);
  const RunSettings rs = rk4_settings(duration, 1e-3);
  const double eps = 1e-6;
  const Eigen::MatrixXd dual = stm_at_end(model, s0, rs).dense_stm();
  const Eigen::MatrixXd fd = stm_by_central_differences(model, s0, rs, eps);
  const Eigen::MatrixXd fd2 = stm_by_central_differences(model, s0, rs, 2 * eps);
  const double load = wait_for_quiet();
  std::vector<double> t_fd, t_dual;
  for (int r = 0; r < repetitions; ++r) {
    t_fd.push_back(seconds([&] { (void)stm_by_central_differences(model, s0, rs, eps); }));
    t_dual.push_back(seconds([&] { (void)stm_at_end(model, s0, rs); }));
  }
  const Stats f = stats(t_fd), d = stats(t_dual);
  std::printf(
      "N = %-3ld %5.0f steps, %ld runs of all N bodies (24 per body, + the nominal run)   load %.2f\n", n,
      std::round(duration / rs.timestep), 24 * n, load);
  std::printf("        central differences (eps = %g)  %9.4f s min %9.4f s median\n", eps, f.min, f.median);
  std::printf(
      "        simulate_sensitivities           %9.4f s min %9.4f s median   FD / dual: %.1f (median)\n",
      d.min, d.median, f.median / d.median);
  std::printf(
      "        max |STM_dual - STM_fd| = %.2e (max |STM| = %.3g); FD's own error, max |FD(eps) - FD(2 eps)| "
      "= %.2e\n\n",
      max_abs(dual - fd), max_abs(dual), max_abs(fd - fd2));
}

// ---- 3. accuracy ----

/// Sign changes of ^bω₂ (the intermediate principal axis) sampled every 0.01 s along the exact flow:
/// the flips, for a body spun about that axis.
int omega2_sign_changes(const Model& model, const SystemState& s0, double duration) {
  RunSettings rs = rk4_settings(duration, 1e-3);
  rs.integrator = "exact";
  rs.output_interval = 0.01;
  int count = 0;
  double last = s0.bodies[0].omega_b()(1);
  (void)simulate(model, s0, rs, [&](const SystemState& s) {
    const double w = s.bodies[0].omega_b()(1);
    if ((w < 0) != (last < 0)) ++count;
    last = w;
    return true;
  });
  return count;
}

/// `target` is rk4's; `exact_target` that of exact's STM (0: none, the case is ill-conditioned).
void accuracy(const std::string& name, const Model& model, const SystemState& s0, double duration,
              double target, double exact_target) {
  const double h = 1e-3;
  const RigidBody& body = model.bodies[0];
  const Vec3 w = s0.bodies[0].omega_b(), I = body.Lambda();
  const double L2 = (I.array() * w.array()).square().sum(), twoE = (I.array() * w.array().square()).sum();
  std::printf("%s\n", name.c_str());
  std::printf(
      "  %.3g s torque-free; (L^2 - 2 E I2) / L^2 = %.3g (0: the separatrix; > 0: circulating about the "
      "major axis, < 0: the minor); ^b omega_2 changes sign %d times\n",
      duration, (L2 - twoE * I(1)) / L2, omega2_sign_changes(model, s0, duration));

  // rk4 at 8h … h/128: the reference is h/128; the differences show the h^4 trend down to rounding.
  const std::vector<double> factors = {8,       4,        2,        1,        1.0 / 2,  1.0 / 4,
                                       1.0 / 8, 1.0 / 16, 1.0 / 32, 1.0 / 64, 1.0 / 128};
  const size_t at_h = 3, at_h64 = factors.size() - 2;
  std::vector<Eigen::MatrixXd> S;
  for (double f : factors) S.push_back(stm_at_end(model, s0, rk4_settings(duration, h * f)).dense_stm());
  const Eigen::MatrixXd& ref = S.back();
  const double scale = max_abs(ref);

  // Independently: central differences of the closed-form flow, over a range of steps (truncation ~eps^2
  // down to where rounding takes over).
  RunSettings exact = rk4_settings(duration, h);
  exact.integrator = "exact";
  double best_eps = 0, best = INFINITY;
  Eigen::MatrixXd fd_exact;
  std::printf(
      "  cross-check, central differences of 'exact' (closed-form Euler-Poinsot flow): max |FD - STM_ref| at "
      "eps");
  for (double eps : {1e-4, 1e-5, 1e-6, 1e-7, 1e-8}) {
    Eigen::MatrixXd F = stm_by_central_differences(model, s0, exact, eps);
    const double e = max_abs(F - ref);
    std::printf(" %g: %.1e;", eps, e);
    if (e < best) {
      best = e;
      best_eps = eps;
      fd_exact = std::move(F);
    }
  }
  std::printf("\n  max |STM_ref| = %.4g\n", scale);
  std::printf("  %-10s %22s %22s %22s\n", "rk4 step", "max|S(step)-S(step/2)|", "max|S(step)-S_ref|",
              "max|S(step)-FD_exact|");
  for (size_t i = 0; i < factors.size(); ++i) {
    const std::string next = i + 1 < factors.size() ? fmt_e(max_abs(S[i] - S[i + 1])) : "-";
    std::printf("  %-10.4g %22s %22s %22s\n", h * factors[i], next.c_str(),
                i + 1 < factors.size() ? fmt_e(max_abs(S[i] - ref)).c_str() : "(reference)",
                fmt_e(max_abs(S[i] - fd_exact)).c_str());
  }
  const double err = max_abs(S[at_h] - ref);
  Eigen::Index row = 0, col = 0;
  (void)(S[at_h] - ref).cwiseAbs().maxCoeff(&row, &col);
  static const char* kComponent[12] = {"p1", "p2", "p3", "th1", "th2", "th3",
                                       "v1", "v2", "v3", "w1",  "w2",  "w3"};
  std::printf(
      "  => reference converged: max |S(h/64) - S(h/128)| = %.1e (%.1e relative); FD of 'exact' (eps %g) "
      "agrees with it to %.1e (%.1e relative)\n",
      max_abs(S[at_h64] - ref), max_abs(S[at_h64] - ref) / scale, best_eps, best, best / scale);
  std::printf(
      "  => rk4 at h = 1e-3: max |STM - STM_ref| = %.2e absolute, %.2e relative to max |STM_ref| (target "
      "%.0e: %s); largest at d%s(T)/d%s(0) = %.9g (ref %.9g)\n",
      err, err / scale, target, err <= target ? "met" : "MISSED", kComponent[row % 12], kComponent[col % 12],
      S[at_h](row, col), ref(row, col));
  std::printf(
      "     rk4's own error at h, extrapolated from 2h by h^4: max |S(2h) - S_ref| / 16 = %.1e (%.1e "
      "relative)\n",
      max_abs(S[at_h - 1] - ref) / 16, max_abs(S[at_h - 1] - ref) / 16 / scale);
  // The exact flow differentiated: exact in closed form from the start, splitting step by step (a free
  // body's Strang step is the flow itself). Both within the reference's own convergence of the truth.
  for (const char* method : {"exact", "splitting"}) {
    RunSettings rs = rk4_settings(duration, h);
    rs.integrator = method;
    const Eigen::MatrixXd E = stm_at_end(model, s0, rs).dense_stm();
    const double e = max_abs(E - ref);
    const std::string verdict = exact_target == 0.0
                                    ? "no target here: near the separatrix a double-precision reference is "
                                      "good only to its own convergence"
                                : e <= exact_target ? "target " + fmt_e(exact_target) + ": met"
                                                    : "target " + fmt_e(exact_target) + ": MISSED";
    std::printf(
        "  => %-9s at h = 1e-3: max |STM - STM_ref| = %.2e absolute, %.2e relative (%s; the reference's own "
        "convergence %.1e)\n",
        method, e, e / scale, verdict.c_str(), max_abs(S[at_h64] - ref));
  }
  std::printf("\n");
}

}  // namespace

int main(int argc, char** argv) {
  if (argc > 1 && (std::string(argv[1]) == "--help" || std::string(argv[1]) == "-h")) {
    std::printf(
        "usage: sensitivity_bench [repetitions] [t_handle.toml] [wait_minutes]   (defaults: 7, "
        "examples/t_handle.toml, 5)\n");
    return 0;
  }
  const int repetitions = argc > 1 ? std::max(5, std::atoi(argv[1])) : 7;
  std::filesystem::path scene_path = argc > 2 ? argv[2] : "examples/t_handle.toml";
  if (argc > 3) g_wait_minutes = std::max(0, std::atoi(argv[3]));
  if (argc <= 2 && !std::filesystem::exists(scene_path)) {
    // Run from elsewhere than the source tree: the example beside this file's.
    scene_path = std::filesystem::path(__FILE__).parent_path().parent_path() / "examples" / "t_handle.toml";
  }

  const EngineInfo engine = engine_info();
  std::printf("sensitivity_bench: the STM by dual numbers (issue 25 targets), %d interleaved repetitions\n",
              repetitions);
  std::printf("machine: %s, %u hardware threads; engine built for %s (%d doubles per pack); load %.2f\n",
              bench::cpu_model().c_str(), std::thread::hardware_concurrency(), engine.instruction_set.c_str(),
              engine.lanes, load_average());
  std::printf(
      "settings: rk4, h = 1e-3 s, mixed formulation, one thread, output only at start and end; "
      "sensitivities with respect to x(0) and the principal moments (12 + 3 directions, %d slots a body;\n"
      "rk4 steps them on packs of %d lanes, a lane a body's 2 or 4 slots, Dual<Pack, 2 or 4>: "
      "src/integrate/tangent_packs.hpp; splitting a body at a time on Dual<double, %d>; simulate() steps "
      "packs of %d bodies)\n\n",
      kTangentDirections, engine.lanes, kTangentDirections, engine.lanes);

  const auto t_start = std::chrono::steady_clock::now();
  std::printf(
      "== 1. cost per tangent direction: N free boxes under gravity, simulate() against "
      "simulate_sensitivities() ==\n");
  cost_per_direction(1, 20.0, repetitions);
  cost_per_direction(1000, 0.2, repetitions);
  cost_per_direction(1000, 0.2, repetitions, "splitting");

  std::printf("== 2. central differences (stm_by_central_differences) beside the dual numbers, 2 s ==\n");
  finite_differences(1, 2.0, repetitions);
  finite_differences(10, 2.0, 5);

  std::printf(
      "== 3. accuracy of the rk4 STM at h = 1e-3 against a converged reference (whole 12 x 12 STM, dual "
      "numbers) ==\n"
      "(and the STMs of 'exact' and 'splitting' at h, the exact torque-free flow differentiated: target for "
      "exact 1e-10; central differences of 'exact' cross-check the reference independently)\n");
  {
    Model model;
    model.add_body(RigidBody::from_principal_moments(1.0, Vec3(1e-2, 2e-2, 3e-2), "triaxial"));
    SystemState s0;
    s0.bodies.push_back(BodyState{Vec3::Zero(), Quat::Identity(), Vec3::Zero(), Vec3(1.0, 0.5, 2.0)});
    accuracy("(a) well conditioned: moments (1, 2, 3)e-2 kg m^2, omega_b = (1, 0.5, 2) rad/s", model, s0, 2.0,
             1e-7, 1e-10);
  }
  {
    const Scene scene = load_scene(scene_path);
    const RigidBody& body = scene.model.bodies[0];
    const Vec3 w = scene.initial.bodies[0].omega_b();
    char name[512];
    std::snprintf(name, sizeof name,
                  "(b) T-handle near its separatrix: %s (mesh, 2700 kg/m^3), principal moments (%.6g, %.6g, "
                  "%.6g) kg m^2, omega_b = (%g, %g, %g) rad/s",
                  scene_path.string().c_str(), body.Lambda()(0), body.Lambda()(1), body.Lambda()(2), w(0),
                  w(1), w(2));
    accuracy(name, scene.model, scene.initial, 5.0, 1e-4, 0.0);
  }
  std::printf("total %.1f s\n",
              std::chrono::duration<double>(std::chrono::steady_clock::now() - t_start).count());
}
