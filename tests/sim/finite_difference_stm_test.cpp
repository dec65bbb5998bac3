// The state transition matrix by central differences (sim/finite_difference_stm.hpp), against the flow
// of a free isotropic body differentiated in closed form (support/isotropic_flow.hpp).
#include <gtest/gtest.h>

#include <cmath>

#include "../support/isotropic_flow.hpp"
#include "tumble/error.hpp"
#include "tumble/forces/model.hpp"
#include "tumble/sim/finite_difference_stm.hpp"

namespace tumble {
namespace {

TEST(FiniteDifferenceStm, AFreeIsotropicBodyGivesItsFlowsDerivativeInClosedForm) {
  Model model;
  model.add_body(RigidBody::from_principal_moments(2.0, Vec3(0.4, 0.4, 0.4), "ball"));
  const Vec3 omega0(0.7, -1.1, 0.5);
  SystemState s0;
  s0.bodies.push_back(BodyState{Vec3(0.1, 0.2, 0.3), Quat(Eigen::AngleAxisd(0.4, Vec3(1, 2, 2).normalized())),
                                Vec3(1.0, -0.5, 0.2), omega0});
  RunSettings settings;
  settings.duration = 1.5;
  settings.timestep = 1e-3;
  settings.integrator = "rk4";
  const double t = settings.duration;
  const Eigen::MatrixXd M = stm_by_central_differences(model, s0, settings, 1e-5);
  const Eigen::MatrixXd expected = test::isotropic_flow_stm(omega0, t);
  // RK4 integrates the attitude at |ω|h = 1.4e-3 to ~1e-13. A central difference of step ε = 1e-5 carries
  // the rounding the 1500 steps accumulate in each run's end (~1e-13 of |x|), over 2ε: 5e-9, and a
  // truncation of ε²|x‴| ~ 1e-10: 1e-8 bounds both.
  EXPECT_LT((M - expected).cwiseAbs().maxCoeff(), 1e-8) << "\n" << M - expected;
  // Refusals.
  EXPECT_THROW((void)stm_by_central_differences(model, s0, settings, 0.0), InvalidArgument);
}

}  // namespace
}  // namespace tumble
