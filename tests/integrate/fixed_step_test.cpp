// Orders of accuracy of the fixed-step integrators, measured against the closed-form motion of a
// torque-free axisymmetric top thrown under uniform gravity, and their known energy behaviour.
#include <gtest/gtest.h>

#include <cmath>

#include "../support/closed_forms.hpp"
#include "../support/sim_helpers.hpp"
#include "tumble/dynamics/quantities.hpp"
#include "tumble/error.hpp"
#include "tumble/forces/forces.hpp"

namespace tumble {
namespace {

const test::AxisymmetricTop kTop{
    0.6, 1.0, Eigen::AngleAxisd(0.5, Vec3(1, 1, 0).normalized()).toRotationMatrix(), Vec3(0.4, -0.3, 2.0)};
const Vec3 kGravity(0, 0, -9.81), kO0(0, 0, 1), kV0(1, 0.5, 5);

/// Largest error at T against the closed form: attitude angle, |ω_b − exact| (rad/s) and |o − exact| (m).
double error_at(const std::string& integrator, Formulation F, double h, double T) {
  Model model;
  model.add_body(RigidBody::from_principal_moments(1.0, Vec3(kTop.I_t, kTop.I_t, kTop.I_s)));
  model.add_force<UniformGravity>(kGravity);
  const BodyState s0{kO0, Quat(kTop.R0), kV0, kTop.R0 * kTop.omega_b0};
  const BodyState s = test::run(model, test::single(s0), T, h, integrator, F).bodies[0];
  const double attitude = rotation_angle_between(s.R(), kTop.R(T));
  const double omega = (s.omega_b() - kTop.omega_b(T)).norm();
  const double position = (s.o - (kO0 + kV0 * T + 0.5 * kGravity * T * T)).norm();
  return std::max({attitude, omega, position});
}

struct OrderCase {
  std::string integrator;
  int order;
  double h;  // largest step of the halving sequence: in the asymptotic range, above rounding
};

TEST(FixedStep, MeasuredOrderMatchesTheory) {
  const OrderCase cases[] = {{"euler", 1, 2e-3},   {"semi_implicit_euler", 1, 2e-3}, {"rk4", 4, 2e-2},
                             {"lie_rk4", 4, 2e-2}, {"implicit_gyro", 1, 2e-3},       {"midpoint", 2, 1e-2}};
  for (const auto& c : cases) {
    for (Formulation F : {Formulation::world, Formulation::mixed, Formulation::body}) {
      const double e1 = error_at(c.integrator, F, c.h, 2.0);
      const double e2 = error_at(c.integrator, F, c.h / 2, 2.0);
      const double e3 = error_at(c.integrator, F, c.h / 4, 2.0);
      // Slope of log(error) against log(h) from the two finer pairs; the bound is ±0.2.
      const double slope1 = std::log2(e1 / e2), slope2 = std::log2(e2 / e3);
      EXPECT_NEAR(slope1, c.order, 0.2)
          << c.integrator << " " << formulation_name(F) << " e=" << e1 << "," << e2;
      EXPECT_NEAR(slope2, c.order, 0.2)
          << c.integrator << " " << formulation_name(F) << " e=" << e2 << "," << e3;
    }
  }
}

TEST(FixedStep, ExplicitEulerGainsExactlyHalfHSquaredOmegaDotLambdaOmegaDot) {
  // Torque-free, mixed formulation: ω̇·Λω = 0, so one explicit Euler step changes the rotational energy
  // by exactly ½h² ω̇ᵀΛω̇ > 0 — the energy gain the research notes report for game-engine steppers.
  const Vec3 Lambda(1.5, 2.5, 4.0), w(0.3, 5.0, 0.4);
  const RigidBody body = RigidBody::from_principal_moments(1.0, Lambda);
  Model model;
  model.add_body(body);
  const double h = 1e-2;
  const BodyState s0{Vec3::Zero(), Quat::Identity(), Vec3::Zero(), w};
  const BodyState s1 = test::run(model, test::single(s0), h, h, "euler").bodies[0];
  const Vec3 w_dot = euler_body<double>(mass_constants<double>(1.0, Lambda), w, Vec3::Zero());
  const double gain = kinetic_energy(body, s1) - kinetic_energy(body, s0);
  EXPECT_GT(gain, 0.0);
  // E ≈ 31 J: rounding of the difference is ~1e-14 J.
  EXPECT_NEAR(gain, 0.5 * h * h * w_dot.dot(Lambda.cwiseProduct(w_dot)), 1e-13);
}

TEST(FixedStep, UnknownNamesAndBadSettingsAreErrors) {
  try {
    (void)make_integrator("rk5");
    FAIL();
  } catch (const InvalidArgument& e) {
    for (const std::string& name : integrator_names()) {
      EXPECT_NE(std::string(e.what()).find(name), std::string::npos) << e.what();
    }
  }
  EXPECT_THROW(parse_formulation("inertial"), InvalidArgument);
  Model model;
  model.add_body(RigidBody::from_principal_moments(1.0, Vec3(1, 1, 1)));
  RunSettings s;
  s.timestep = 0;
  EXPECT_THROW(simulate(model, test::single(BodyState{}), s), InvalidArgument);
  s.timestep = 1e-3;
  s.duration = std::nan("");
  EXPECT_THROW(simulate(model, test::single(BodyState{}), s), InvalidArgument);
}

TEST(FixedStep, SamplesLandOnTheOutputGridAndTheFinalTime) {
  Model model;
  model.add_body(RigidBody::from_principal_moments(1.0, Vec3(1, 2, 2.5)));
  RunSettings s;
  s.duration = 1.05;
  s.timestep = 0.03;  // not a divisor of the output interval: steps are shortened to land on samples
  s.output_interval = 0.1;
  std::vector<double> times;
  simulate(model, test::single(BodyState{}), s, [&](const SystemState& x) {
    times.push_back(x.t);
    return true;
  });
  ASSERT_EQ(times.size(), 12u);  // 0, 0.1, ..., 1.0, and the final 1.05
  for (size_t k = 0; k + 1 < times.size(); ++k) EXPECT_DOUBLE_EQ(times[k], 0.1 * static_cast<double>(k));
  EXPECT_DOUBLE_EQ(times.back(), 1.05);
}

TEST(FixedStep, ABlowUpIsReportedWithBodyTimeAndStep) {
  Model model;
  model.add_body(RigidBody::from_principal_moments(1.0, Vec3(1, 2, 2.5), "rocket"));
  // A finite but enormous force: the velocity overflows to infinity after a few steps.
  model.add_force<BodyCallback>(0, [](double t, const RigidBody&, const BodyState&) {
    return Wrench{Vec3(0, 0, t > 0.5 ? 1.7e308 : 0.0), Vec3::Zero()};
  });
  RunSettings s;
  s.duration = 2;
  s.timestep = 0.1;
  s.integrator = "euler";
  try {
    simulate(model, test::single(BodyState{}), s);
    FAIL();
  } catch (const Error& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("body 'rocket'"), std::string::npos) << m;
    EXPECT_NE(m.find("step "), std::string::npos) << m;
    EXPECT_NE(m.find("reduce the timestep"), std::string::npos) << m;
  }
}

TEST(FixedStep, AStopRequestEndsTheRunAfterTheCurrentStepWithALastSample) {
  // The request is asked after every step, or after every chunk of up to 16 full steps that simulate
  // hands over at once between samples (simulate.hpp): the run ends within one chunk of it.
  Model model;
  model.add_body(RigidBody::from_principal_moments(1.0, Vec3(1, 2, 2.5)));
  RunSettings s;
  s.duration = 10.0;
  s.timestep = 0.01;
  s.output_interval = 1.0;
  for (const char* name : {"rk4", "midpoint"}) {  // chunked (fused) and step by step
    s.integrator = name;
    IntegratorStats stats;
    std::vector<double> times;
    const SystemState end = simulate(
        model, test::single(BodyState{}), s,
        [&](const SystemState& x) {
          times.push_back(x.t);
          return true;
        },
        &stats, [&] { return stats.steps >= 250; });
    ASSERT_EQ(times.size(), 4u) << name;  // 0, 1, 2 on the grid, then where the run stopped
    EXPECT_GE(stats.steps, 250) << name;
    EXPECT_LT(stats.steps, 250 + 16) << name;
    if (std::string(name) == "midpoint") {
      EXPECT_EQ(stats.steps, 250);
    }
    // Fewer than 70 additions of h after the last snapped sample time: rounding ≤ 70 ulp(2.7) ≈ 3e-14.
    EXPECT_NEAR(times.back(), 0.01 * static_cast<double>(stats.steps), 1e-13) << name;
    EXPECT_EQ(end.t, times.back());
  }
}

}  // namespace
}  // namespace tumble
