// The orbit frame LVLH (dynamics/orbit_frame.hpp) and the output fields relative to it
// (sim/output_fields.hpp): checked against
//  - its definition built by hand on an orbit whose axes are known (circular, in the xy-plane);
//  - the frame's own motion along a Kepler ellipse: central differences of R_lvlh(t) give its angular
//    velocity, which must be (r × v)/|r|² (the plane does not turn under central gravity);
//  - the physics of gravity-gradient equilibrium: a satellite whose principal axes are aligned with
//    LVLH and which turns at the orbital rate stays aligned, so its `_lvlh` fields stay zero through a
//    whole orbit of a run, while its world attitude turns by 2π.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "../support/random.hpp"
#include "tumble/dynamics/orbit_frame.hpp"
#include "tumble/error.hpp"
#include "tumble/forces/forces.hpp"
#include "tumble/sim/output_fields.hpp"
#include "tumble/sim/simulate.hpp"

namespace tumble {
namespace {

constexpr double pi = std::numbers::pi;

TEST(OrbitFrame, IsNadirAndAntiNormalBuiltByHand) {
  // r along x, v along y: the orbit normal is +z, so ŷ = −z, ẑ = −x and x̂ = ŷ × ẑ = +y (along v).
  const Mat3 R = lvlh_orientation(Vec3(7e6, 0.0, 0.0), Vec3(0.0, 7.5e3, 0.0))->toRotationMatrix();
  Mat3 expected;
  expected.col(0) = Vec3::UnitY();
  expected.col(1) = -Vec3::UnitZ();
  expected.col(2) = -Vec3::UnitX();
  EXPECT_LT((R - expected).cwiseAbs().maxCoeff(), 1e-15);
  // No orbit plane: at rest, along the radius, at the centre.
  EXPECT_FALSE(lvlh_orientation(Vec3(7e6, 0, 0), Vec3::Zero()));
  EXPECT_FALSE(lvlh_orientation(Vec3(7e6, 0, 0), Vec3(-3.0, 0, 0)));
  EXPECT_FALSE(lvlh_orientation(Vec3::Zero(), Vec3(0, 1, 0)));
}

/// Position and velocity on a Kepler ellipse (semi-major axis a, eccentricity e, μ) at time t from
/// periapsis, in its plane turned by `tilt` (Kepler's equation solved by Newton's method to rounding).
std::pair<Vec3, Vec3> kepler(double a, double e, double mu, double t, const Mat3& tilt) {
  const double n = std::sqrt(mu / (a * a * a)), M = n * t;
  double E = M;
  for (int k = 0; k < 50; ++k) E -= (E - e * std::sin(E) - M) / (1 - e * std::cos(E));
  const double b = a * std::sqrt(1 - e * e), E_dot = n / (1 - e * std::cos(E));
  const Vec3 r(a * (std::cos(E) - e), b * std::sin(E), 0.0);
  const Vec3 v(-a * std::sin(E) * E_dot, b * std::cos(E) * E_dot, 0.0);
  return {tilt * r, tilt * v};
}

TEST(OrbitFrame, TurnsAtTheRateOfItsAngularVelocityAlongAKeplerEllipse) {
  const double mu = 3.986e14, a = 8e6, e = 0.3;
  const Mat3 tilt = Eigen::AngleAxisd(0.9, Vec3(1.0, 0.2, 0.0).normalized()).toRotationMatrix();
  const double eps = 1e-2;  // s; the difference's error ~ ε² |Ω⃛|/6 ≈ 1e-13 rad/s at this orbit's rates
  for (double t = 0.0; t < 7000.0; t += 350.0) {
    const auto [r, v] = kepler(a, e, mu, t, tilt);
    const auto [r1, v1] = kepler(a, e, mu, t + eps, tilt);
    const auto [r0, v0] = kepler(a, e, mu, t - eps, tilt);
    const Quat q1 = *lvlh_orientation(r1, v1), q0 = *lvlh_orientation(r0, v0);
    // R(t+ε) R(t−ε)ᵀ = exp(2ε [Ω]×) + O(ε³): Ω in world axes.
    const Vec3 Omega = quat_log(q1 * q0.conjugate()) / (2 * eps);
    const Vec3 expected = lvlh_angular_velocity(r, v);
    EXPECT_LT((Omega - expected).norm(), 1e-9 * expected.norm()) << t;
  }
}

TEST(OrbitFrame, AGravityGradientEquilibriumStaysAtZeroInTheOrbitFrame) {
  // A satellite on a circular orbit of 7000 km, principal axes along LVLH (λ₁ along x̂, the velocity;
  // λ₂ along ŷ, the anti-normal; λ₃ along ẑ, nadir) and turning with it at n about the orbit normal:
  // the gravity-gradient torque 3n² r̂ × (I r̂) vanishes, so the attitude stays aligned with LVLH.
  const double mu = 3.986004418e14, R = 7.0e6, n = std::sqrt(mu / (R * R * R));
  Model model;
  model.add_body(RigidBody::from_principal_moments(500.0, Vec3(200.0, 300.0, 350.0), "sat"));
  model.add_force<GravityGradient>(mu, Vec3::Zero());
  const Vec3 r(R, 0.0, 0.0), v(0.0, n * R, 0.0);
  BodyState s;
  s.o = r;
  s.v = v;
  s.q = *lvlh_orientation(r, v);  // principal = reference axes here (from_principal_moments)
  s.omega_w = lvlh_angular_velocity(r, v);
  RunSettings settings;
  settings.integrator = "rk4";
  settings.timestep = 1.0;
  settings.duration = 2 * pi / n;  // one orbit, ~97 min
  settings.output_interval = settings.duration / 8;
  const std::vector<const BodyField*> fields =
      body_fields({"euler_zyx_lvlh", "mrp_lvlh", "angular_velocity_lvlh", "euler_zyx"}, model);
  double worst_angle = 0.0, worst_rate = 0.0, yaw_turn = 0.0;
  (void)simulate(model, SystemState{0.0, {s}, {}}, settings, [&](const SystemState& x) {
    double out[12];
    fields_of_row(fields, model, x, 0, out);
    for (int k = 0; k < 6; ++k) worst_angle = std::max(worst_angle, std::abs(out[k]));
    for (int k = 6; k < 9; ++k) worst_rate = std::max(worst_rate, std::abs(out[k]));
    yaw_turn = std::max(yaw_turn, std::abs(out[9] - pi / 2));  // the world attitude does turn
    return true;
  });
  // rk4 at h = 1 s on an orbit of 5830 s: the orbit's own phase error is ~(nh)⁴ n t ≈ 1e-12 rad; the
  // equilibrium is unstable about one axis (λ₂ < λ₃ along the normal and nadir) and grows a rounding
  // seed by e^(√3 n t) ~ 1e5 at most: 1e-9 rad and 1e-12 rad/s bound both by far.
  EXPECT_LT(worst_angle, 1e-9);
  EXPECT_LT(worst_rate, 1e-12);
  EXPECT_GT(yaw_turn, 3.0);  // yaw swept the circle: the test watched a moving frame
}

TEST(OrbitFrame, FieldsRelativeToItNeedACentralBody) {
  Model model;
  model.add_body(RigidBody::from_principal_moments(1.0, Vec3(1, 2, 3), "box"));
  EXPECT_THROW((void)body_fields({"mrp_lvlh"}, model), InvalidArgument);
  EXPECT_NO_THROW((void)body_fields({"mrp"}, model));
  model.add_force<GravityGradient>(3.986e14, Vec3::Zero());
  EXPECT_NO_THROW((void)body_fields({"mrp_lvlh"}, model));
  model.add_force<GravityGradient>(3.986e14, Vec3(1.0, 0.0, 0.0));  // a second, elsewhere
  EXPECT_THROW((void)central_body(model), InvalidArgument);
  // A state on the radial line has no orbit plane: the field names the body and the time.
  SystemState x{2.5, {BodyState{}}, {}};
  x.bodies[0].o = Vec3(7e6, 0, 0);
  x.bodies[0].v = Vec3(10.0, 0, 0);
  model.forces.pop_back();
  double out[3];
  try {
    field_of_row(*body_fields({"mrp_lvlh"}, model)[0], model, x, 0, out);
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("'box' has no orbit frame at t = 2.5 s"), std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace tumble

namespace tumble {
namespace {

TEST(OrbitFrame, OrbitalElementsGiveTheStateTheirIntegralsDescribe) {
  // Independent of the perifocal construction: the vis-viva energy v²/2 − μ/r = −μ/(2a), the angular
  // momentum |r × v| = √(μ a (1 − e²)) along Rz(Ω) Rx(i) ẑ, the eccentricity vector (v × h)/μ − r̂ of
  // length e toward the periapsis Rz(Ω) Rx(i) Rz(ω) x̂, and r = a(1 − e²)/(1 + e cos ν).
  const double mu = 3.986004418e14;
  test::Random rng(17);
  for (int k = 0; k < 200; ++k) {
    OrbitalElements el;
    el.a = rng.uniform(6.6e6, 4.2e7);
    el.e = rng.uniform(0.0, 0.9);
    el.i = rng.uniform(0.0, pi);
    el.raan = rng.uniform(-pi, pi);
    el.argp = rng.uniform(-pi, pi);
    el.nu = rng.uniform(-pi, pi);
    const auto [r, v] = orbit_state(mu, el);
    const Vec3 h = r.cross(v);
    const Mat3 plane = (Eigen::AngleAxisd(el.raan, Vec3::UnitZ()) * Eigen::AngleAxisd(el.i, Vec3::UnitX()))
                           .toRotationMatrix();
    const Vec3 periapsis = plane * Eigen::AngleAxisd(el.argp, Vec3::UnitZ()).toRotationMatrix() *
                           Vec3::UnitX();
    const Vec3 e_vec = v.cross(h) / mu - r.normalized();
    // Each is a few roundings of quantities of their own size: 1e-13 relative bounds them.
    EXPECT_NEAR((v.squaredNorm() / 2 - mu / r.norm()) / (mu / (2 * el.a)), -1.0, 1e-13) << k;
    EXPECT_NEAR(h.norm() / std::sqrt(mu * el.a * (1 - el.e * el.e)), 1.0, 1e-13) << k;
    EXPECT_LT((h.normalized() - plane * Vec3::UnitZ()).norm(), 1e-13) << k;
    EXPECT_LT((e_vec - el.e * periapsis).norm(), 1e-13) << k;
    EXPECT_NEAR(r.norm() * (1 + el.e * std::cos(el.nu)) / (el.a * (1 - el.e * el.e)), 1.0, 1e-14) << k;
  }
}

}  // namespace
}  // namespace tumble
