// Ensembles: draws that depend on (seed, run) alone and follow their distributions, tables that do not
// depend on threads, per-run physics against the closed form, and clear errors for bad studies.
#include <gtest/gtest.h>

#include <fmt/format.h>

#include <bit>
#include <cmath>
#include <numbers>
#include <set>

#include "../support/closed_forms.hpp"
#include "../support/scene_files.hpp"
#include "tumble/io/ensemble.hpp"
#include "tumble/study/runs.hpp"

namespace tumble {
namespace {

// A box spun near its intermediate axis (no mesh: fast), with a flip event.
EnsembleStudy study(const std::string& ensemble) {
  return EnsembleStudy::parse(test::racket_scene(8.0) + ensemble, "study.toml");
}

/// The draws of every run, column k.
std::vector<double> column(const EnsembleStudy& s, size_t k) {
  std::vector<double> x;
  for (long i = 0; i < s.runs(); ++i) x.push_back(s.draws(i)[k]);
  return x;
}

double mean(const std::vector<double>& x) {
  double sum = 0;
  for (double v : x) sum += v;
  return sum / static_cast<double>(x.size());
}

double variance(const std::vector<double>& x) {
  const double m = mean(x);
  double sum = 0;
  for (double v : x) sum += (v - m) * (v - m);
  return sum / static_cast<double>(x.size() - 1);
}

// The tests of the sample moments below allow 5 standard errors: a correct generator fails one with
// probability below 1e-6; a wrong distribution (a wrong scale, shift or shape) misses by far more.
constexpr double kSigmas = 5.0;

TEST(Ensemble, DrawsFollowTheirDistributionsAndDependOnSeedAndRunAlone) {
  const EnsembleStudy s = study(R"([ensemble]
runs = 20000
seed = 7
[[ensemble.vary]]
path = "bodies.racket.angular_velocity[0]"
distribution = "uniform"
low = -1.0
high = 3.0
[[ensemble.vary]]
path = "bodies.racket.angular_velocity[1]"
distribution = "normal"
mean = 10.0
std = 0.5
[[ensemble.vary]]
path = "bodies.racket.mass"
distribution = "lognormal"
mu = 0.0
sigma = 0.25
[[ensemble.vary]]
path = "simulation.duration"
distribution = "truncated_normal"
mean = 1.0
std = 1.0
low = 0.5
high = 2.0
)");
  const double n = static_cast<double>(s.runs());
  // uniform(−1, 3): mean 1, variance 16/12.
  const auto u = column(s, 0);
  EXPECT_NEAR(mean(u), 1.0, kSigmas * std::sqrt(16.0 / 12 / n));
  EXPECT_NEAR(variance(u), 16.0 / 12, kSigmas * std::sqrt(16.0 * 16 / 180 / n));  // var of s²: (μ₄ − σ⁴)/n
  for (double v : u) EXPECT_TRUE(v > -1.0 && v < 3.0);
  // normal(10, 0.5).
  const auto g = column(s, 1);
  EXPECT_NEAR(mean(g), 10.0, kSigmas * 0.5 / std::sqrt(n));
  EXPECT_NEAR(std::sqrt(variance(g)), 0.5, kSigmas * 0.5 / std::sqrt(2 * n));
  // lognormal(0, 0.25): mean e^{σ²/2}, variance (e^{σ²} − 1) e^{σ²}.
  const auto l = column(s, 2);
  const double s2 = 0.25 * 0.25;
  EXPECT_NEAR(mean(l), std::exp(s2 / 2), kSigmas * std::sqrt((std::exp(s2) - 1) * std::exp(s2) / n));
  // truncated normal(1, 1) on [0.5, 2]: mean μ + σ (φ(α) − φ(β)) / (Φ(β) − Φ(α)), α = −0.5, β = 1.
  const auto t = column(s, 3);
  const auto phi = [](double x) { return std::exp(-x * x / 2) / std::sqrt(2 * std::numbers::pi); };
  const auto Phi = [](double x) { return 0.5 * std::erfc(-x / std::sqrt(2.0)); };
  const double tm = 1.0 + (phi(-0.5) - phi(1.0)) / (Phi(1.0) - Phi(-0.5));
  EXPECT_NEAR(mean(t), tm, kSigmas * std::sqrt(variance(t) / n));
  for (double v : t) EXPECT_TRUE(v >= 0.5 && v <= 2.0);
  // Run 123's draws are the same from another load of the study, and differ from run 124's.
  const EnsembleStudy again = study(R"([ensemble]
runs = 5
seed = 7
[[ensemble.vary]]
path = "bodies.racket.angular_velocity[0]"
distribution = "uniform"
low = -1.0
high = 3.0
)");
  EXPECT_EQ(again.draws(3)[0], s.draws(3)[0]) << "the same (seed, run, variation): the same value";
  EXPECT_NE(s.draws(123)[0], s.draws(124)[0]);
  // The drawn value is what the run's scene holds.
  EXPECT_EQ(s.scene_of_run(5).model.bodies[0].mass(), s.draws(5)[2]);
  EXPECT_EQ(s.scene_of_run(5).settings.duration, s.draws(5)[3]);
}

TEST(Ensemble, RandomRotationsAndDirectionsAreUniform) {
  const EnsembleStudy s = study(R"([ensemble]
runs = 20000
[[ensemble.vary]]
path = "bodies.racket.angular_velocity"
distribution = "direction"
magnitude = 2.0
[[ensemble.vary]]
path = "bodies.racket.orientation"
distribution = "rotation"
)");
  const double n = static_cast<double>(s.runs());
  // A uniform direction: |x| = magnitude, each component mean 0 and variance m²/3.
  for (int k = 0; k < 3; ++k) {
    const auto c = column(s, static_cast<size_t>(k));
    EXPECT_NEAR(mean(c), 0.0, kSigmas * std::sqrt(4.0 / 3 / n));
    EXPECT_NEAR(variance(c), 4.0 / 3, kSigmas * std::sqrt((16.0 / 5 - 16.0 / 9) / n));  // E x⁴ = m⁴/5
  }
  for (long i = 0; i < 100; ++i) {
    const auto d = s.draws(i);
    EXPECT_NEAR(std::hypot(d[0], d[1], d[2]), 2.0, 1e-15);
  }
  // A uniform rotation (Haar measure): each quaternion component squared has mean 1/4 (the unit
  // 3-sphere is symmetric), and the mean rotation matrix is 0: E[R_zz] = E[1 − 2(x² + y²)] = 0.
  std::vector<double> w2, Rzz;
  for (long i = 0; i < s.runs(); ++i) {
    const auto d = s.draws(i);
    const double w = d[3], x = d[4], y = d[5], z = d[6];
    EXPECT_NEAR(w * w + x * x + y * y + z * z, 1.0, 1e-15);
    w2.push_back(w * w);
    Rzz.push_back(1 - 2 * (x * x + y * y));
  }
  EXPECT_NEAR(mean(w2), 0.25, kSigmas * std::sqrt(variance(w2) / n));
  EXPECT_NEAR(mean(Rzz), 0.0, kSigmas * std::sqrt(1.0 / 3 / n));  // R_zz uniform on [−1, 1]
}

TEST(Ensemble, ListsCycleAndGridsCoverEveryPointOnce) {
  const EnsembleStudy s = study(R"([ensemble]
[[ensemble.vary]]
path = "bodies.racket.angular_velocity[1]"
distribution = "grid"
values = [8.0, 9.0, 10.0]
[[ensemble.vary]]
path = "bodies.racket.mass"
distribution = "grid"
values = [1.0, 2.0]
[[ensemble.vary]]
path = "simulation.timestep"
distribution = "list"
values = [1e-3, 2e-3]
)");
  ASSERT_EQ(s.runs(), 6) << "runs defaults to the grid's size";
  std::set<std::pair<double, double>> points;
  for (long i = 0; i < 6; ++i) {
    const auto d = s.draws(i);
    points.insert({d[0], d[1]});
    EXPECT_EQ(d[2], i % 2 == 0 ? 1e-3 : 2e-3);
  }
  EXPECT_EQ(points.size(), 6u);
}

TEST(Ensemble, TheTableIsTheSameForAnyNumberOfThreads) {
  const EnsembleStudy s = study(R"([ensemble]
runs = 24
seed = 3
[[ensemble.vary]]
path = "bodies.racket.angular_velocity[0]"
distribution = "uniform"
low = 0.01
high = 0.2
[ensemble.outputs]
extrema = ["w2", "w1"]
final = ["orientation"]
)");
  const std::vector<long> runs = every_run(s);
  const auto one = run_ensemble(s, runs, 1, {});
  const auto two = run_ensemble(s, runs, 2, {});
  ASSERT_EQ(one.size(), runs.size());
  ASSERT_EQ(two.size(), runs.size());
  for (size_t k = 0; k < runs.size(); ++k) {
    EXPECT_EQ(one[k].run, static_cast<long>(k));
    ASSERT_EQ(one[k].values.size(), s.columns().size() - 1);
    for (size_t c = 0; c < one[k].values.size(); ++c) {
      const double a = one[k].values[c], b = two[k].values[c];
      EXPECT_TRUE(a == b || (std::isnan(a) && std::isnan(b))) << s.columns()[c + 1] << " run " << k;
    }
  }
}

/// Every value of the rows of run_batch equals that of each run simulated alone (run_alone), bit for bit
/// (NaN where NaN).
void expect_batch_equals_runs_alone(const EnsembleStudy& s) {
  const std::vector<long> runs = every_run(s);
  const std::vector<EnsembleRow> batch = run_batch(s, runs);
  ASSERT_EQ(batch.size(), runs.size());
  for (size_t k = 0; k < runs.size(); ++k) {
    const EnsembleRow alone = run_alone(s, runs[k]);
    ASSERT_EQ(batch[k].run, runs[k]);
    ASSERT_EQ(batch[k].values.size(), alone.values.size());
    for (size_t c = 0; c < alone.values.size(); ++c) {
      const double a = alone.values[c], b = batch[k].values[c];
      EXPECT_TRUE(std::bit_cast<std::uint64_t>(a) == std::bit_cast<std::uint64_t>(b) ||
                  (std::isnan(a) && std::isnan(b)))
          << s.columns()[c + 1] << " of run " << runs[k] << ": alone " << a << ", in the batch " << b;
    }
  }
}

// The runs of a study stepped as lanes of one system give the rows of each run stepped alone, bit for
// bit: the engine steps a body alike in any company, each lane locates its crossings by stepping its
// own model, and the rows are reduced by the same code. Per integrator, with draws of the initial state,
// the mass, the attitude and an event's value, and forces shared (gravity) or copied per run (a torque
// and a force on the body, damping of the body).
TEST(Ensemble, RunsSteppedAsOneBatchGiveTheRowsOfEachRunAloneBitForBit) {
  for (const char* integrator : {"rk4", "splitting", "lie_rk4", "midpoint", "implicit_gyro", "exact"}) {
    SCOPED_TRACE(integrator);
    const bool free = std::string(integrator) == "exact";  // exact refuses torques and damping
    const std::string forces = free ? ""
                                    : "[[forces]]\ntype = \"torque\"\nbody = \"racket\"\ntorque = [0.0, 0.0, "
                                      "1e-3]\nframe = \"reference\"\n"
                                      "[[forces]]\ntype = \"force\"\nbody = \"racket\"\nforce = [0.1, 0.0, "
                                      "0.0]\npoint = [0.0, 0.05, 0.0]\n"
                                      "[[forces]]\ntype = \"damping\"\nbody = \"racket\"\nangular = 1e-4\n";
    std::string scene = test::racket_scene(2.0) + forces;
    scene.insert(scene.find("timestep"), fmt::format("integrator = \"{}\"\n", integrator));
    scene.insert(scene.find("[[bodies]]"), "[world]\ngravity = [0.0, 0.0, -9.81]\n");
    const EnsembleStudy s = EnsembleStudy::parse(scene + R"([[events]]
name = "tilt"
body = "racket"
axis = [0.0, 0.0, 1.0]
toward = [0.0, 0.0, 1.0]
angle_deg = 20.0
[ensemble]
runs = 37
seed = 5
[[ensemble.vary]]
path = "bodies.racket.angular_velocity"
distribution = "direction"
magnitude = 10.0
[[ensemble.vary]]
path = "bodies.racket.mass"
distribution = "uniform"
low = 0.5
high = 2.0
[[ensemble.vary]]
path = "bodies.racket.orientation"
distribution = "rotation"
[[ensemble.vary]]
path = "events.tilt.angle_deg"
distribution = "uniform"
low = 5.0
high = 90.0
[ensemble.outputs]
extrema = ["w1", "w2", "com_z"]
final = ["orientation", "angular_velocity"]
)",
                                                 "study.toml");
    expect_batch_equals_runs_alone(s);
  }
}

// A run that stops at its event ends its lane there, while the others go on: its final values are
// those at the crossing, as when it runs alone.
TEST(Ensemble, ALaneThatStopsAtItsEventEndsThereAndTheOthersGoOn) {
  std::string scene = test::racket_scene(8.0);
  scene.insert(scene.find("[[bodies]]"), "[world]\ngravity = [0.0, 0.0, -9.81]\n");
  scene.insert(scene.find("angular_velocity ="), "velocity = [0.0, 0.0, 0.0]\n");
  const EnsembleStudy s = EnsembleStudy::parse(scene + R"([[events]]
name = "fallen"
body = "racket"
column = "com_z"
value = -1.0
stop = true
[ensemble]
runs = 20
[[ensemble.vary]]
path = "bodies.racket.velocity[2]"
distribution = "uniform"
low = -2.0
high = 8.0
[ensemble.outputs]
final = ["com_position"]
)",
                                               "study.toml");
  expect_batch_equals_runs_alone(s);
  // Each run stops where its centre of mass reaches z = −1 m, at t = (v + √(v² + 2g)) / g.
  const auto& c = s.columns();
  const auto at = [&](const std::string& name) {
    const auto k = std::find(c.begin(), c.end(), name);
    EXPECT_NE(k, c.end()) << name;
    return static_cast<size_t>(k - c.begin()) - 1;
  };
  int stopped = 0;
  for (const EnsembleRow& r : run_batch(s, every_run(s))) {
    const double v = r.values[0], t = (v + std::sqrt(v * v + 2 * 9.81)) / 9.81;
    if (t > 8.0) continue;  // still falling at the end
    // RK4 integrates the parabola exactly; the crossing is located to 4 ulp of t.
    EXPECT_NEAR(r.values[at("racket.com_z_final")], -1.0, 1e-12) << "run " << r.run;
    EXPECT_NEAR(r.values[at("fallen.first_t")], t, 1e-12) << "run " << r.run;
    ++stopped;
  }
  EXPECT_GT(stopped, 10);
}

