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
  const Model model = test::ball_model();
  const SystemState s0 = test::ball_state();
  const Vec3& omega0 = test::kBallOmega0;
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
