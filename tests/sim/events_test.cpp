// Events: the moment a condition crosses zero, located inside a step.
#include <gtest/gtest.h>

#include <cmath>

#include "../support/sim_helpers.hpp"
#include "tumble/error.hpp"
#include "tumble/forces/forces.hpp"
#include "tumble/integrate/euler_poinsot.hpp"
#include "tumble/sim/event_specs.hpp"

namespace tumble {
namespace {

// A ball thrown up from z₀ = 2 m at v₀ = 10 m/s: its apex is at t = v₀/g and it lands at
// t* = (v₀ + √(v₀² + 2g z₀))/g.
constexpr double g = 9.81, z0 = 2.0, v0 = 10.0;
Model thrown_ball() {
  Model model;
  model.add_body(RigidBody::from_principal_moments(1.0, Vec3(1, 2, 2.5), "ball"));
  model.add_force<UniformGravity>(Vec3(0, 0, -g));
  return model;
}
Event landing() {
  return {"landing", [](const SystemState& s) { return s.bodies[0].o.z(); }, -1, true};
}

TEST(Events, ABallStopsWhenItLandsAtTheClosedFormTime) {
  const Model model = thrown_ball();
  RunSettings rs;
  rs.duration = 10.0;
  rs.timestep = 0.01;
  rs.output_interval = 0.5;
  RunHooks hooks;
  hooks.events.push_back(landing());
  std::vector<EventHit> hits;
  hooks.on_event = [&](const EventHit& hit) { hits.push_back(hit); };
  double last_sample = -1;
  hooks.on_sample = [&](const SystemState& s) {
    last_sample = s.t;
    return true;
  };
  const SystemState end = simulate(
      model, test::single({Vec3(0, 0, z0), Quat::Identity(), Vec3(0, 0, v0), Vec3::Zero()}), rs, hooks);
  const double t_star = (v0 + std::sqrt(v0 * v0 + 2 * g * z0)) / g;
  ASSERT_EQ(hits.size(), 1u);
  EXPECT_EQ(hits[0].name, "landing");
  // RK4 integrates the parabola exactly; regula falsi resolves the time to 4 ulp of t ≈ 2.2 s.
  EXPECT_NEAR(hits[0].state.t, t_star, 1e-14 * 4);
  EXPECT_LE(hits[0].state.bodies[0].o.z(), 0.0);
  EXPECT_GT(hits[0].state.bodies[0].o.z(), -1e-13);
  EXPECT_EQ(end.t, hits[0].state.t);
  EXPECT_EQ(last_sample, end.t);  // the stopping state is the last sample
}

TEST(Events, TheTHandleFlipsAreRecordedAtTheEllipticInterval) {
  const Vec3 Lambda(1.2e-5, 3.1e-5, 4.0e-5), w0(2.0, 20.0, 2.0);
  Model model;
  model.add_body(RigidBody::from_principal_moments(0.1, Lambda, "t_handle"));
  RunSettings rs;
  rs.duration = 10.0;
  rs.timestep = 0.05;
  rs.integrator = "splitting";  // exact for a free body: only the event location's resolution remains
  RunHooks hooks;
  hooks.events.push_back({"flip", [](const SystemState& s) { return s.bodies[0].omega_b().y(); }, 0, false});
  hooks.events.push_back(
      {"flip up", [](const SystemState& s) { return s.bodies[0].omega_b().y(); }, +1, false});
  std::vector<double> flips, ups;
  hooks.on_event = [&](const EventHit& hit) { (hit.name == "flip" ? flips : ups).push_back(hit.state.t); };
  simulate(model, test::single({Vec3::Zero(), Quat::Identity(), Vec3::Zero(), w0}), rs, hooks);
  const EulerPoinsot exact(Lambda, Quat::Identity(), w0);
  ASSERT_GE(flips.size(), 10u);
  for (size_t i = 1; i < flips.size(); ++i) {
    // ω₂ ∝ sn: its zeros are 2K/λ apart; located to 4 ulp of t on exact steps.
    EXPECT_NEAR(flips[i] - flips[i - 1], exact.flip_interval(), 1e-13) << i;
  }
  // ω₂ starts positive, so the rising crossings are every second one, beginning with the second.
  ASSERT_EQ(ups.size(), flips.size() / 2);
  for (size_t i = 0; i < ups.size(); ++i) EXPECT_EQ(ups[i], flips[2 * i + 1]);
}

TEST(Events, AdaptiveRunsLocateEventsOnTheirDenseOutput) {
  // The same landing with dopri45: its continuous extension is exact for the parabola (degree 2 ≤ 4),
  // so the landing time is again exact to the location's resolution.
  const Model model = thrown_ball();
  RunSettings rs;
  rs.duration = 10.0;
  rs.integrator = "dopri45";
  rs.output_interval = 0.25;
  RunHooks hooks;
  hooks.events.push_back(landing());
  hooks.events.push_back({"apex", [](const SystemState& s) { return s.bodies[0].v.z(); }, -1, false});
  std::vector<EventHit> hits;
  hooks.on_event = [&](const EventHit& hit) { hits.push_back(hit); };
  std::vector<double> samples;
  hooks.on_sample = [&](const SystemState& s) {
    samples.push_back(s.t);
    return true;
  };
  const SystemState end = simulate(
      model, test::single({Vec3(0, 0, z0), Quat::Identity(), Vec3(0, 0, v0), Vec3(0.1, 3, 0)}), rs, hooks);
  ASSERT_EQ(hits.size(), 2u);
  EXPECT_EQ(hits[0].name, "apex");
  EXPECT_NEAR(hits[0].state.t, v0 / g, 1e-13);
  EXPECT_EQ(hits[1].name, "landing");
  EXPECT_NEAR(hits[1].state.t, (v0 + std::sqrt(v0 * v0 + 2 * g * z0)) / g, 1e-13);
  EXPECT_EQ(end.t, hits[1].state.t);
  // Samples on the grid up to the landing, then the landing itself, in time order.
  ASSERT_GE(samples.size(), 3u);
  for (size_t i = 0; i + 1 < samples.size(); ++i)
    EXPECT_NEAR(samples[i], 0.25 * static_cast<double>(i), 1e-12);
  EXPECT_EQ(samples.back(), end.t);
}

TEST(Events, AdaptiveRunsStopAfterTheStepInWhichAStopIsRequested) {
  Model model;
  model.add_body(RigidBody::from_principal_moments(1.0, Vec3(1, 2, 2.5)));
  RunSettings rs;
  rs.duration = 100.0;
  rs.integrator = "dopri45";
  rs.output_interval = 50.0;  // samples far apart: the stop must not wait for one
  int asked = 0;
  std::vector<double> samples;
  IntegratorStats stats;
  RunHooks hooks;
  hooks.on_sample = [&](const SystemState& s) {
    samples.push_back(s.t);
    return true;
  };
  hooks.stats = &stats;
  hooks.stop_requested = [&] { return ++asked == 5; };
  const SystemState end = simulate(
      model, test::single({Vec3::Zero(), Quat::Identity(), Vec3::Zero(), Vec3(0.3, 2, 0.1)}), rs, hooks);
  EXPECT_EQ(stats.steps, 5);      // asked once per accepted step
  ASSERT_EQ(samples.size(), 2u);  // t = 0, then the state where the run stopped
  EXPECT_GT(end.t, 0.0);
  EXPECT_LT(end.t, 50.0);
  EXPECT_EQ(samples.back(), end.t);
}

TEST(Events, ANonFiniteEventValueIsAnErrorNamingTheEvent) {
  const Model model = thrown_ball();
  RunSettings rs;
  RunHooks hooks;
  hooks.events.push_back(
      {"broken", [](const SystemState& s) { return s.t > 0.5 ? std::nan("") : 1.0; }, 0, false});
  try {
    simulate(model, test::single({Vec3(0, 0, z0), Quat::Identity(), Vec3(0, 0, v0), Vec3::Zero()}), rs,
             hooks);
    FAIL();
  } catch (const InvalidArgument& e) {
    EXPECT_NE(std::string(e.what()).find("event 'broken' returned nan"), std::string::npos) << e.what();
  }
}

TEST(Events, AVariableWatchedIsReadInlineWithTheBitsOfItsFunction) {
  // A ball thrown up, spinning near its major axis: its height (com_z, held as it is in every
  // formulation) and ω₂ in principal axes (w2, which oscillates: the mixed and body formulations' own ω)
  // cross their thresholds. Read inline (Event::variable) or through g_variables, the crossings are the
  // same, bit for bit.
  Model model;
  model.add_body(RigidBody::from_principal_moments(1.0, Vec3(1, 2, 2.5), "ball"));
  model.add_force<UniformGravity>(Vec3(0, 0, -g));
  const auto spec = [](const std::string& column, double value) {
    EventSpec e;
    e.name = column;
    std::tie(e.field, e.component) = *find_column(column);
    e.value = value;
    return e;
  };
  for (const Formulation F : {Formulation::world, Formulation::mixed, Formulation::body}) {
    std::vector<EventHit> inline_hits, called_hits;
    for (const bool read_inline : {true, false}) {
      RunSettings rs;
      rs.duration = 2.5;
      rs.timestep = 0.01;
      rs.formulation = F;
      RunHooks hooks;
      for (const EventSpec& s : {spec("com_z", 5.0), spec("w2", 0.0)}) {
        Event e = make_event(model, s);
        ASSERT_TRUE(e.variable.has_value());
        const int column = e.variable->column[static_cast<size_t>(F)];
        EXPECT_EQ(column >= 0, s.name == "com_z" || F != Formulation::world) << s.name;
        if (!read_inline) e.variable.reset();
        hooks.events.push_back(std::move(e));
      }
      std::vector<EventHit>& hits = read_inline ? inline_hits : called_hits;
      hooks.on_event = [&](const EventHit& hit) { hits.push_back(hit); };
      simulate(model, test::single({Vec3(0, 0, z0), Quat::Identity(), Vec3(0, 0, v0), Vec3(0.5, 0.5, 5.0)}),
               rs, hooks);
    }
    ASSERT_GE(inline_hits.size(), 4u);  // up through 5 m and down again, and ω₂ changing sign
    ASSERT_EQ(inline_hits.size(), called_hits.size());
    for (size_t i = 0; i < inline_hits.size(); ++i) {
      EXPECT_EQ(inline_hits[i].name, called_hits[i].name);
      EXPECT_EQ(inline_hits[i].state.t, called_hits[i].state.t) << i;
    }
  }
}

}  // namespace
}  // namespace tumble
