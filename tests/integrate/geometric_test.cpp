// What the structure-preserving and adaptive integrators promise, and the honest behaviour of the
// game-engine step.
#include <gtest/gtest.h>

#include <cmath>

#include "../support/closed_forms.hpp"
#include "../support/sim_helpers.hpp"
#include "tumble/dynamics/quantities.hpp"
#include "tumble/forces/forces.hpp"
#include "tumble/sim/diagnostics.hpp"

namespace tumble {
namespace {

Model free_body(const Vec3& Lambda) {
  Model model;
  model.add_body(RigidBody::from_principal_moments(1.0, Lambda));
  return model;
}

TEST(LieRk4, OrientationStaysOnSO3WithoutRenormalisation) {
  // 10⁵ steps, each a product of exact unit quaternions: |q| − 1 performs a random walk of rounding,
  // ~1e-16·√10⁵ ≈ 3e-14, with no systematic drift.
  const Model model = free_body(Vec3(1.5, 2.5, 4.0));
  const BodyState s0{Vec3::Zero(), Quat::Identity(), Vec3::Zero(), Vec3(0.3, 5.0, 0.4)};
  for (Formulation F : {Formulation::world, Formulation::mixed}) {
    RunSettings rs;
    rs.duration = 100.0;
    rs.timestep = 1e-3;
    rs.output_interval = 100.0;
    rs.integrator = "lie_rk4";
    rs.formulation = F;
    // Read the raw coordinates: step the integrator directly (simulate normalises nothing either).
    const auto integrator = make_integrator("lie_rk4");
    SystemCoordinates x = to_coordinates(F, test::single(s0));
    for (int i = 0; i < 100000; ++i) integrator->step(model, F, x, 1e-3);
    EXPECT_LT(std::abs(x.bodies.quat(0).norm() - 1.0), 1e-13) << formulation_name(F);
  }
}

TEST(ImplicitGyro, StableAtLargeStepsBecauseItDissipates) {
  // The test body of Hairer, Lubich & Wanner (GNI §IV.1), I = (2, 1, 2/3), violates the triangle inequality (2 > 1 + 2/3:
  // no mass distribution has it) and tumble refuses it; take a physical body of the same shape class.
  const Vec3 I(1.0, 2.0, 2.5);
  const Model model = free_body(I);
  const Vec3 L_b(std::sin(1.1), 0.0, std::cos(1.1));
  const BodyState s0{Vec3::Zero(), Quat::Identity(), Vec3::Zero(), L_b.cwiseQuotient(I)};
  const auto traj = test::trajectory(model, test::single(s0), 107.3, 0.05, "implicit_gyro");
  double E_prev = kinetic_energy(model.bodies[0], s0);
  double L_prev = angular_momentum(model.bodies[0], s0).norm();
  for (const auto& x : traj) {
    const double E = kinetic_energy(model.bodies[0], x.bodies[0]);
    const double L = angular_momentum(model.bodies[0], x.bodies[0]).norm();
    // Backward Euler on Euler's equation never gains energy or momentum (up to rounding).
    EXPECT_LE(E, E_prev * (1 + 1e-14));
    EXPECT_LE(L, L_prev * (1 + 1e-14));
    E_prev = E;
    L_prev = L;
  }
  // Over 107 s at h = 0.05 the loss is of order ten per cent (the research note measured 17 % on its
  // body); the point is that this method is not for physics that must conserve.
  const double loss = 1 - E_prev / kinetic_energy(model.bodies[0], s0);
  std::printf("implicit_gyro energy loss over 107.3 s at h = 0.05 s: %.3g\n", loss);
  EXPECT_GT(loss, 0.01);
}

TEST(Dopri45, MeetsItsToleranceAndLandsOnSampleTimes) {
  // Axisymmetric top under gravity against its closed form, at two tolerances.
  const test::AxisymmetricTop top{
      0.6, 1.0, Eigen::AngleAxisd(0.5, Vec3(1, 1, 0).normalized()).toRotationMatrix(), Vec3(0.4, -0.3, 5.0)};
  Model model = free_body(Vec3(top.I_t, top.I_t, top.I_s));
  const BodyState s0{Vec3::Zero(), Quat(top.R0), Vec3::Zero(), top.R0 * top.omega_b0};
  std::vector<double> errors;
  std::vector<long> steps;
  for (double tol : {1e-7, 1e-10}) {
    RunSettings rs;
    rs.duration = 20.0;
    rs.timestep = 1e-2;
    rs.output_interval = 0.37;  // not related to the steps the method takes
    rs.integrator = "dopri45";
    rs.tolerances = {tol, tol * 1e-3};
    IntegratorStats stats;
    double worst = 0;
    int samples = 0;
    simulate(
        model, test::single(s0), rs,
        [&](const SystemState& x) {
          EXPECT_NEAR(x.t, std::min(0.37 * samples, 20.0), 1e-12);
          ++samples;
          worst = std::max(worst, rotation_angle_between(x.bodies[0].R(), top.R(x.t)));
          worst = std::max(worst, (x.bodies[0].omega_b() - top.omega_b(x.t)).norm() / top.omega_b0.norm());
          return true;
        },
        &stats);
    EXPECT_EQ(samples, 56);  // 0, 0.37, ..., 19.98 and 20
    EXPECT_GT(stats.steps, 0);
    EXPECT_GE(stats.evaluations, 6 * stats.steps);
    errors.push_back(worst);
    steps.push_back(stats.steps);
    // Global error of a tolerance-controlled method is a modest multiple of the local tolerance over
    // ~30 periods of the precession: 100× covers the accumulation.
    EXPECT_LT(worst, 100 * tol) << "tolerance " << tol;
  }
  EXPECT_LT(errors[1], errors[0]);
  // Fifth-order local error: 1000× tighter tolerance costs ~1000^(1/5) ≈ 4× the steps.
  EXPECT_GT(static_cast<double>(steps[1]) / static_cast<double>(steps[0]), 2.5);
  EXPECT_LT(static_cast<double>(steps[1]) / static_cast<double>(steps[0]), 6.5);
}

}  // namespace
}  // namespace tumble