// Draws that change the structure (here the step) put the runs into groups that share it: each group
// is one batch, and the rows are still those of each run alone; a spring between a body and the world
// (a system model) keeps every run on its own.
TEST(Ensemble, RunsAreBatchedByStructureAndSystemModelsRunAlone) {
  expect_batch_equals_runs_alone(study(R"([ensemble]
runs = 30
[[ensemble.vary]]
path = "simulation.timestep"
distribution = "grid"
values = [1e-3, 2e-3, 4e-3]
[[ensemble.vary]]
path = "bodies.racket.angular_velocity[0]"
distribution = "uniform"
low = 0.01
high = 0.2
)"));
  expect_batch_equals_runs_alone(study(R"([[forces]]
type = "spring"
a = { body = "racket", point = [0.0, 0.0, 0.15] }
b = { anchor = [0.0, 0.0, 1.0] }
stiffness = 10.0
[ensemble]
runs = 6
[[ensemble.vary]]
path = "bodies.racket.angular_velocity[0]"
distribution = "uniform"
low = 0.01
high = 0.2
)"));
}

// A run that blows up inside a batch is named with its draws' run number.
TEST(Ensemble, ARunThatBlowsUpInABatchIsNamed) {
  const EnsembleStudy s = study(R"([[forces]]
type = "drag"
body = "racket"
angular = 1e-3
[ensemble]
runs = 16
[[ensemble.vary]]
path = "bodies.racket.angular_velocity[1]"
distribution = "list"
values = [1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1e6, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0]
)");
  try {
    (void)run_batch(s, every_run(s));
    FAIL() << "the blow-up went unnoticed";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("body 'racket' of run 7 became non-finite"), std::string::npos)
        << e.what();
  }
}

// Each run's mean interval between flips against 2K(m)/λ computed from its own drawn ω (Euler–Poinsot).
// RK4 at ω h = 0.01 rad: the interval carries its phase error, ~1e-9 s over 8 s (measured 1e-10 for
// the T-handle in examples_test at twice the step); 1e-7 s leaves room.
TEST(Ensemble, EachRunsFlipIntervalIsTheExactOne) {
  const EnsembleStudy s = study(R"([ensemble]
runs = 40
seed = 11
[[ensemble.vary]]
path = "bodies.racket.angular_velocity[0]"
distribution = "lognormal"
mu = -3.0
sigma = 0.5
[[ensemble.vary]]
path = "bodies.racket.angular_velocity[1]"
distribution = "normal"
mean = 10.0
std = 0.3
)");
  const auto rows = run_ensemble(s, every_run(s), 2, {});
  const auto& c = s.columns();
  const auto at = [&](const std::string& name) {
    return static_cast<size_t>(std::find(c.begin(), c.end(), name) - c.begin()) - 1;
  };
  const Vec3 Lambda = s.base().model.bodies[0].Lambda();
  int checked = 0;
  for (const EnsembleRow& r : rows) {
    const Vec3 w(r.values[0], r.values[1], 0.0);
    const double T = test::intermediate_axis_flip_interval(Lambda, w);
    if (r.values[at("flip.count")] < 2) continue;
    EXPECT_NEAR(r.values[at("flip.mean_interval")], T, 1e-7) << "run " << r.run;
    EXPECT_NEAR(r.values[at("flip.first_t")], T / 2, 1e-7)
        << "ω₂ starts at its extreme: the first flip at T/2";
    ++checked;
  }
  EXPECT_GT(checked, 30) << "most runs flip twice in 8 s";
  // A free body conserves energy and angular momentum: RK4's drift over 8 s at ω h = 0.01 is ~1e-12.
  const auto stats = summarize(c, rows);
  for (const ColumnSummary& st : stats) {
    if (st.column == "energy_drift_max") {
      EXPECT_LT(st.max, 1e-9);
    }
    if (st.column == "flip.first_t") {
      EXPECT_EQ(st.count, 40);
      EXPECT_LE(st.q05, st.q50);
      EXPECT_LE(st.q50, st.q95);
      long total = 0;
      for (long h : st.histogram) total += h;
      EXPECT_EQ(total, 40);
    }
  }
}

TEST(Ensemble, MistakesAreNamed) {
  const auto error = [](const std::string& ensemble) {
    try {
      (void)study(ensemble);
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(error("[ensemble]\nruns = 3\n[[ensemble.vary]]\npath = \"bodies.rocket.mass\"\ndistribution = "
                  "\"uniform\"\nlow = 1\nhigh = 2\n")
                .find("no element of bodies is named \"rocket\""),
            std::string::npos);
  EXPECT_NE(error(
                "[ensemble]\nruns = 3\n[[ensemble.vary]]\npath = \"bodies.racket.velocity[0]\"\ndistribution "
                "= \"uniform\"\nlow = 1\nhigh = 2\n")
                .find("bodies.racket.velocity is not in the scene: write it in the file"),
            std::string::npos);
  EXPECT_NE(
      error("[ensemble]\nruns = 3\n[[ensemble.vary]]\npath = \"bodies.racket.angular_velocity[3]\"\n"
            "distribution = \"uniform\"\nlow = 1\nhigh = 2\n")
          .find("angular_velocity[3] is not in the scene (bodies.racket.angular_velocity has 3 elements)"),
      std::string::npos);
  EXPECT_NE(error("[ensemble]\nruns = 3\n[[ensemble.vary]]\npath = \"bodies.racket.mass\"\ndistribution = "
                  "\"gaussian\"\n")
                .find("unknown distribution \"gaussian\""),
            std::string::npos);
  EXPECT_NE(error("[ensemble]\nruns = 3\n[[ensemble.vary]]\npath = \"bodies.racket.mass\"\ndistribution = "
                  "\"rotation\"\n")
                .find("a rotation distribution sets 4 numbers"),
            std::string::npos);
  EXPECT_NE(error("[ensemble]\n[[ensemble.vary]]\npath = \"bodies.racket.mass\"\ndistribution = \"normal\"\n"
                  "mean = 1\nstd = 1\n")
                .find("missing 'runs'"),
            std::string::npos);
  // A draw that makes the scene invalid: the run and its values are named.
  const EnsembleStudy s = study(R"([ensemble]
runs = 50
[[ensemble.vary]]
path = "bodies.racket.mass"
distribution = "normal"
mean = 0.0
std = 1.0
)");
  long negative = 0;
  while (s.draws(negative)[0] > 0) ++negative;
  try {
    (void)s.scene_of_run(negative);
    FAIL() << "a negative mass was accepted";
  } catch (const SceneError& e) {
    EXPECT_NE(std::string(e.what()).find(fmt::format("run {} (bodies.racket.mass = -", negative)),
              std::string::npos)
        << e.what();
    EXPECT_NE(std::string(e.what()).find("it must be positive"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace tumble
