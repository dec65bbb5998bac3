// Studies run into rows (study/runs.hpp): the runs of a batch stepped together give the rows of each
// run alone, bit for bit; tables do not depend on threads; each run's physics against the closed form.
#include <gtest/gtest.h>

#include <fmt/format.h>

#include <bit>
#include <cmath>

#include "../support/closed_forms.hpp"
#include "../support/racket_study.hpp"
#include "../support/scene_files.hpp"
#include "tumble/study/runs.hpp"

namespace tumble {
namespace {

EnsembleStudy study(const std::string& ensemble) { return test::racket_study(ensemble); }

TEST(StudyRuns, TheTableIsTheSameForAnyNumberOfThreads) {
  const EnsembleStudy s = study(R"([ensemble]
runs = 24
seed = 3)" + test::vary("bodies.racket.angular_velocity[0]", "uniform", "low = 0.01\nhigh = 0.2") +
                                R"([ensemble.outputs]
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
/// Where column `name` of the table is in a row's values (they start after "run"); fails the test for a
/// name the table lacks.
size_t value_index(const EnsembleStudy& s, const std::string& name) {
  const auto& c = s.columns();
  const auto k = std::find(c.begin(), c.end(), name);
  EXPECT_NE(k, c.end()) << name;
  return static_cast<size_t>(k - c.begin()) - 1;
}

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
TEST(StudyRuns, RunsSteppedAsOneBatchGiveTheRowsOfEachRunAloneBitForBit) {
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
    const EnsembleStudy s = EnsembleStudy::parse(
        scene + R"([[events]]
name = "tilt"
body = "racket"
axis = [0.0, 0.0, 1.0]
toward = [0.0, 0.0, 1.0]
angle_deg = 20.0
[ensemble]
runs = 37
seed = 5)" + test::vary("bodies.racket.angular_velocity", "direction", "magnitude = 10.0") +
            test::vary("bodies.racket.mass", "uniform", "low = 0.5\nhigh = 2.0") +
            test::vary("bodies.racket.orientation", "rotation") +
            test::vary("events.tilt.angle_deg", "uniform", "low = 5.0\nhigh = 90.0") + R"([ensemble.outputs]
extrema = ["w1", "w2", "com_z"]
final = ["orientation", "angular_velocity"]
)",
        "study.toml");
    expect_batch_equals_runs_alone(s);
  }
}

// Free bodies (no force model): each run's drifts are reduced a pack of runs at a time, its extrema of
// variables (w1 in the mixed formulation, com_z) a pack at a time and the others (wx, and w1 in the
// world formulation) run by run; runs of two bodies are gathered from rows two apart, and a run that
// stops takes its last sample alone. The rows are those of each run alone, bit for bit, in every
// formulation; and a free run's drifts are RK4's: its error grows like t ω (ω h)⁴ / 120 ≈ 2e-9 over
// t = 2 s at ω = 10 rad/s, h = 1e-3 (measured: 1.7e-10), and is never exactly zero.
TEST(StudyRuns, FreeRunsAreReducedAPackOfRunsAtATimeWithTheBitsOfEachRunAlone) {
  for (const char* formulation : {"world", "mixed", "body"}) {
    SCOPED_TRACE(formulation);
    std::string scene = test::racket_scene(2.0);
    scene.insert(scene.find("timestep"), fmt::format("formulation = \"{}\"\n", formulation));
    scene.insert(scene.find("[[events]]"),
                 "[[bodies]]\nname = \"plate\"\nshape = { type = \"box\", size = [0.3, 0.2, 0.01] }\n"
                 "mass = 0.5\nposition = [1.0, 0.0, 0.0]\nvelocity = [0.0, 0.0, 0.3]\n"
                 "angular_velocity = [3.0, 0.1, 0.2]\n");
    const EnsembleStudy s =
        EnsembleStudy::parse(scene + R"([[events]]
name = "high"
body = "plate"
column = "com_z"
value = 0.4
stop = true
[ensemble]
runs = 21
seed = 9)" + test::vary("bodies.racket.angular_velocity", "direction", "magnitude = 10.0") +
                                 test::vary("bodies.plate.velocity[2]", "uniform", "low = 0.0\nhigh = 0.5") +
                                 R"([ensemble.outputs]
extrema = ["w1", "com_z", "wx"]
)",
                             "study.toml");
    expect_batch_equals_runs_alone(s);
    const auto at = [&](const std::string& name) { return value_index(s, name); };
    int stopped = 0;
    for (const EnsembleRow& r : run_batch(s, every_run(s))) {
      for (const char* drift : {"energy_drift_max", "angular_momentum_drift_max"}) {
        EXPECT_GT(r.values[at(drift)], 0.0) << drift << " of run " << r.run;
        EXPECT_LT(r.values[at(drift)], 2e-9) << drift << " of run " << r.run;
      }
      // The plate rises at its drawn speed (no gravity): it stops at z = 0.4 m if it gets there.
      const double v = r.values[at("bodies.plate.velocity[2]")];
      if (2.0 * v > 0.4) {
        ++stopped;
        EXPECT_NEAR(r.values[at("plate.com_z_max")], 0.4, 1e-12) << r.run;
      }
    }
    EXPECT_GT(stopped, 3);
  }
}

