// The time loop (sim/simulate.hpp): between samples it hands full steps to Integrator::steps in
// chunks; the samples must be exactly those of stepping one step at a time, and a blow-up inside a
// chunk is still reported with the body and the interval of time.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

#include "../support/allocation_counter.hpp"
#include "../support/random.hpp"
#include "tumble/error.hpp"
#include "tumble/forces/forces.hpp"
#include "tumble/integrate/euler_poinsot.hpp"
#include "tumble/sim/event_specs.hpp"
#include "tumble/sim/run.hpp"
#include "tumble/sim/simulate.hpp"

namespace tumble {
namespace {

bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

bool same_state(const SystemState& a, const SystemState& b) {
  if (!same_bits(a.t, b.t) || a.bodies.size() != b.bodies.size()) return false;
  for (size_t i = 0; i < a.bodies.size(); ++i) {
    const BodyState &x = a.bodies[i], &y = b.bodies[i];
    for (int k = 0; k < 3; ++k) {
      if (!same_bits(x.o[k], y.o[k]) || !same_bits(x.v[k], y.v[k]) || !same_bits(x.omega_w[k], y.omega_w[k]))
        return false;
    }
    for (int k = 0; k < 4; ++k) {
      if (!same_bits(x.q.coeffs()[k], y.q.coeffs()[k])) return false;
    }
  }
  return true;
}

TEST(Simulate, SamplesEqualThoseOfSteppingOneStepAtATimeBitForBit) {
  // 70 bodies under gravity (fused steps: simulate hands chunks of steps over), sampled every 37 steps
  // of a step that is not a binary fraction, so sample times and accumulated times both round. The
  // reference steps one at a time, the last step before a sample being what remains of the interval,
  // and the clock kept on the grid t_last_sample + n h (as simulate documents).
  test::Random rng(41);
  Model model;
  SystemState s0;
  s0.t = 0.25;
  for (int i = 0; i < 70; ++i) {
    std::string name = "b";
    name += std::to_string(i);  // (not "b" + …: GCC 12 warns falsely, -Wrestrict)
    model.add_body(RigidBody::from_mass_properties(rng.body(), name));
    s0.bodies.push_back(BodyState{rng.vec(-1, 1), Quat(rng.rotation()), rng.vec(-1, 1), rng.vec(-5, 5)});
  }
  model.add_force<UniformGravity>(Vec3(0, 0, -9.81));
  RunSettings settings;
  settings.timestep = 1.3e-3;
  settings.output_interval = 37 * 1.3e-3;
  settings.duration = 0.5;
  for (const char* name : {"rk4", "lie_rk4", "semi_implicit_euler"}) {
    settings.integrator = name;
    std::vector<SystemState> samples;
    const SystemState end = simulate(model, s0, settings, [&](const SystemState& s) {
      samples.push_back(s);
      return true;
    });
    // The state the run ends in is its last sample, handed back without converting it again.
    EXPECT_TRUE(same_state(end, samples.back())) << name;

    std::vector<SystemState> expected{s0};
    SystemCoordinates x = to_coordinates(settings.formulation, s0);
    auto integrator = make_integrator(name);
    const double h = settings.timestep, t_end = s0.t + settings.duration, tiny = 1e-9 * h;
    long k_out = 1, n = 0;
    double t_last = s0.t;
    while (x.t < t_end - tiny) {
      const double t_sample = std::min(s0.t + static_cast<double>(k_out) * settings.output_interval, t_end);
      const double remaining = t_sample - x.t;
      integrator->step(model, settings.formulation, x, remaining <= h + tiny ? remaining : h);
      ++n;
      x.t = t_last + static_cast<double>(n) * h;  // the clock on its grid, as simulate keeps it
      if (x.t >= t_sample - tiny) {
        x.t = t_last = t_sample;
        n = 0;
        ++k_out;
        expected.push_back(to_state(settings.formulation, x));
      }
    }
    ASSERT_EQ(samples.size(), expected.size()) << name;
    for (size_t k = 0; k < samples.size(); ++k)
      EXPECT_TRUE(same_state(samples[k], expected[k])) << name << ", sample " << k;
  }
  // A run of no duration ends in its start as the variables hold it (the quaternion normalised).
  settings.duration = 0;
  const SystemState end = simulate(model, s0, settings);
  EXPECT_TRUE(same_state(end, to_state(settings.formulation, to_coordinates(settings.formulation, s0))));
}

TEST(Simulate, GivenSampleTimesAreSampledWhereGiven) {
  // A free body (torque-free: Jacobi's closed form, EulerPoinsot, is the reference), started at t0 ≠ 0.
  const Vec3 Lambda(1.0, 2.0, 3.0), w0(0.3, 2.0, 0.1);
  Model model;
  model.add_body(RigidBody::from_principal_moments(1.0, Lambda, "b"));
  SystemState s0;
  s0.t = 0.25;
  s0.bodies.push_back(BodyState{Vec3::Zero(), Quat::Identity(), Vec3(1, 0, 0), w0});
  const EulerPoinsot exact(Lambda, Quat::Identity(), w0);
  RunSettings settings;
  settings.timestep = 1e-3;
  settings.integrator = "rk4";

  // Times on the output grid: the same samples as the grid's, bit for bit (steps fused between them).
  settings.output_interval = 0.05;
  settings.duration = 0.5;
  std::vector<SystemState> on_grid, given;
  simulate(model, s0, settings, [&](const SystemState& s) { return on_grid.push_back(s), true; });
  for (long k = 1; k <= 10; ++k) settings.sample_times.push_back(std::min(s0.t + k * 0.05, s0.t + 0.5));
  simulate(model, s0, settings, [&](const SystemState& s) { return given.push_back(s), true; });
  ASSERT_EQ(given.size(), on_grid.size());
  for (size_t k = 0; k < given.size(); ++k) EXPECT_TRUE(same_state(given[k], on_grid[k])) << "sample " << k;

  // Times off any grid, some closer than a step: sampled at exactly those times, on the closed form.
  // RK4's global error, O((|ω| h)⁴) per unit time, and dopri45's (rtol 1e-9 a step, its dense output
  // between steps) stay below 1e-10 and 1e-7 here, with room; a sample a step (1e-3 s) off its time
  // would be off by |dω/dt| 1e-3 ~ 1e-3.
  test::Random rng(7);
  settings.sample_times.clear();
  double t = s0.t;
  for (int k = 0; k < 40; ++k) settings.sample_times.push_back(t += rng.uniform(1e-5, 0.05));
  settings.duration = settings.sample_times.back() - s0.t;
  for (const char* integrator : {"rk4", "dopri45"}) {
    settings.integrator = integrator;
    given.clear();
    simulate(model, s0, settings, [&](const SystemState& s) { return given.push_back(s), true; });
    ASSERT_EQ(given.size(), settings.sample_times.size() + 1) << integrator;
    for (size_t k = 1; k < given.size(); ++k) {
      const double tk = settings.sample_times[k - 1];
      EXPECT_TRUE(same_bits(given[k].t, tk)) << integrator << ", sample " << k;
      const double tol = std::string(integrator) == "rk4" ? 1e-10 : 1e-7;
      EXPECT_LT((given[k].bodies[0].omega_w - exact.omega_w(tk - s0.t)).norm(), tol)
          << integrator << " at " << tk;
      EXPECT_LT((given[k].bodies[0].o - Vec3(tk - s0.t, 0, 0)).norm(), tol) << integrator << " at " << tk;
    }
  }

  // Times that cannot be sampled are refused, saying which and why.
  const auto refused = [&](std::vector<double> times, double duration, const std::string& says) {
    settings.sample_times = std::move(times);
    settings.duration = duration;
    try {
      simulate(model, s0, settings);
      ADD_FAILURE() << "accepted: " << says;
    } catch (const InvalidArgument& e) {
      EXPECT_NE(std::string(e.what()).find(says), std::string::npos) << e.what();
    }
  };
  settings.integrator = "rk4";
  refused({0.25, 0.5}, 0.25, "sample time #0 (0.25 s) is not after the start (0.25 s)");
  refused({0.5, 0.4, 0.6}, 0.35, "sample time #1 (0.4 s) is not after sample time #0 (0.5 s)");
  refused({0.5, std::numeric_limits<double>::quiet_NaN()}, 0.25, "sample time #1 is nan");
  refused({0.5, 0.75}, 1.0, "the last sample time (0.75 s) is not where the run ends");
}

TEST(Simulate, ABlowUpInsideAChunkNamesTheBodyAndTheInterval) {
  // Explicit Euler gains energy on a free rotor by a factor ~1 + (hω)² per step: at hω = 50 the state
  // overflows within ~60 steps, inside a chunk of steps between samples 1 s apart.
  Model model;
  model.add_body(RigidBody::from_principal_moments(1.0, Vec3(1.0, 2.0, 3.0), "spinner"));
  model.add_force<UniformGravity>(Vec3(0, 0, -9.81));
  SystemState s0;
  s0.bodies.push_back(BodyState{Vec3::Zero(), Quat::Identity(), Vec3::Zero(), Vec3(300.0, 300.0, 300.0)});
  RunSettings settings;
  settings.integrator = "euler";
  settings.timestep = 0.1;
  settings.output_interval = 1.0;
  settings.duration = 100.0;
  try {
    simulate(model, s0, settings);
    FAIL() << "a non-finite state was not reported";
  } catch (const Error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("the state of body 'spinner' became non-finite between t = "), std::string::npos)
        << what;
    EXPECT_NE(what.find("integrator euler"), std::string::npos) << what;
  }
}

}  // namespace
}  // namespace tumble

