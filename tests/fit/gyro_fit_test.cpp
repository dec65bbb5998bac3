// tumble fit on noiseless telemetry: the inertia, the initial angular velocity and the bias come back
// to 1e-9 from motion computed by independent methods (the exact Euler–Poinsot solution; tumble's
// simulator at a step far below the fit's); the scale is absolute only when a torque is known; and a
// spin about one principal axis is judged "not determined".
#include <gtest/gtest.h>

#include <random>

#include "fit_support.hpp"
#include "tumble/forces/forces.hpp"
#include "tumble/sim/simulate.hpp"

namespace tumble {
namespace {

using fit::FitOptions;
using fit::FitResult;

double rel(const Mat3& A, const Mat3& B) { return (A - B).cwiseAbs().maxCoeff() / B.cwiseAbs().maxCoeff(); }

// Tolerance of the noiseless fits: the fit's RK4 error is held below 0.1 σ/√(3n) (σ = 1e-9 rad/s
// here: about 4e-12 rad/s, against |ω| ~ 1.4 rad/s), the exact motion is accurate to ~1e-15 relative, and
// the estimate's sensitivity to the samples (the covariance's σ for a unit σ, ~1e2…1e3 relative) turns
// rounding-level residuals into ~1e-12. 1e-9 leaves a wide margin, as the issue asks.
constexpr double kNoiseless = 1e-9;
constexpr double kSigma = 1e-9;  // "noiseless": σ far below any real gyro

TEST(GyroFit, RecoversTheInertiaRatiosAndInitialRateFromTheExactTorqueFreeMotion) {
  const test::GyroTruth truth = test::tumbling_satellite();
  const fit::Telemetry d = test::torque_free_telemetry(truth, 201, 0.1);
  const FitResult f = fit::fit_gyro(d, test::fit_options(kSigma));
  EXPECT_FALSE(f.absolute);  // no torque, no wheel: J/trace J only
  const Mat3 J = truth.J() / truth.J().trace();
  EXPECT_LT(rel(f.J, J), kNoiseless) << f.J << "\n" << J;
  EXPECT_NEAR(f.J.trace(), 1.0, 1e-15);
  EXPECT_LT((f.omega0.value - truth.omega0()).norm() / truth.omega0().norm(), kNoiseless);
  EXPECT_LT((f.principal_moments.value - truth.Lambda / truth.Lambda.sum()).norm(), kNoiseless);
  // The principal axes are the columns of U (up to their signs).
  for (int i = 0; i < 3; ++i)
    EXPECT_GT(std::abs(f.principal_axes.col(i).dot(truth.U.col(i))), 1 - kNoiseless);
  EXPECT_TRUE(f.determined) << f.reason;
  EXPECT_TRUE(f.positive_definite);
  EXPECT_TRUE(f.triangle_inequality);
  EXPECT_LT(f.rms_sigma, 1.0);  // the residuals are rounding, not model error
}

TEST(GyroFit, RecoversAConstantGyroBias) {
  const test::GyroTruth truth = test::tumbling_satellite();
  const Vec3 bias(0.012, -0.021, 0.006);
  const fit::Telemetry d = test::torque_free_telemetry(truth, 201, 0.1, bias);
  const FitResult f = fit::fit_gyro(d, test::fit_options(kSigma, true));
  ASSERT_TRUE(f.bias_estimated);
  EXPECT_LT((f.bias.value - bias).norm() / truth.omega0().norm(), kNoiseless) << f.bias.value.transpose();
  EXPECT_LT(rel(f.J, truth.J() / truth.J().trace()), kNoiseless);
  EXPECT_LT((f.omega0.value - truth.omega0()).norm() / truth.omega0().norm(), kNoiseless);
  // Without the bias in the model the same data do not fit: the residuals are far above σ.
  const FitResult without = fit::fit_gyro(d, test::fit_options(1e-3));
  EXPECT_GT(without.rms_sigma, 2.0);
  EXPECT_FALSE(without.notes.empty());
}

TEST(GyroFit, AKnownTorqueGivesTheAbsoluteInertia) {
  // A body with J full in its reference (= sensor) axes, a constant torque in those axes, stepped by
  // tumble's own simulator (rk4, mixed formulation) at h = 1e-4 s: its error, O(h⁴) ~ 1e-16 relative
  // per unit time, is below the fit's own.
  const test::GyroTruth truth = test::tumbling_satellite();
  const Vec3 tau(3.0, -2.0, 1.5);  // N·m: changes |ω| by ~2e-2 rad/s over the record
  const RigidBody body = RigidBody::from_inertia(500.0, truth.J());
  Model model;
  model.add_body(body);
  model.add_force<PureTorque>(0, tau, Frame::reference);
  const BodyState s0 = state_from_reference(body, Vec3::Zero(), Quat::Identity(), Vec3::Zero(),
                                            truth.omega0(), Frame::reference);
  RunSettings settings;
  settings.duration = 20.0;
  settings.timestep = 1e-4;
  settings.output_interval = 0.1;
  settings.integrator = "rk4";
  fit::Telemetry d;
  simulate(model, SystemState{0.0, {s0}, {}}, settings, [&](const SystemState& x) {
    const ReferenceFrameState ref = reference_state(body, x.bodies[0]);
    d.t.push_back(x.t);
    d.omega.push_back(ref.orientation.conjugate() * ref.omega_w);  // ω in sensor axes
    d.tau.push_back(tau);
    return true;
  });
  ASSERT_EQ(d.t.size(), 201u);
  const FitResult f = fit::fit_gyro(d, test::fit_options(kSigma));
  EXPECT_TRUE(f.absolute);
  // The simulator's step, 1e-4 s, leaves ~1e-13 rad/s in the samples; 1e-9 holds with room.
  EXPECT_LT(rel(f.J, truth.J()), kNoiseless) << f.J << "\n" << truth.J();
  EXPECT_LT((f.omega0.value - truth.omega0()).norm() / truth.omega0().norm(), kNoiseless);
  EXPECT_TRUE(f.determined) << f.reason;
}

TEST(GyroFit, AKnownWheelMomentumGivesTheAbsoluteInertia) {
  // Reaction wheels with momentum h(t) in sensor axes act on the body by the torque h × ω − ḣ (the
  // wheels' momentum changes by −that). Here tumble's simulator steps the body alone with that torque
  // applied as a callback (world axes: R (h × ω − ḣ)), an independent route from the fit's, which
  // integrates the total momentum L = J ω + h. h changes linearly, as the fit interpolates it between
  // samples, so the two models are the same equation.
  const test::GyroTruth truth = test::tumbling_satellite();
  const Vec3 h0(20.0, -10.0, 30.0), h_dot(0.5, 0.2, -0.3);  // N·m·s, N·m
  const RigidBody body = RigidBody::from_inertia(500.0, truth.J());
  Model model;
  model.add_body(body);
  model.add_force<BodyCallback>(0, [&](double t, const RigidBody& b, const BodyState& x) {
    const ReferenceFrameState ref = reference_state(b, x);
    const Vec3 omega = ref.orientation.conjugate() * ref.omega_w;
    const Vec3 h = h0 + t * h_dot;
    return Wrench{Vec3::Zero(), ref.orientation * Vec3(h.cross(omega) - h_dot)};
  });
  const BodyState s0 = state_from_reference(body, Vec3::Zero(), Quat::Identity(), Vec3::Zero(),
                                            truth.omega0(), Frame::reference);
  RunSettings settings;
  settings.duration = 10.0;
  settings.timestep = 1e-4;
  settings.output_interval = 0.1;
  fit::Telemetry d;
  simulate(model, SystemState{0.0, {s0}, {}}, settings, [&](const SystemState& x) {
    const ReferenceFrameState ref = reference_state(body, x.bodies[0]);
    d.t.push_back(x.t);
    d.omega.push_back(ref.orientation.conjugate() * ref.omega_w);
    d.h.push_back(h0 + x.t * h_dot);
    return true;
  });
  ASSERT_EQ(d.t.size(), 101u);
  const FitResult f = fit::fit_gyro(d, test::fit_options(kSigma));
  EXPECT_TRUE(f.absolute);
  // As above: the simulator's RK4 at 1e-4 s leaves ~1e-13 rad/s in the samples.
  EXPECT_LT(rel(f.J, truth.J()), kNoiseless) << f.J << "\n" << truth.J();
  EXPECT_LT((f.omega0.value - truth.omega0()).norm() / truth.omega0().norm(), kNoiseless);
  EXPECT_TRUE(f.determined) << f.reason;
}

TEST(GyroFit, ASpinAboutOnePrincipalAxisDoesNotDetermineTheInertia) {
  // Steady spin about the major axis: ω is constant, J ω ∥ ω, and nothing else about J shows.
  test::GyroTruth truth = test::tumbling_satellite();
  truth.omega_b0 = Vec3(0.0, 0.0, 0.8);
  for (const double noise : {0.0, 1e-3}) {
    const fit::Telemetry d = test::torque_free_telemetry(truth, 200, 0.1, Vec3::Zero(), noise, 7);
    const FitResult f = fit::fit_gyro(d, test::fit_options(noise > 0 ? noise : 1e-6));
    EXPECT_FALSE(f.determined) << "noise " << noise << ": " << f.reason;
    EXPECT_NE(f.reason.find("spins about one axis"), std::string::npos) << f.reason;
    EXPECT_NE(f.reason.find("Excite the other axes"), std::string::npos) << f.reason;
    const std::string json = fit::fit_json(f);
    EXPECT_NE(json.find("\"verdict\": \"not determined\""), std::string::npos);
    EXPECT_EQ(json.find("nan"), std::string::npos);  // undetermined quantities are null, not NaN
  }
}

TEST(GyroFit, RejectsOptionsItCannotUse) {
  const fit::Telemetry d = test::torque_free_telemetry(test::tumbling_satellite(), 20, 0.1);
  for (const double sigma : {0.0, -1.0, std::nan("")}) {
    try {
      (void)fit::fit_gyro(d, test::fit_options(sigma));
      ADD_FAILURE() << sigma;
    } catch (const InvalidArgument& e) {
      EXPECT_NE(std::string(e.what()).find("the gyro's noise"), std::string::npos) << e.what();
    }
  }
  FitOptions o = test::fit_options(1e-3);
  o.substep = 0.0;
  EXPECT_THROW((void)fit::fit_gyro(d, o), InvalidArgument);
  o = test::fit_options(1e-3);
  o.max_iterations = 0;
  EXPECT_THROW((void)fit::fit_gyro(d, o), InvalidArgument);
}

}  // namespace
}  // namespace tumble