// A run that stops at its event ends its lane there, while the others go on: its final values are
// those at the crossing, as when it runs alone.
TEST(StudyRuns, ALaneThatStopsAtItsEventEndsThereAndTheOthersGoOn) {
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
runs = 20)" + test::vary("bodies.racket.velocity[2]", "uniform", "low = -2.0\nhigh = 8.0") +
                                                   R"([ensemble.outputs]
final = ["com_position"]
)",
                                               "study.toml");
  expect_batch_equals_runs_alone(s);
  // Each run stops where its centre of mass reaches z = −1 m, at t = (v + √(v² + 2g)) / g.
  const auto at = [&](const std::string& name) { return value_index(s, name); };
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
TEST(StudyRuns, RunsAreBatchedByStructureAndSystemModelsRunAlone) {
  expect_batch_equals_runs_alone(study(R"([ensemble]
runs = 30)" + test::vary("simulation.timestep", "grid", "values = [1e-3, 2e-3, 4e-3]") +
                                       test::vary("bodies.racket.angular_velocity[0]", "uniform",
                                                  "low = 0.01\nhigh = 0.2")));
  expect_batch_equals_runs_alone(study(R"([[forces]]
type = "spring"
a = { body = "racket", point = [0.0, 0.0, 0.15] }
b = { anchor = [0.0, 0.0, 1.0] }
stiffness = 10.0
[ensemble]
runs = 6)" + test::vary("bodies.racket.angular_velocity[0]", "uniform", "low = 0.01\nhigh = 0.2")));
}

// A run that blows up inside a batch is named with its draws' run number.
TEST(StudyRuns, ARunThatBlowsUpInABatchIsNamed) {
  const EnsembleStudy s = study(R"([[forces]]
type = "drag"
body = "racket"
angular = 1e-3
[ensemble]
runs = 16)" + test::vary("bodies.racket.angular_velocity[1]", "list",
                         "values = [1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1e6, 1.0, 1.0, 1.0, "
                         "1.0, 1.0, 1.0, 1.0, 1.0]"));
  try {
    (void)run_batch(s, every_run(s));
    FAIL() << "the blow-up went unnoticed";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(
                  "body 'racket' of run 7 (bodies.racket.angular_velocity[1] = 1000000) became non-finite"),
              std::string::npos)
        << e.what();
  }
  try {
    (void)run_alone(s, 7);
    FAIL() << "the blow-up of run 7 alone went unnoticed";
  } catch (const Error& e) {
    EXPECT_EQ(
        std::string(e.what()).rfind("run 7 (bodies.racket.angular_velocity[1] = 1000000): the state of body "
                                    "'racket' became non-finite",
                                    0),
        0u)
        << e.what();
  }
}

// When several runs fail, the study reports the first of them, whatever thread meets a failure first:
// here every run's draw is invalid, and two threads take batches of 4 runs side by side.
TEST(StudyRuns, OfSeveralFailingRunsTheFirstIsReportedOnAnyThread) {
  const EnsembleStudy s =
      study("[ensemble]\nruns = 64" + test::vary("bodies.racket.mass", "uniform", "low = -2.0\nhigh = -1.0"));
  for (int attempt = 0; attempt < 20; ++attempt) {
    try {
      (void)run_ensemble(s, every_run(s), 2, {});
      FAIL() << "the invalid masses went unnoticed";
    } catch (const Error& e) {
      ASSERT_EQ(std::string(e.what()).rfind("run 0 (", 0), 0u) << e.what();
    }
  }
}

// Each run's mean interval between flips against 2K(m)/λ computed from its own drawn ω (Euler–Poinsot).
// RK4 at ω h = 0.01 rad: the interval carries its phase error, ~1e-9 s over 8 s (measured 1e-10 for
// the T-handle in examples_test at twice the step); 1e-7 s leaves room.
TEST(StudyRuns, EachRunsFlipIntervalIsTheExactOne) {
  const EnsembleStudy s = study(R"([ensemble]
runs = 40
seed = 11)" + test::vary("bodies.racket.angular_velocity[0]", "lognormal", "mu = -3.0\nsigma = 0.5") +
                                test::vary("bodies.racket.angular_velocity[1]", "normal",
                                           "mean = 10.0\nstd = 0.3"));
  const auto rows = run_ensemble(s, every_run(s), 2, {});
  const auto at = [&](const std::string& name) { return value_index(s, name); };
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
  const auto stats = summarize(s.columns(), rows);
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

}  // namespace
}  // namespace tumble