namespace tumble {
namespace {

/// Heap allocations of a batch of 16 lanes (each its own model and an event watched every step) run by
/// a Run with an observer, for `duration`.
long allocations_of_a_batch(double duration, std::vector<double>& largest_w2) {
  constexpr size_t kRuns = 16;
  std::vector<Model> models(kRuns);
  Model batch;
  SystemState initial;
  for (size_t r = 0; r < kRuns; ++r) {
    models[r].add_body(
        RigidBody::from_principal_moments(1.0 + 0.1 * static_cast<double>(r), Vec3(1, 2, 2.5), "b"));
    models[r].add_force<UniformGravity>(Vec3(0, 0, -9.81));
    batch.bodies.push_back(models[r].bodies[0]);
    initial.bodies.push_back(
        {Vec3(0, 0, 100), Quat::Identity(), Vec3::Zero(), Vec3(0.1, 5.0 + 0.1 * static_cast<double>(r), 0)});
  }
  batch.add_force<UniformGravity>(Vec3(0, 0, -9.81));
  std::vector<Lane> lanes(kRuns);
  largest_w2.assign(kRuns, 0.0);
  for (size_t r = 0; r < kRuns; ++r) {
    lanes[r].model = &models[r];
    lanes[r].label = [] { return std::string("run"); };
    EventSpec below;  // the centre of mass below z = -1 km: watched at every step, never crossed
    below.name = "deep";
    below.field = find_column("com_z")->first;
    below.component = 2;
    below.value = -1000.0;
    lanes[r].events.push_back(make_event(models[r], below));
    lanes[r].on_variables = [&largest_w2, r](const SystemCoordinates& x, size_t first) {
      largest_w2[r] = std::max(largest_w2[r], x.bodies[BodyColumns::omega + 1][first]);
      return true;
    };
  }
  struct Energy final : RunObserver {
    double largest = 0;
    void on_sample(const SystemState&, const DriftSample& d) override {
      largest = std::max(largest, std::abs(d.energy_drift.value_or(0.0)));
    }
  } energy;
  RunSettings s;
  s.duration = duration;
  s.timestep = 1e-3;
  s.output_interval = 0.01;
  Run run(batch, initial, s, Conservation{});
  run.as_lanes(std::move(lanes)).attach(energy);
  const test::CountAllocations count;
  run.run();
  return count.count();
}

// Stepping allocates nothing, observers, lanes and events attached: a run twice as long makes the same
// allocations (those of setting it up), not more.
TEST(Simulate, StepsAllocateNothingWithLanesEventsAndObservers) {
  std::vector<double> w2_short, w2_long;
  (void)allocations_of_a_batch(0.1, w2_short);  // what is made once per process (registries, statics)
  const long short_run = allocations_of_a_batch(1.0, w2_short);
  const long long_run = allocations_of_a_batch(2.0, w2_long);
  EXPECT_EQ(long_run, short_run);
  for (double w : w2_long) EXPECT_GT(w, 4.9);  // the observer saw every lane's samples
}

}  // namespace
}  // namespace tumble
