// Each force model against a closed form or a conservation law.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "../support/random.hpp"
#include "../support/sim_helpers.hpp"
#include "tumble/dynamics/quantities.hpp"
#include "tumble/error.hpp"
#include "tumble/forces/forces.hpp"
#include "tumble/sim/diagnostics.hpp"

namespace tumble {
namespace {

RigidBody ball(double m = 2.0, double I = 0.1) {
  return RigidBody::from_principal_moments(m, Vec3(I, I, I), "ball");
}

TEST(Forces, ViscousDampingDecaysExponentially) {
  // m v̇ = −c v ⇒ v = v₀ e^{−ct/m}; for an isotropic body I ω̇ = −c_ω ω ⇒ ω = ω₀ e^{−c_ω t/I}.
  Model model;
  model.add_body(ball());
  model.add_force<ViscousDamping>(all_bodies, 0.5, 0.02);
  const BodyState s0{Vec3::Zero(), Quat::Identity(), Vec3(3, -1, 2), Vec3(1, 2, -4)};
  const double T = 2.0;
  const BodyState s = test::run(model, test::single(s0), T, 1e-3, "rk4").bodies[0];
  // RK4 on a linear ODE with rate 0.25/s and 0.2/s: relative error ~ (h·rate)⁴ t ≈ 1e-14.
  EXPECT_LT((s.v - s0.v * std::exp(-0.5 * T / 2.0)).norm(), 1e-12);
  EXPECT_LT((s.omega_w - s0.omega_w * std::exp(-0.02 * T / 0.1)).norm(), 1e-12);
  // Position: o = v₀ m/c (1 − e^{−ct/m}).
  EXPECT_LT((s.o - s0.v * (2.0 / 0.5) * (1 - std::exp(-0.5 * T / 2.0))).norm(), 1e-12);
}

TEST(Forces, QuadraticDragSlowsAsOneOverTime) {
  // m v̇ = −k |v| v along a fixed direction ⇒ v = v₀ / (1 + k v₀ t / m).
  Model model;
  model.add_body(ball());
  model.add_force<QuadraticDrag>(0, 0.3, 0.0);
  const Vec3 dir = Vec3(1, 2, 2).normalized();
  const double v0 = 10.0, T = 3.0;
  const BodyState s =
      test::run(model, test::single({Vec3::Zero(), Quat::Identity(), v0 * dir, Vec3::Zero()}), T, 1e-3, "rk4")
          .bodies[0];
  const double v = v0 / (1 + 0.3 * v0 * T / 2.0);
  // Rates up to k v₀/m = 1.5/s at h = 1e-3: RK4 relative error ≲ 1e-12.
  EXPECT_NEAR(s.v.norm(), v, 1e-11 * v0);
  EXPECT_LT((s.v.normalized() - dir).norm(), 1e-14);
  // Distance travelled: (m/k) ln(1 + k v₀ t/m).
  EXPECT_NEAR(s.o.norm(), 2.0 / 0.3 * std::log(1 + 0.3 * v0 * T / 2.0), 1e-11);
}

TEST(Forces, DampedSpringToAnAnchorFollowsTheOscillatorSolution) {
  // Spring from the centre of mass to a world anchor, along x: m ẍ = −k x − c ẋ, x(0) = A, ẋ(0) = 0:
  // x = A e^{−ζω₀t}(cos ω_d t + ζω₀/ω_d sin ω_d t).
  const double m = 2.0, k = 50.0, c = 1.0, A = 0.2;
  Model model;
  model.add_body(ball(m));
  const Vec3 anchor(1, 2, 3);
  model.add_force<Spring>(Spring::End{0, Vec3::Zero()}, Spring::End{all_bodies, anchor}, k, 0.0, c);
  const BodyState s0{anchor + Vec3(A, 0, 0), Quat::Identity(), Vec3::Zero(), Vec3::Zero()};
  const double T = 3.0;
  const BodyState s = test::run(model, test::single(s0), T, 1e-3, "rk4").bodies[0];
  const double w0 = std::sqrt(k / m), zeta = c / (2 * std::sqrt(k * m)), wd = w0 * std::sqrt(1 - zeta * zeta);
  const double x = A * std::exp(-zeta * w0 * T) * (std::cos(wd * T) + zeta * w0 / wd * std::sin(wd * T));
  // ω₀h = 5e-3: RK4 phase error ~ (ω₀h)⁴ ω₀T ≈ 1e-8 relative.
  EXPECT_NEAR(s.o.x() - anchor.x(), x, 1e-9);
  EXPECT_NEAR(s.o.y(), anchor.y(), 1e-15);
}

TEST(Forces, SpringBetweenTwoTumblingBodiesConservesMomentaAndEnergy) {
  Model model;
  model.add_body(RigidBody::from_principal_moments(1.0, Vec3(0.02, 0.03, 0.04), "a"));
  model.add_body(RigidBody::from_principal_moments(1.5, Vec3(0.05, 0.06, 0.09), "b"));
  model.add_force<Spring>(Spring::End{0, Vec3(0.1, 0.0, 0.05)}, Spring::End{1, Vec3(-0.05, 0.1, 0.0)}, 20.0,
                          0.5, 0.0);
  const SystemState s0{0.0,
                       {BodyState{Vec3(0, 0, 0), Quat::Identity(), Vec3(0.1, 0, 0), Vec3(1, 2, 3)},
                        BodyState{Vec3(1, 0.2, 0), Quat(Eigen::AngleAxisd(1.0, Vec3::UnitZ())),
                                  Vec3(-0.2, 0.1, 0), Vec3(-2, 0, 1)}},
                       {}};
  const Invariants a = invariants(model, s0);
  const Invariants b = invariants(model, test::run(model, s0, 5.0, 5e-4, "rk4"));
  // Internal forces: Σp and Σl are conserved exactly by the equations; RK4 error (h|ω|)⁴·t ≈ 1e-11.
  EXPECT_LT((b.linear_momentum - a.linear_momentum).norm(), 1e-12);
  EXPECT_LT((b.angular_momentum - a.angular_momentum).norm(), 1e-9);
  EXPECT_NEAR(*b.total_energy(), *a.total_energy(), 1e-9 * *a.total_energy());
}

TEST(Forces, PointForcesAndTorquesInEachFrame) {
  const RigidBody body = RigidBody::from_mass_properties(
      MassProperties{1.0, Vec3(0.1, 0, 0), Vec3(0.1, 0.2, 0.25).asDiagonal(), 0}, "part");
  const Quat q(Eigen::AngleAxisd(std::numbers::pi / 2, Vec3::UnitZ()));  // reference x → world y
  const BodyState s = state_from_reference(body, Vec3(1, 0, 0), q, Vec3::Zero(), Vec3::Zero());
  // o = p + R c = (1, 0.1, 0).
  EXPECT_LT((s.o - Vec3(1, 0.1, 0)).norm(), 1e-15);
  Model model;
  model.add_body(body);
  const SystemState x{0.0, {s}, {}};
  auto loads_of = [&](auto&& force) {
    Loads l;
    l.reset(1, 0);
    force.accumulate(model.view(x), l);
    return l.bodies[0];
  };
  // Body-frame force (1,0,0) at the body point (0.1, 0.2, 0): in world, f = (0,1,0) at (0.8, 0.1, 0).
  const Wrench w1 = loads_of(PointForce(0, Vec3(1, 0, 0), Frame::body, Vec3(0.1, 0.2, 0), Frame::body));
  EXPECT_LT((w1.force - Vec3(0, 1, 0)).norm(), 1e-15);
  EXPECT_LT((w1.torque - Vec3(-0.2, 0, 0).cross(Vec3(0, 1, 0))).norm(), 1e-15);
  // World force at a world point: τ = (x − o) × f.
  const Wrench w2 = loads_of(PointForce(0, Vec3(0, 0, 2), Frame::world, Vec3(2, 0.1, 0), Frame::world));
  EXPECT_LT((w2.torque - Vec3(1, 0, 0).cross(Vec3(0, 0, 2))).norm(), 1e-15);
  // A body-frame couple rotates with the body.
  const Wrench w3 = loads_of(PureTorque(0, Vec3(1, 0, 0), Frame::body));
  EXPECT_LT((w3.torque - Vec3(0, 1, 0)).norm(), 1e-15);
  EXPECT_EQ(w3.force, Vec3::Zero());
}

TEST(Forces, GravityGradientTorqueMatchesTheClosedFormAndConservesEnergy) {
  const double mu = 3.986004418e14;        // Earth, m³/s²
  const Vec3 Lambda(100.0, 200.0, 250.0);  // kg·m², a small satellite
  const RigidBody sat = RigidBody::from_principal_moments(500.0, Lambda, "sat");
  test::Random rng(31);
  const Vec3 r(7.0e6, 1.0e6, -0.5e6);
  const BodyState s{r, Quat(rng.rotation()), Vec3(0, 7.5e3, 0), Vec3(0.001, -0.002, 0.0015)};
  Model model;
  model.add_body(sat);
  model.add_force<GravityGradient>(mu, Vec3::Zero());
  const Loads loads = evaluate_loads(model, test::single(s));
  const Vec3 u = r.normalized();
  const Mat3 I = inertia_world(sat, s);
  const Vec3 tau = 3 * mu / std::pow(r.norm(), 3) * u.cross(I * u);  // 3μ/R³ R̂ × (I R̂)
  EXPECT_LT((loads.bodies[0].torque - tau).norm(), 1e-13 * tau.norm());
  // The pull is the point-mass one up to the I/(m r²) ~ 1e-14 correction.
  EXPECT_LT((loads.bodies[0].force + mu * 500.0 / r.squaredNorm() * u).norm(),
            1e-12 * mu * 500.0 / r.squaredNorm());
  // A principal axis along r̂ feels no torque.
  BodyState aligned = s;
  aligned.q = Quat::FromTwoVectors(Vec3::UnitX(), u);
  EXPECT_LT(evaluate_loads(model, test::single(aligned)).bodies[0].torque.norm(), 1e-12 * tau.norm());
  // Energy (orbital + attitude + gradient potential) is conserved over a tenth of an orbit.
  const Invariants a = invariants(model, test::single(s));
  const Invariants b = invariants(model, test::run(model, test::single(s), 600.0, 0.5, "rk4"));
  // RK4 at h = 0.5 s on a 5900 s orbit: relative energy error ~ (h n)⁴ ≈ 1e-14 per unit of phase.
  EXPECT_NEAR(*b.total_energy(), *a.total_energy(), 1e-11 * std::abs(*a.total_energy()));
}

TEST(Forces, ForceModelsNameWhatIsWrong) {
  Model model;
  model.add_body(ball());
  model.add_force<PureTorque>(3, Vec3(1, 0, 0), Frame::world);
  try {
    evaluate_loads(model, test::single(BodyState{}));
    FAIL();
  } catch (const InvalidArgument& e) {
    EXPECT_NE(std::string(e.what()).find("torque refers to body #3, but the model has 1 bodies"),
              std::string::npos);
  }
  EXPECT_THROW(model.body_index("nope"), InvalidArgument);
  EXPECT_EQ(model.body_index("ball"), 0u);
}

}  // namespace
}  // namespace tumble
