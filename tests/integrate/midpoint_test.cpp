// midpoint (implicit midpoint + Cayley, the energy–momentum method): exact conservation of energy,
// |L| and L_w without torque at any step, the exact angular-impulse balance, second order.
#include <gtest/gtest.h>

#include <cmath>

#include "../support/sim_helpers.hpp"
#include "tumble/dynamics/quantities.hpp"
#include "tumble/error.hpp"
#include "tumble/forces/forces.hpp"
#include "tumble/integrate/euler_poinsot.hpp"
#include "tumble/sim/diagnostics.hpp"

namespace tumble {
namespace {

const Vec3 kLambda(1.2e-5, 3.1e-5, 4.0e-5);  // the T-handle of splitting_test.cpp
const Vec3 kOmega0(2.0, 20.0, 2.0);

TEST(Midpoint, ConservesEnergyAndMomentumExactlyWithoutTorque) {
  Model model;
  model.add_body(RigidBody::from_principal_moments(0.1, kLambda));
  const BodyState s0{Vec3::Zero(), Quat::Identity(), Vec3::Zero(), kOmega0};
  const Invariants a = invariants(model, test::single(s0));
  for (Formulation F : {Formulation::mixed, Formulation::world, Formulation::body}) {
    double worst_E = 0, worst_L = 0;
    for (const auto& x : test::trajectory(model, test::single(s0), 50.0, 0.02, "midpoint", F)) {
      const Invariants b = invariants(model, x);
      worst_E = std::max(worst_E, std::abs(b.kinetic_energy / a.kinetic_energy - 1));
      worst_L =
          std::max(worst_L, (b.angular_momentum - a.angular_momentum).norm() / a.angular_momentum.norm());
    }
    // The quadratic invariants are kept by the scheme itself; what remains is rounding of 2500 steps
    // (each step's fixed point is converged to 4 ulp): ~3e-14 measured in the mixed and body variables.
    // The world formulation converts ω_w → ^bω → ω_w every step, which measured a systematic 4e-16 per
    // step (1e-12 after 2500 steps, the same as splitting's): its bound is 2500 · 2 conversions · 2 ulp.
    const double tol = F == Formulation::world ? 2500 * 2 * 2 * 2.2e-16 : 1e-12;
    EXPECT_LT(worst_E, tol) << formulation_name(F);
    EXPECT_LT(worst_L, tol) << formulation_name(F);
  }
}

TEST(Midpoint, AngularImpulseBalanceIsExact) {
  // A constant world torque: L_{n+1} = L_n + h τ exactly, so L_w(T) − L_w(0) = τ T to rounding.
  Model model;
  model.add_body(RigidBody::from_principal_moments(1.0, Vec3(0.5, 0.8, 1.1)));
  const Vec3 tau(0.3, -0.2, 0.1);
  model.add_force<PureTorque>(0, tau, Frame::world);
  const BodyState s0{Vec3::Zero(), Quat::Identity(), Vec3::Zero(), Vec3(1, 4, 0.5)};
  const SystemState end = test::run(model, test::single(s0), 5.0, 0.01, "midpoint");
  const Vec3 dL = angular_momentum(model.bodies[0], end.bodies[0]) - angular_momentum(model.bodies[0], s0);
  EXPECT_LT((dL - tau * 5.0).norm(), 1e-13 * 100);  // |L| ~ 4, 500 steps: rounding ~1e-13
}

TEST(Midpoint, IsSecondOrderUnderTorque) {
  Model model;
  model.add_body(RigidBody::from_principal_moments(1.0, Vec3(0.02, 0.03, 0.04)));
  model.add_force<Spring>(Spring::End{0, Vec3(0.1, 0.05, 0.0)}, Spring::End{all_bodies, Vec3(0, 0, 0.5)},
                          30.0, 0.3, 0.0);
  model.add_force<UniformGravity>(Vec3(0, 0, -9.81));
  const BodyState s0{Vec3(0.1, 0, 0), Quat::Identity(), Vec3(0, 0.3, 0), Vec3(1, 8, 0.5)};
  // Reference: RK4 at h = 1e-4, error ~1e-13, far below the midpoint errors compared here.
  const BodyState ref = test::run(model, test::single(s0), 2.0, 1e-4, "rk4").bodies[0];
  auto error = [&](double h) {
    const BodyState s = test::run(model, test::single(s0), 2.0, h, "midpoint").bodies[0];
    return std::max({rotation_angle_between(s.R(), ref.R()), (s.o - ref.o).norm(),
                     (s.omega_w - ref.omega_w).norm() / 10});
  };
  const double e1 = error(1e-2), e2 = error(5e-3), e3 = error(2.5e-3);
  EXPECT_NEAR(std::log2(e1 / e2), 2.0, 0.2) << e1 << " " << e2;
  EXPECT_NEAR(std::log2(e2 / e3), 2.0, 0.2) << e2 << " " << e3;
}

TEST(Midpoint, RefusesAStepTooLargeForItsSolve) {
  Model model;
  model.add_body(RigidBody::from_principal_moments(0.1, kLambda));
  const BodyState s0{Vec3::Zero(), Quat::Identity(), Vec3::Zero(), kOmega0};
  try {
    test::run(model, test::single(s0), 10.0, 1.0, "midpoint");  // h|ω| = 20
    FAIL() << "expected the fixed-point solve to fail";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("reduce the timestep"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace tumble
