// Sensitivities (sim/sensitivities.hpp): forward-mode derivatives of the steps each integrator takes,
// checked against
//  - the free isotropic body's flow, differentiated in closed form (support/isotropic_flow.hpp);
//  - central differences of the same integrator (sim/finite_difference_stm.hpp), whose own error is
//    shown by halving their step;
//  - a conserved quantity's derivative: without torque L_w(t) = L_w(0) for every x(0), so
//    ∂L_w(t)/∂x(0) = ∂L_w(0)/∂x(0), which RK4 keeps to its order h⁴;
//  - the run's own states: the dual numbers' values are simulate()'s, bit for bit.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <tuple>

#include "../support/isotropic_flow.hpp"
#include "tumble/error.hpp"
#include "tumble/forces/forces.hpp"
#include "tumble/sim/finite_difference_stm.hpp"
#include "tumble/sim/sensitivities.hpp"

namespace tumble {
namespace {

/// Settings of a run of `duration` s in steps of h by `integrator` (sampled at the end only).
RunSettings run(const std::string& integrator, double duration, double h) {
  RunSettings settings;
  settings.integrator = integrator;
  settings.duration = duration;
  settings.timestep = h;
  return settings;
}

/// The sensitivities at the end of a run.
Sensitivities at_end(const Model& model, const SystemState& s0, const RunSettings& settings,
                     SensitivityParameters parameters = SensitivityParameters::inertia,
                     SystemState* end = nullptr) {
  Sensitivities last;
  const SystemState e = simulate_sensitivities(model, s0, settings, parameters,
                                               [&](const SystemState&, const Sensitivities& s) {
                                                 last = s;
                                                 return true;
                                               });
  if (end) *end = e;
  return last;
}

/// A T-handle-like triaxial body tumbling near its intermediate axis, its reference frame off its
/// centre of mass and turned from its principal axes (so every conversion of the tangent space shows).
RigidBody handle() {
  Mat3 I;
  I << 0.8, 0.1, -0.05, 0.1, 1.6, 0.2, -0.05, 0.2, 2.1;
  return RigidBody::from_inertia(3.0, I * 1e-2, Vec3(0.05, -0.02, 0.1), "handle");
}
BodyState handle_state(const RigidBody& body) {
  return state_from_reference(body, Vec3(0.3, -0.1, 1.0),
                              Quat(Eigen::AngleAxisd(0.7, Vec3(1, -2, 0.5).normalized())),
                              Vec3(0.4, 0.1, 2.0), Vec3(0.2, 6.0, 0.3), Frame::reference);
}

/// The handle under gravity with a body-fixed force off its centre of mass and quadratic drag: every
/// column of the tangent space (and the loads' own dependence on the state) is exercised.
Model forced_handle() {
  Model model;
  model.add_body(handle());
  model.add_force<UniformGravity>(Vec3(0, 0, -9.81));
  model.add_force<PointForce>(0, Vec3(0.3, 0.0, 0.5), Frame::reference, Vec3(0.1, 0.0, 0.0),
                              Frame::reference);
  model.add_force<QuadraticDrag>(all_bodies, 0.05, 1e-3);
  return model;
}

TEST(Sensitivities, AFreeIsotropicBodyGivesItsFlowsDerivativeInClosedForm) {
  const Model model = test::ball_model();
  const SystemState s0 = test::ball_state();
  const Vec3& omega0 = test::kBallOmega0;
  for (const std::string& integrator : differentiating_integrators()) {
    for (Formulation F : {Formulation::world, Formulation::mixed, Formulation::body}) {
      const bool exact_flow = integrator == "splitting" || integrator == "splitting4" ||
                              integrator == "exact";
      const bool fourth_order = integrator == "rk4" || integrator == "lie_rk4" || exact_flow;
      RunSettings settings = run(integrator, fourth_order ? 1.5 : 0.3, fourth_order ? 1e-3 : 1e-4);
      settings.formulation = F;
      settings.output_interval = 0.5;
      const double t = settings.duration;
      const Sensitivities S = at_end(model, s0, settings);
      const Eigen::MatrixXd expected = test::isotropic_flow_stm(omega0, t);
      // RK4 and Lie–RK4 at |ω|h = 1.4e-3: attitude errors ~1e-13 per unit, so their derivatives agree
      // to 1e-10. The first-order methods at h = 1e-4 (3000 steps) err by ~|ω|²h t ≈ 6e-5 (a free
      // isotropic body's ω is constant, its attitude error O(h)): 1e-3 bounds it. dopri45 at its default
      // tolerances (1e-9 relative) keeps each step's error below 1e-9 of the state: over the run 4e-9
      // measured, 1e-7 bounds it.
      // splitting, splitting4 and exact evaluate the free flow itself: rounding alone, ~1e-16 a step.
      const double tolerance = exact_flow                ? 1e-12
                               : fourth_order            ? 1e-10
                               : integrator == "dopri45" ? 1e-7
                                                         : 1e-3;
      EXPECT_LT((S.stm - expected).cwiseAbs().maxCoeff(), tolerance)
          << integrator << " " << formulation_name(F) << "\n"
          << S.stm - expected;
      // The translation does not depend on the moments: ∂p/∂I = ∂v/∂I = 0, exactly where v is integrated
      // in world axes; the body formulation moves o by R ^bv, whose rotation does depend on them, so
      // there the method's own error shows (the tolerance above). (The rotation does depend on them:
      // changing one moment makes the sphere a triaxial body, whose ω moves at first order.)
      const double translation = F == Formulation::body ? tolerance : 0.0;
      EXPECT_LE(S.parameters.topRows(3).cwiseAbs().maxCoeff(), translation) << integrator;
      EXPECT_LE(S.parameters.middleRows(6, 3).cwiseAbs().maxCoeff(), translation) << integrator;
    }
  }
}

TEST(Sensitivities, EachIntegratorAgreesWithCentralDifferencesOfItself) {
  const Model model = forced_handle();
  SystemState s0;
  s0.bodies.push_back(handle_state(model.bodies[0]));
  for (const std::string& integrator : differentiating_integrators()) {
    if (integrator == "dopri45") continue;  // its step lengths move with x(0): the next test
    if (integrator == "exact") continue;    // solves no forced motion: the free-body tests
    const RunSettings settings = run(integrator, 0.5, 2e-3);
    const Eigen::MatrixXd S = at_end(model, s0, settings).stm;
    const Eigen::MatrixXd fd = stm_by_central_differences(model, s0, settings, 1e-6);
    const Eigen::MatrixXd fd2 = stm_by_central_differences(model, s0, settings, 2e-6);
    // A central difference errs by ε²|x‴|/6 (truncation: 4× from ε to 2ε, so |fd − fd2| ≈ 3× it) plus
    // the rounding of 250 steps' ends over 2ε (~1e-16·|x|·√250/1e-6 ≈ 1e-9, |x| ~ 10): the dual numbers
    // must be within that of the difference at ε.
    const double fd_error = (fd - fd2).cwiseAbs().maxCoeff();
    EXPECT_LT((S - fd).cwiseAbs().maxCoeff(), fd_error + 1e-8) << integrator << "\n" << S - fd;
    EXPECT_GT(S.cwiseAbs().maxCoeff(), 1.0) << "not trivially zero";
  }
}

TEST(Sensitivities, Dopri45DifferentiatesItsAcceptedStepsWithTheirLengthsHeldFixed) {
  // The step lengths dopri45's error control chooses depend on x(0); its sensitivities hold them fixed
  // (docs/sensitivities.md), so they are not the derivative of the adaptive run (which central
  // differences of it would approximate, jumps of its step sequence included) but of its accepted
  // steps, and like its states they converge to the flow's as the tolerance shrinks. Reference: RK4 at
  // h = 1e-4 (|ω|h = 6e-4: its error ~(|ω|h)⁴ ≈ 1e-13, below every tolerance here).
  const Model model = forced_handle();
  SystemState s0;
  s0.bodies.push_back(handle_state(model.bodies[0]));
  const Eigen::MatrixXd reference = at_end(model, s0, run("rk4", 0.5, 1e-4)).stm;
  double error[3];
  const double relative[3] = {1e-8, 1e-10, 1e-12};
  for (int r = 0; r < 3; ++r) {
    RunSettings settings = run("dopri45", 0.5, 1e-3);
    settings.tolerances = {relative[r], 1e-3 * relative[r]};
    const Eigen::MatrixXd S = at_end(model, s0, settings).stm;
    error[r] = (S - reference).cwiseAbs().maxCoeff();
    // The local errors, each ≤ the tolerance, add up over the run and the tangent inherits them: the
    // state's own error is ~10× the relative tolerance here (|x| ~ 10), its derivatives' (|S| ~ 4)
    // measured 1.3–4.2 × the tolerance.
    EXPECT_LT(error[r], 20.0 * relative[r] * S.cwiseAbs().maxCoeff()) << relative[r];
  }
  // Converging with the tolerance, not stalled at some error of the treatment of the steps: 100× smaller
  // each time (the 5th-order steps' error per unit step is proportional to the tolerance).
  EXPECT_LT(error[1], error[0] / 30) << error[0] << " " << error[1];
  EXPECT_LT(error[2], error[1] / 30) << error[1] << " " << error[2];
}

TEST(Sensitivities, TheInertiaColumnsAreDerivativesWithRespectToThePrincipalMoments) {
  // ∂x/∂I_k with x(0) fixed: against rerunning the body with I_k ± ε (principal axes = reference axes).
  const Vec3 Lambda(0.02, 0.05, 0.06);
  const BodyState s{Vec3(0, 0, 0), Quat(Eigen::AngleAxisd(0.3, Vec3(0, 1, 1).normalized())), Vec3(1, 0, 0),
                    Vec3(0.1, 4.0, 0.2)};
  auto model_with = [&](const Vec3& moments, double mass) {
    Model m;
    m.add_body(RigidBody::from_principal_moments(mass, moments, "box"));
    m.add_force<GravityGradient>(3.986e14, Vec3(-7.0e6, 0, 0));
    // A thrust off the centre of mass: gravity alone would give every mass the same motion.
    m.add_force<PointForce>(0, Vec3(0.0, 0.2, 0.1), Frame::reference, Vec3(0.1, 0.0, 0.0), Frame::reference);
    return m;
  };
  const RunSettings settings = run("rk4", 1.0, 1e-3);
  SystemState s0;
  s0.bodies.push_back(s);
  const Sensitivities S = at_end(model_with(Lambda, 4.0), s0, settings);
  const Sensitivities Sm = at_end(model_with(Lambda, 4.0), s0, settings, SensitivityParameters::mass);
  const double eps = 1e-7;
  const Model reference = model_with(Lambda, 4.0);
  const RigidBody& body = reference.bodies[0];
  for (int k = 0; k < 4; ++k) {
    Vec3 up = Lambda, down = Lambda;
    double m_up = 4.0, m_down = 4.0;
    if (k < 3) {
      up(k) += eps;
      down(k) -= eps;
    } else {
      m_up += eps;
      m_down -= eps;
    }
    const SystemState a = simulate(model_with(up, m_up), s0, settings);
    const SystemState b = simulate(model_with(down, m_down), s0, settings);
    const Tangent fd =
        tangent_between(reference_state(body, b.bodies[0]), reference_state(body, a.bodies[0])) / (2 * eps);
    const Tangent dual = k < 3 ? Tangent(S.parameters.col(k)) : Tangent(Sm.parameters.col(0));
    // Rounding of the ends over 2ε: ~1e-15·|x|/2e-7 ≈ 1e-7 relative to the derivatives (~1e2).
    EXPECT_LT((dual - fd).cwiseAbs().maxCoeff(), 1e-6 * (1 + fd.cwiseAbs().maxCoeff())) << k << "\n"
                                                                                        << dual - fd;
    EXPECT_GT(dual.cwiseAbs().maxCoeff(), 1e-3) << "the moments do move the body: " << k;
  }
}

TEST(Sensitivities, TheForceColumnsAreDerivativesWithRespectToTheForceModelsParameters) {
  // ∂x/∂p for every parameter of every built-in model, against rerunning with p ± ε (relative). 14
  // parameters with a body's 12 state columns take two passes; a spring's 3 on two bodies (coupled, dense).
  auto forced = [](const std::vector<double>& p) {
    Model m;
    m.add_body(handle());
    m.add_force<UniformGravity>(Vec3(p[0], p[1], p[2]));
    m.add_force<PointForce>(0, Vec3(p[3], p[4], p[5]), Frame::reference, Vec3(0.3, 0.0, 0.5),
                            Frame::reference);
    m.add_force<PureTorque>(0, Vec3(p[6], p[7], p[8]), Frame::principal);
    m.add_force<ViscousDamping>(all_bodies, p[9], p[10]);
    m.add_force<QuadraticDrag>(all_bodies, p[11], p[12]);
    m.add_force<GravityGradient>(p[13], Vec3(-20.0, 0.0, 0.0));
    return m;
  };
  auto sprung = [](const std::vector<double>& p) {
    Model m;
    m.add_body(handle());
    m.add_body(RigidBody::from_principal_moments(2.0, Vec3(0.02, 0.03, 0.04), "block"));
    m.add_force<Spring>(Spring::End{0, Vec3(0.1, 0.0, 0.0)}, Spring::End{1, Vec3(0.0, 0.05, 0.0)}, p[0], p[1],
                        p[2]);
    return m;
  };
  const std::vector<double> p_forced = {0.1,   -0.2,  -9.81, 0.05,  0.2,  -0.1, 0.01,
                                        -0.02, 0.005, 0.3,   0.002, 0.05, 1e-3, 40.0};
  const std::vector<double> p_sprung = {50.0, 0.4, 0.5};
  struct Case {
    std::function<Model(const std::vector<double>&)> make;
    std::vector<double> p0;
    const char* integrator;
  };
  for (const Case& c :
       {Case{forced, p_forced, "rk4"}, Case{forced, p_forced, "splitting"}, Case{sprung, p_sprung, "rk4"}}) {
    const auto& make = c.make;
    const std::vector<double>& p0 = c.p0;
    const char* integrator = c.integrator;
    const Model model = make(p0);
    SystemState s0;
    for (const RigidBody& b : model.bodies) s0.bodies.push_back(handle_state(b));
    s0.bodies.back().o += Vec3(0.5, 0.0, 0.0) * static_cast<double>(model.bodies.size() - 1);
    const RunSettings settings = run(integrator, 0.5, 1e-3);
    const Sensitivities S = at_end(model, s0, settings, SensitivityParameters::forces);
    ASSERT_EQ(S.parameters.cols(), static_cast<Eigen::Index>(p0.size()));
    ASSERT_EQ(S.parameter_names.size(), p0.size());
    EXPECT_TRUE(S.parameter_names[0].ends_with(p0.size() == 3 ? "stiffness" : "g_x")) << S.parameter_names[0];
    EXPECT_EQ(S.parameters_per_body, 0);
    for (size_t k = 0; k < p0.size(); ++k) {
      // Central differences at ε and 2ε (ε = 1e-5 |p|): their difference shows their own error
      // (truncation ε²|x‴|/6, 4× at 2ε; rounding of the ends over 2ε, ½ at 2ε).
      auto central = [&](double eps) {
        std::vector<double> up = p0, down = p0;
        up[k] += eps;
        down[k] -= eps;
        const SystemState a = simulate(make(up), s0, settings), b = simulate(make(down), s0, settings);
        Eigen::MatrixXd fd(12 * model.bodies.size(), 1);
        for (size_t i = 0; i < model.bodies.size(); ++i) {
          const RigidBody& body = model.bodies[i];
          fd.block<12, 1>(12 * static_cast<Eigen::Index>(i), 0) =
              tangent_between(reference_state(body, b.bodies[i]), reference_state(body, a.bodies[i])) /
              (2 * eps);
        }
        return fd;
      };
      const double eps = 1e-5 * std::abs(p0[k]);
      const Eigen::MatrixXd fd = central(eps), fd2 = central(2 * eps);
      const Eigen::MatrixXd dual = S.parameters.col(static_cast<Eigen::Index>(k));
      // The roundings at ε and 2ε are independent, so |fd − fd2| can understate them by chance: 3× it,
      // and at least 1e-9 of the derivative.
      EXPECT_LT((dual - fd).cwiseAbs().maxCoeff(),
                3 * (fd - fd2).cwiseAbs().maxCoeff() + 1e-9 * fd.cwiseAbs().maxCoeff())
          << integrator << " " << S.parameter_names[k] << "\n"
          << (dual - fd).transpose() << "\nFD's own error: " << (fd - fd2).cwiseAbs().maxCoeff();
      EXPECT_GT(dual.cwiseAbs().maxCoeff(), 1e-4)
          << "the parameter moves the bodies: " << S.parameter_names[k];
    }
  }
}

TEST(Sensitivities, TheDerivativeOfTheConservedAngularMomentumIsConservedToTheMethodsOrder) {
  // L_w = R Λ Rᵀ ω is conserved by the torque-free flow for every x(0), so along column j of the tangent
  // space δL(t) = δL(0): δL = δθ × L − I(δθ × ω) + I δω in world axes. RK4 keeps L to O(h⁴), and the
  // derivative of its error to the same order: halving h divides the defect by ~16.
  Model model;
  model.add_body(handle());
  SystemState s0;
  s0.bodies.push_back(handle_state(model.bodies[0]));
  auto dL = [&](const BodyState& s, const Eigen::MatrixXd& stm) {
    const Mat3 R = s.R();
    const Mat3 I = R * model.bodies[0].Lambda().asDiagonal() * R.transpose();
    const Vec3 L = I * s.omega_w;
    Eigen::Matrix<double, 3, 12> G = Eigen::Matrix<double, 3, 12>::Zero();
    G.block<3, 3>(0, 3) = -skew(L) + I * skew(s.omega_w);  // δθ × L − I(δθ × ω) = (−[L]× + I[ω]×) δθ
    G.block<3, 3>(0, 9) = I;
    return Eigen::Matrix<double, 3, 12>(G * stm);
  };
  const Eigen::Matrix<double, 3, 12> dL0 = dL(s0.bodies[0], Eigen::MatrixXd::Identity(12, 12));
  double defect[2];
  for (int r = 0; r < 2; ++r) {
    const RunSettings settings = run("rk4", 2.0, r == 0 ? 4e-3 : 2e-3);
    SystemState end;
    const Sensitivities S = at_end(model, s0, settings, SensitivityParameters::inertia, &end);
    defect[r] = (dL(end.bodies[0], S.stm) - dL0).cwiseAbs().maxCoeff();
  }
  EXPECT_LT(defect[1], 1e-6 * dL0.cwiseAbs().maxCoeff());
  EXPECT_GT(defect[0] / defect[1], 12.0) << defect[0] << " " << defect[1];  // 2⁴ = 16 for order 4
  EXPECT_LT(defect[0] / defect[1], 20.0) << defect[0] << " " << defect[1];
}

TEST(Sensitivities, TheExactFlowsMethodsKeepTheInvariantsDerivativesToRounding) {
  // Without torque L_w and 2E = ω·Iω are the same function of x(0) at every t, so ∂L_w(t)/∂x(0) =
  // ∂L_w(0)/∂x(0) and ∂E(t)/∂x(0) = ∂E(0)/∂x(0) (and the same for ∂/∂I_k). splitting, splitting4 and
  // exact evaluate the torque-free flow itself, whose drift is a rotation of L_w, not an approximation:
  // they keep both derivatives to rounding (~1e-16 a step of derivatives ~10: 1e-11 over 500 steps),
  // where RK4 keeps them to its order (the test above). The handle tumbles near its separatrix and its
  // STM grows to ~7 in the second: the invariants' derivatives staying put is not that of a small STM.
  Model model;
  model.add_body(handle());
  model.add_force<UniformGravity>(Vec3(0, 0, -9.81));  // no torque about the centre of mass
  SystemState s0;
  s0.bodies.push_back(handle_state(model.bodies[0]));
  const Vec3 Lambda = model.bodies[0].Lambda();
  // δL and δ(2E) of a tangent column at state s, in world axes (δL = δθ × L − I(δθ × ω) + I δω, δ(2E) =
  // 2ω·δL − ω·(δθ × L − I(δθ × ω))), and of a moment's column (∂I = R e_k e_kᵀ Rᵀ).
  auto invariants = [&](const BodyState& s, const Eigen::MatrixXd& stm, const Eigen::MatrixXd& dI) {
    const Mat3 R = s.R();
    const Mat3 I = R * Lambda.asDiagonal() * R.transpose();
    const Vec3 L = I * s.omega_w;
    Eigen::Matrix<double, 4, 12> G = Eigen::Matrix<double, 4, 12>::Zero();
    const Mat3 dL_dtheta = -skew(L) + I * skew(s.omega_w);
    G.block<3, 3>(0, 3) = dL_dtheta;
    G.block<3, 3>(0, 9) = I;
    // 2E = ω·L: δ(2E) = δω·L + ω·δL = L·δω + ω·(dL_dθ δθ + I δω).
    G.block<1, 3>(3, 3) = s.omega_w.transpose() * dL_dtheta;
    G.block<1, 3>(3, 9) = L.transpose() + s.omega_w.transpose() * I;
    Eigen::Matrix<double, 4, 15> out;
    out.leftCols<12>() = G * stm;
    out.rightCols<3>() = G * dI;
    for (int k = 0; k < 3; ++k) {  // the moment's own part: ∂I ω and ω·∂I ω
      const Vec3 e = R.col(k);
      out.block<3, 1>(0, 12 + k) += e * e.dot(s.omega_w);
      out(3, 12 + k) += e.dot(s.omega_w) * e.dot(s.omega_w);
    }
    return out;
  };
  const Eigen::Matrix<double, 4, 15> at_start =
      invariants(s0.bodies[0], Eigen::MatrixXd::Identity(12, 12), Eigen::MatrixXd::Zero(12, 3));
  for (const std::string integrator : {"splitting", "splitting4", "exact"}) {
    SystemState end;
    const Sensitivities S =
        at_end(model, s0, run(integrator, 1.0, 2e-3), SensitivityParameters::inertia, &end);
    const Eigen::Matrix<double, 4, 15> at_end_ = invariants(end.bodies[0], S.stm, S.parameters);
    EXPECT_LT((at_end_ - at_start).cwiseAbs().maxCoeff(), 1e-11 * (1 + at_start.cwiseAbs().maxCoeff()))
        << integrator << "\n"
        << at_end_ - at_start;
    EXPECT_GT(S.stm.cwiseAbs().maxCoeff(), 5.0) << integrator;
  }
}

TEST(Sensitivities, TheValuesAreTheRunsOwnStates) {
  Model model;
  model.add_body(handle());
  model.add_force<UniformGravity>(Vec3(0, 0, -9.81));
  SystemState s0;
  s0.bodies.push_back(handle_state(model.bodies[0]));
  for (const std::string& integrator : differentiating_integrators()) {
    RunSettings settings = run(integrator, 0.3, 1e-2);
    settings.output_interval = 0.025;  // samples between steps: the step before each is shortened
    std::vector<SystemState> primal, dual;
    (void)simulate(model, s0, settings, [&](const SystemState& s) {
      primal.push_back(s);
      return true;
    });
    (void)simulate_sensitivities(model, s0, settings, SensitivityParameters::inertia,
                                 [&](const SystemState& s, const Sensitivities& S) {
                                   dual.push_back(s);
                                   if (dual.size() == 1) {
                                     EXPECT_EQ(S.stm, Eigen::MatrixXd::Identity(12, 12));
                                     EXPECT_EQ(S.parameters, Eigen::MatrixXd::Zero(12, 3));
                                   }
                                   return true;
                                 });
    ASSERT_EQ(primal.size(), dual.size()) << integrator;
    // implicit_gyro solves a 3 × 3 system by Eigen's LU, which on double runs SIMD packets (another order
    // of roundings than on dual numbers); midpoint iterates until its derivatives have converged too, a
    // few iterations past where the values stop, each free to move a value by an ulp. Both agree to
    // rounding, ~1e-16 relative per step: 1e-13 over these 30 steps.
    const double tolerance = integrator == "implicit_gyro" || integrator == "midpoint" ||
                                     integrator == "dopri45" || integrator == "splitting" ||
                                     integrator == "splitting4"
                                 ? 1e-13
                                 : 0.0;
    for (size_t k = 0; k < primal.size(); ++k) {
      const BodyState &a = primal[k].bodies[0], &b = dual[k].bodies[0];
      EXPECT_EQ(primal[k].t, dual[k].t) << integrator << " sample " << k;
      EXPECT_LE((a.o - b.o).cwiseAbs().maxCoeff(), tolerance) << integrator << " sample " << k;
      EXPECT_LE((a.q.coeffs() - b.q.coeffs()).cwiseAbs().maxCoeff(), tolerance)
          << integrator << " sample " << k;
      EXPECT_LE((a.v - b.v).cwiseAbs().maxCoeff(), tolerance) << integrator << " sample " << k;
      EXPECT_LE((a.omega_w - b.omega_w).cwiseAbs().maxCoeff(), tolerance * 10)
          << integrator << " sample " << k;
    }
  }
}

TEST(Sensitivities, BodiesApartGiveBlocksAndASpringCouplesThem) {
  Model model;
  model.add_body(handle());
  model.add_body(RigidBody::from_principal_moments(1.0, Vec3(0.01, 0.02, 0.025), "box"));
  SystemState s0;
  s0.bodies.push_back(handle_state(model.bodies[0]));
  s0.bodies.push_back(BodyState{Vec3(1.0, 0.0, 1.0), Quat::Identity(), Vec3(0, 0.5, 0), Vec3(3.0, 0.1, 0.2)});
  const RunSettings settings = run("rk4", 0.4, 2e-3);
  const Sensitivities apart = at_end(model, s0, settings);
  EXPECT_FALSE(apart.coupled);
  EXPECT_EQ(apart.stm.cols(), 12);  // each body's own block only: no 24 × 24
  Model alone;
  alone.add_body(model.bodies[1]);
  SystemState s1;
  s1.bodies.push_back(s0.bodies[1]);
  // Body 1's block is what it is alone, bit for bit: a body's derivatives do not depend on its company.
  EXPECT_EQ(apart.stm.block(12, 0, 12, 12), at_end(alone, s1, settings).stm);

  model.add_force<Spring>(Spring::End{0, Vec3(0.1, 0, 0)}, Spring::End{1, Vec3(0, 0.05, 0)}, 40.0, 0.5, 0.3);
  const Sensitivities joined = at_end(model, s0, settings);
  EXPECT_TRUE(joined.coupled);
  ASSERT_EQ(joined.stm.cols(), 24);
  const Eigen::MatrixXd fd = stm_by_central_differences(model, s0, settings, 1e-6);
  EXPECT_LT((joined.stm - fd).cwiseAbs().maxCoeff(), 1e-6) << "\n" << joined.stm - fd;
  EXPECT_GT(joined.stm.block(0, 12, 12, 12).cwiseAbs().maxCoeff(), 1e-3) << "the spring couples them";
  EXPECT_EQ(joined.dense_parameters().cols(), 6);
}

TEST(Sensitivities, RefusesWhatItCannotDifferentiate) {
  Model model;
  model.add_body(handle());
  SystemState s0;
  s0.bodies.push_back(handle_state(model.bodies[0]));
  RunSettings settings = run("rk4", 0.1, 1e-3);
  const std::vector<std::string> differentiating = differentiating_integrators();
  for (const std::string& integrator : integrator_names()) {
    settings.integrator = integrator;
    const bool differentiates = std::find(differentiating.begin(), differentiating.end(), integrator) !=
                                differentiating.end();
    if (differentiates) {
      EXPECT_NO_THROW((void)at_end(model, s0, settings)) << integrator;
    } else {
      EXPECT_THROW((void)at_end(model, s0, settings), InvalidArgument) << integrator;
    }
  }
  settings.integrator = "rk4";
  model.add_force<BodyCallback>(
      0, [](double, const RigidBody&, const BodyState&) { return Wrench{}; }, "my thruster law");
  try {
    (void)at_end(model, s0, settings);
    FAIL() << "a callback cannot be differentiated";
  } catch (const InvalidArgument& e) {
    EXPECT_NE(std::string(e.what()).find("my thruster law"), std::string::npos) << e.what();
  }
  EXPECT_THROW((void)parse_sensitivity_parameters("moments"), InvalidArgument);
}

}  // namespace
}  // namespace tumble
