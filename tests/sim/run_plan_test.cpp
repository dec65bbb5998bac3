// The plan of a run (sim/run_plan.hpp): its counts are the ones the run then makes, and runs that no
// clock could finish are refused before they start.
#include <gtest/gtest.h>

#include "../support/sim_helpers.hpp"
#include "tumble/dynamics/rigid_body.hpp"
#include "tumble/error.hpp"
#include "tumble/sim/run_plan.hpp"

namespace tumble {
namespace {

/// The samples and steps a run makes.
std::pair<double, double> samples_and_steps(const Model& model, const SystemState& initial,
                                            const RunSettings& s) {
  double n = 0;
  IntegratorStats stats;
  simulate(
      model, initial, s, [&](const SystemState&) { return ++n, true; }, &stats);
  return {n, static_cast<double>(stats.steps)};
}

/// The default output fields' widths: position, orientation, velocity, angular velocity (13 columns).
constexpr int kWidths[] = {3, 4, 3, 3};

TEST(RunPlan, CountsAreTheRunsOwn) {
  Model model;
  model.add_body(RigidBody::from_principal_moments(2.0, Vec3(1, 2, 3)));
  const SystemState initial = test::single(BodyState{});
  RunSettings s;
  s.duration = 1.0;
  s.timestep = 1e-3;
  // Δ a multiple of h or not, longer or shorter than h, or longer than the run; T = 1 s or 1.25 s.
  for (const double duration : {1.0, 1.25}) {
    for (const double interval : {0.0, 0.01, 0.0015, 0.0004, 0.3, 2.0}) {
      s.duration = duration;
      s.output_interval = interval;
      const RunPlan p = plan_run(s, 1, 0, kWidths);
      SCOPED_TRACE(testing::Message() << "T = " << duration << ", interval " << interval);
      const auto [samples, steps] = samples_and_steps(model, initial, s);
      EXPECT_EQ(p.samples, samples);
      EXPECT_EQ(p.steps, steps);
      EXPECT_EQ(p.rows, p.samples);
    }
  }
  s.duration = 1.0;
  s.output_interval = 0.0015;  // 666 intervals of 2 steps (h, then 0.5 h), and a last step of h
  EXPECT_EQ(plan_run(s, 1, 0, kWidths).steps, 666.0 * 2 + 1);
  s.integrator = "dopri45";
  EXPECT_FALSE(plan_run(s, 1, 0, kWidths).steps.has_value());
  // Bytes: 8 a value in HDF5, for each of 3 rows (2 bodies and a particle) and 13 columns, plus the
  // diagnostics; CSV is bounded by 25 characters a value and 30 for t and the name.
  s.output_interval = 0.5;  // samples at 0, 0.5, 1
  const RunPlan p = plan_run(s, 2, 1, kWidths);
  EXPECT_EQ(p.rows, 9.0);
  EXPECT_GT(p.hdf5_bytes, 9.0 * 13 * 8);
  EXPECT_GT(p.csv_bytes, 9.0 * (30 + 13 * 25));
}

TEST(RunPlan, RunsNoClockCouldFinishAreRefused) {
  RunSettings s;
  s.timestep = 5e-324;
  s.duration = 20;
  EXPECT_THROW(validate(s), InvalidArgument);
  s.timestep = 1e-3;
  s.duration = 1e300;
  try {
    validate(s);
    ADD_FAILURE() << "a run of 1e303 steps was accepted";
  } catch (const InvalidArgument& e) {
    EXPECT_EQ(
        std::string(e.what()),
        "timestep 0.001 s is too small for duration 1e+300 s: 1e+303 steps, more than 2^53, where a step no "
        "longer advances the clock; give a larger timestep or a shorter duration");
  }
  s.duration = 20;
  s.output_interval = 1e-300;
  EXPECT_THROW(validate(s), InvalidArgument);
  // 2⁵³ steps exactly is still countable.
  s.output_interval = 0;
  s.timestep = 1.0;
  s.duration = kMaxCount;
  EXPECT_NO_THROW(validate(s));
}

}  // namespace
}  // namespace tumble
