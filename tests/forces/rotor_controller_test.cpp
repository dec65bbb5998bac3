// Rotors driven by a controller (RotorController: sampled every Δ, its torques held between samples),
// checked against
//  - the sampled-data system's exact recurrence: a body turning about its symmetry axis by a wheel on
//    that axis is a double integrator, C θ̈ = −u, whose state after a held u is known in closed form;
//  - the same motion with the constant torque a constant law gives;
//  - the motor's limits: a command beyond max_torque is clipped, a speed at max_speed is held;
//  - the total angular momentum, conserved whatever the controller does.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "../support/sim_helpers.hpp"
#include "tumble/error.hpp"
#include "tumble/forces/rotors.hpp"
#include "tumble/sim/diagnostics.hpp"
#include "tumble/sim/run.hpp"
#include "tumble/sim/sensitivities.hpp"
#include "tumble/sim/simulate.hpp"

namespace tumble {
namespace {

using test::end_only;

/// A body of moments (A, A, C) (its wheel included, as if locked) at rest, with a wheel of moment J on
/// its symmetry axis, whose motor a PD law drives to turn the body to θ* about z: u = K_p (θ − θ*) + K_d ω
/// (the wheel's reaction −u turns the body: C ω̇ = −u, so the loop is C θ̈ = −K_p (θ − θ*) − K_d θ̇).
struct Slew {
  double A = 8.0, C = 10.0, J = 0.05, Kp = 2.0, Kd = 6.0, target = 0.5, interval = 0.1;
  Model model;
  std::shared_ptr<const Rotors> rotors;
  SystemState s0;
  explicit Slew(double max_torque = 0.0) {
    model.add_body(RigidBody::from_principal_moments(50.0, Vec3(A, A, C), "sat"));
    Rotor wheel{"wheel", 0, Vec3::UnitZ(), J, 0.0, 0.0, 0.0, max_torque, {}};
    const Rotors open_loop(std::vector<Rotor>{wheel}, model.bodies);
    rotors = open_loop.controlled_by(
        {interval, [this](const SystemView& v, std::span<const double>, std::span<double> u) {
           u[0] = Kp * (yaw(v.body_states[0]) - target) + Kd * v.body_states[0].omega_w.z();
         }});
    model.forces.push_back(rotors);
    s0.bodies.push_back(BodyState{});
  }
  /// θ of a rotation about z.
  static double yaw(const BodyState& b) { return 2.0 * std::atan2(b.q.z(), b.q.w()); }
};

/// The sampled-data system's state at sample k: (θ, ω, Ω).
struct Sampled {
  double theta = 0.0, omega = 0.0, Omega = 0.0;
};

/// The exact recurrence of the held torque over one interval Δ: ω' = ω − Δ u/C, θ' = θ + Δ ω − Δ² u/(2C),
/// Ω' = Ω + Δ u/J.
std::vector<Sampled> recurrence(const Slew& s, int samples) {
  std::vector<Sampled> out{{}};
  for (int k = 1; k < samples; ++k) {
    const Sampled& x = out.back();
    const double u = s.Kp * (x.theta - s.target) + s.Kd * x.omega, d = s.interval;
    out.push_back(
        {x.theta + d * x.omega - d * d * u / (2 * s.C), x.omega - d * u / s.C, x.Omega + d * u / s.J});
  }
  return out;
}

TEST(RotorController, APdSlewIsItsSampledDataSystemsExactRecurrence) {
  const Slew s;
  const double T = 10.0;
  const std::vector<Sampled> exact = recurrence(s, 101);
  // rk4 at h = 1e-3 inside each held interval: ω̇ is constant there, so ω is exact to rounding and the
  // attitude's error is rk4's on a rotation at ≤ 0.3 rad/s, (|ω|h)⁵ per step ≈ 1e-18; what remains is
  // rounding over 10⁴ steps, n ε |θ| ≈ 1e-12: 1e-11 on θ, and on Ω, which sums u Δ/J (|Ω| ≤ 20).
  RunSettings settings = end_only("rk4", T, 1e-3);
  settings.output_interval = s.interval;
  std::vector<SystemState> samples;
  std::vector<double> speeds;
  double worst_L = 0.0;
  (void)simulate(s.model, s.s0, settings, [&](const SystemState& x) {
    samples.push_back(x);
    speeds.push_back(s.rotors->speed(0, x.t));
    worst_L = std::max(worst_L, invariants(s.model, x).angular_momentum.norm());
    return true;
  });
  ASSERT_EQ(samples.size(), exact.size());
  for (size_t k = 0; k < samples.size(); ++k) {
    EXPECT_DOUBLE_EQ(samples[k].t, 0.1 * static_cast<double>(k)) << k;  // the output grid, unchanged
    EXPECT_NEAR(Slew::yaw(samples[k].bodies[0]), exact[k].theta, 1e-11) << k;
    EXPECT_NEAR(samples[k].bodies[0].omega_w.z(), exact[k].omega, 1e-12) << k;
    EXPECT_NEAR(speeds[k], exact[k].Omega, 1e-11) << k;
  }
  // The loop settles: ω_n = √(K_p/C) = 0.45 rad/s, ζ = K_d/(2√(K_p C)) = 0.67, so the error's envelope
  // 0.5 e^{−ζ ω_n t}/√(1 − ζ²) is 0.034 rad at 10 s: below a tenth of the slew.
  EXPECT_NEAR(Slew::yaw(samples.back().bodies[0]), s.target, 0.05);
  // C ω + J Ω = 0: the total angular momentum stays what it was, whatever the motor does (rounding on
  // terms of |J Ω| ≤ 1 over 10⁴ steps).
  EXPECT_LT(worst_L, 1e-12);

  // The run is the same again (the controller starts from the scene's speeds and torques each run),
  // and samples off the controller's grid (every 0.25 s) are where the grid puts them, on the same
  // motion (the steps now also end at 0.25 k: rounding only).
  settings.output_interval = 0.25;
  std::vector<SystemState> coarse;
  const SystemState end = simulate(s.model, s.s0, settings, [&](const SystemState& x) {
    coarse.push_back(x);
    return true;
  });
  ASSERT_EQ(coarse.size(), 41u);
  for (size_t k = 0; k < coarse.size(); ++k) {
    EXPECT_EQ(coarse[k].t, std::min(0.25 * static_cast<double>(k), T)) << k;
    if (k % 2 == 0) {
      EXPECT_NEAR(Slew::yaw(coarse[k].bodies[0]), exact[k * 5 / 2].theta, 1e-11) << k;
    }
  }
  EXPECT_NEAR(end.bodies[0].omega_w.z(), exact.back().omega, 1e-12);
}

TEST(RotorController, AnEventStopsTheRunWhereItCrosses) {
  const Slew s;
  RunHooks hooks;
  Event half{"half way", [&](const SystemState& x) { return Slew::yaw(x.bodies[0]) - 0.25; }, +1, true};
  hooks.events = {half};
  std::vector<double> hits;
  hooks.on_event = [&](const EventHit& hit) { hits.push_back(hit.state.t); };
  std::vector<double> times;
  hooks.on_sample = [&](const SystemState& x) {
    times.push_back(x.t);
    return true;
  };
  RunSettings settings = end_only("rk4", 10.0, 1e-3);
  settings.output_interval = 0.1;
  const SystemState end = simulate(s.model, s.s0, settings, hooks);
  ASSERT_EQ(hits.size(), 1u);
  EXPECT_EQ(end.t, hits[0]);
  EXPECT_EQ(times.back(), hits[0]);  // the crossing is the last sample
  EXPECT_NEAR(Slew::yaw(end.bodies[0]), 0.25, 1e-12);
  // Before it, the grid's samples, each once.
  for (size_t k = 0; k + 1 < times.size(); ++k) EXPECT_DOUBLE_EQ(times[k], 0.1 * static_cast<double>(k));
}

TEST(RotorController, AConstantLawIsTheConstantTorque) {
  // A wheel off the principal axes spun up at 0.02 N m on a tumbling body: the controller that gives
  // 0.02 every 0.05 s runs the motion of the constant torque, its pieces restarting the speed's line at
  // each sample (rounding only: 1e-12 on states of order 1 over 2·10³ steps).
  Mat3 I;
  I << 2.0, 0.1, -0.05, 0.1, 3.0, 0.2, -0.05, 0.2, 4.0;
  Model constant;
  constant.add_body(RigidBody::from_inertia(20.0, I, Vec3::Zero(), "sat"));
  const Rotor wheel{"wheel", 0, Vec3(1.0, 2.0, 2.0) / 3.0, 0.01, 5.0, 0.02, 0.0, 0.0, {}};
  const auto fixed = std::make_shared<const Rotors>(std::vector<Rotor>{wheel}, constant.bodies);
  constant.forces.push_back(fixed);
  Model controlled = constant;
  const auto rotors = fixed->controlled_by(
      {0.05, [](const SystemView&, std::span<const double>, std::span<double> u) { u[0] = 0.02; }});
  controlled.forces = {rotors};
  SystemState s0;
  s0.bodies.push_back(BodyState{});
  s0.bodies[0].omega_w = Vec3(0.4, -0.3, 0.9);
  const SystemState a = simulate(constant, s0, end_only("rk4", 2.0, 1e-3));
  const SystemState b = simulate(controlled, s0, end_only("rk4", 2.0, 1e-3));
  EXPECT_LT((a.bodies[0].omega_w - b.bodies[0].omega_w).norm(), 1e-12);
  EXPECT_LT(a.bodies[0].q.angularDistance(b.bodies[0].q), 1e-12);
  EXPECT_NEAR(rotors->speed(0, 2.0), fixed->speed(0, 2.0), 1e-12);
  EXPECT_NEAR(fixed->speed(0, 2.0), 5.0 + 0.02 * 2.0 / 0.01, 1e-12);
}

TEST(RotorController, ARunAgainStartsFromTheScenesSpeeds) {
  // A controlled model run twice through Run: the second starts from the scene's speeds again (not
  // where the first ended), so its samples are the first's and the drift monitor's L at t = 0 is the
  // start's (a stale one would show a drift of order 1).
  Model model;
  model.add_body(RigidBody::from_principal_moments(20.0, Vec3(2.0, 3.0, 4.0), "sat"));
  const Rotor wheel{"wheel", 0, Vec3(0.0, 0.6, 0.8), 0.01, 5.0, 0.0, 0.0, 0.0, {}};
  model.forces.push_back(Rotors(std::vector<Rotor>{wheel}, model.bodies)
                             .controlled_by({0.05, [](const SystemView& v, auto, std::span<double> u) {
                                               u[0] = 0.02 * v.body_states[0].omega_w.x();
                                             }}));
  SystemState s0;
  s0.bodies.push_back(BodyState{});
  s0.bodies[0].omega_w = Vec3(0.4, -0.3, 0.9);
  struct Drifts final : RunObserver {
    std::vector<double> speeds, drifts;
    void on_sample(const SystemState&, const DriftSample& d) override {
      speeds.push_back(d.rotor_speed.at(0));
      drifts.push_back(d.angular_momentum_drift.value_or(-1.0));
    }
  } first, second;
  RunSettings settings = end_only("rk4", 1.0, 1e-3);
  settings.output_interval = 0.1;
  const Conservation conserved{false, true, true};
  tumble::Run(model, s0, settings, conserved).attach(first).run();
  tumble::Run(model, s0, settings, conserved).attach(second).run();
  EXPECT_EQ(second.speeds, first.speeds);
  EXPECT_EQ(second.drifts, first.drifts);
  EXPECT_EQ(first.speeds.front(), 5.0);
  EXPECT_NE(first.speeds.back(), 5.0);  // the controller did work
  // rk4's L error at |ω|h = 1e-3 over 10³ steps: rounding-level (1e-15 measured); 1e-13 bounds it.
  EXPECT_LT(*std::max_element(first.drifts.begin(), first.drifts.end()), 1e-13);
}

TEST(RotorController, TheMotorsLimitsClipTheCommandAndHoldTheTopSpeed) {
  // The law asks 1 N m; the motor gives at most 0.3 until its wheel reaches 100 rad/s, then nothing:
  // Ω = 0.3 t/J up to t = 100 J/0.3 = 3.33 s, then 100 rad/s.
  Model model;
  model.add_body(RigidBody::from_principal_moments(50.0, Vec3(8.0, 8.0, 10.0), "sat"));
  const Rotor wheel{"wheel", 0, Vec3::UnitZ(), 0.01, 0.0, 0.0, 100.0, 0.3, {}};
  const auto rotors = Rotors(std::vector<Rotor>{wheel}, model.bodies)
                          .controlled_by({0.1, [](const SystemView&, std::span<const double>,
                                                  std::span<double> u) { u[0] = 1.0; }});
  model.forces.push_back(rotors);
  SystemState s0;
  s0.bodies.push_back(BodyState{});
  RunSettings settings = end_only("rk4", 5.0, 1e-3);
  settings.output_interval = 1.0;
  std::vector<double> speeds, torques;
  (void)simulate(model, s0, settings, [&](const SystemState& x) {
    speeds.push_back(rotors->speed(0, x.t));
    torques.push_back(rotors->motor_torque(0, x.t));
    return true;
  });
  const std::vector<double> expected{0.0, 30.0, 60.0, 90.0, 100.0, 100.0};
  ASSERT_EQ(speeds.size(), expected.size());
  for (size_t k = 0; k < speeds.size(); ++k) EXPECT_NEAR(speeds[k], expected[k], 1e-12) << k;
  EXPECT_EQ(torques[2], 0.3);
  EXPECT_EQ(torques.back(), 0.0);
}

TEST(RotorController, WhatItCannotDoIsAClearError) {
  const Slew s;
  const Rotors& open_loop = *s.rotors;
  EXPECT_EQ(
      open_loop.describe(s.model.bodies),
      "rotors 'wheel' on 'sat' (J = 0.05 kg m^2, 0 rad/s, torque by the controller); a controller every "
      "0.1 s");
  // No interval, no law.
  EXPECT_THROW((void)open_loop.controlled_by({0.0, [](auto&, auto, auto) {}}), InvalidArgument);
  EXPECT_THROW((void)open_loop.controlled_by({0.1, {}}), InvalidArgument);
  // A torque table and a controller.
  Rotor tabled{"tabled", 0, Vec3::UnitX(), 0.1, 0.0, 0.0, 0.0, 0.0, {{0.0, 0.0}, {1.0, 0.1}}};
  try {
    (void)Rotors(std::vector<Rotor>{tabled}, s.model.bodies).controlled_by({0.1, [](auto&, auto, auto) {}});
    ADD_FAILURE() << "a table was controlled";
  } catch (const InvalidArgument& e) {
    EXPECT_NE(std::string(e.what()).find("rotor 'tabled' has a torque table"), std::string::npos) << e.what();
  }
  // A torque that is not a number, named with its rotor and time.
  Model model = s.model;
  model.forces = {open_loop.controlled_by(
      {0.1, [](const SystemView& v, auto, std::span<double> u) { u[0] = v.t > 0.25 ? std::nan("") : 0.1; }})};
  try {
    (void)simulate(model, s.s0, end_only("rk4", 1.0, 1e-2));
    ADD_FAILURE() << "a NaN torque was held";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("torque of rotor 'wheel' at t = 0.3"), std::string::npos)
        << e.what();
  }
  // Sensitivities (the law's derivatives are unknown) and run points (the held torques are not in them).
  EXPECT_THROW((void)simulate_sensitivities(s.model, s.s0, end_only("rk4", 1.0, 1e-2),
                                            SensitivityParameters::mass, {}),
               InvalidArgument);
  RunPoint point;
  RunHooks hooks;
  hooks.run_point = &point;
  EXPECT_THROW((void)simulate(s.model, s.s0, end_only("rk4", 1.0, 1e-2), hooks), InvalidArgument);
}

}  // namespace
}  // namespace tumble
