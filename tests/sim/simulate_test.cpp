// The time loop (sim/simulate.hpp): between samples it hands full steps to Integrator::steps in
// chunks; the samples must be exactly those of stepping one step at a time, and a blow-up inside a
// chunk is still reported with the body and the interval of time.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>
#include <vector>

#include "../support/allocation_counter.hpp"
#include "../support/random.hpp"
#include "tumble/error.hpp"
#include "tumble/forces/forces.hpp"
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
