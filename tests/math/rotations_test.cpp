// Euler angles (ZYX and 3-1-3) and axis–angle (math/rotations.hpp): they reproduce the rotation they
// came from, lie in their documented ranges, and resolve gimbal lock as documented.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <optional>

#include "../support/random.hpp"
#include "tumble/math/rotations.hpp"

namespace tumble {
namespace {

constexpr double pi = std::numbers::pi;
// Rebuilding R from its angles multiplies three rotations (each entry a rounded sum of products), and
// the angles carry the rounding of the input's entries through atan2, amplified near gimbal lock by
// 1/cos(pitch): measured ≤ 4.3e-15 over 2000 random rotations. 1e-14 (45 ulp) bounds that; a wrong
// convention or range is off by O(1).
constexpr double kRebuilt = 1e-14;

TEST(Rotations, EulerAnglesRebuildTheRotationAndLieInTheirRanges) {
  test::Random rng(3);
  for (int k = 0; k < 2000; ++k) {
    const Mat3 R = rng.rotation();
    const Vec3 zyx = euler_zyx(R);
    EXPECT_LT(test::rel_diff(from_euler_zyx(zyx), R), kRebuilt) << k;
    EXPECT_GT(zyx.x(), -pi);
    EXPECT_LE(zyx.x(), pi);
    EXPECT_GE(zyx.y(), -pi / 2);
    EXPECT_LE(zyx.y(), pi / 2);
    EXPECT_GT(zyx.z(), -pi);
    EXPECT_LE(zyx.z(), pi);
    const Vec3 zxz = euler_zxz(R);
    EXPECT_LT(test::rel_diff(from_euler_zxz(zxz), R), kRebuilt) << k;
    EXPECT_GE(zxz.y(), 0.0);
    EXPECT_LE(zxz.y(), pi);
  }
}

TEST(Rotations, AnglesInsideTheRangesComeBackUnchanged) {
  // Away from gimbal lock the angles are well conditioned: each comes back to a few ulp of π.
  test::Random rng(5);
  for (int k = 0; k < 2000; ++k) {
    const Vec3 zyx(rng.uniform(-3.1, 3.1), rng.uniform(-1.5, 1.5), rng.uniform(-3.1, 3.1));
    EXPECT_LT((euler_zyx(from_euler_zyx(zyx)) - zyx).cwiseAbs().maxCoeff(), 1e-13) << k;
    const Vec3 zxz(rng.uniform(-3.1, 3.1), rng.uniform(0.05, 3.09), rng.uniform(-3.1, 3.1));
    EXPECT_LT((euler_zxz(from_euler_zxz(zxz)) - zxz).cwiseAbs().maxCoeff(), 1e-13) << k;
  }
  // The aerospace textbook case: yaw 30°, pitch 20°, roll 10° gives x_body along
  // (cos 30° cos 20°, sin 30° cos 20°, −sin 20°).
  const Mat3 R = from_euler_zyx(Vec3(pi / 6, pi / 9, pi / 18));
  EXPECT_NEAR(R(0, 0), std::cos(pi / 6) * std::cos(pi / 9), 1e-16);
  EXPECT_NEAR(R(1, 0), std::sin(pi / 6) * std::cos(pi / 9), 1e-16);
  EXPECT_NEAR(R(2, 0), -std::sin(pi / 9), 1e-16);
}

TEST(Rotations, GimbalLockPutsTheWholeTurnInTheFirstAngle) {
  // Exact matrices at pitch = ±π/2 (ZYX) and θ = 0, π (ZXZ), composed with a yaw of 0.7 rad.
  Mat3 up, down;
  up << 0, 0, 1, 0, 1, 0, -1, 0, 0;    // Ry(π/2)
  down << 0, 0, -1, 0, 1, 0, 1, 0, 0;  // Ry(−π/2)
  for (const Mat3& P : {up, down}) {
    const Mat3 R = rotation_z(0.7) * P;
    const Vec3 a = euler_zyx(R);
    EXPECT_EQ(a.z(), 0.0);
    EXPECT_NEAR(std::abs(a.y()), pi / 2, 1e-15);
    EXPECT_NEAR(a.x(), 0.7, 1e-15);
    EXPECT_LT(test::rel_diff(from_euler_zyx(a), R), kRebuilt);
  }
  Mat3 flip;
  flip << 1, 0, 0, 0, -1, 0, 0, 0, -1;  // Rx(π)
  for (const Mat3& P : {Mat3(Mat3::Identity()), flip}) {
    const Mat3 R = rotation_z(-2.5) * P;
    const Vec3 a = euler_zxz(R);
    EXPECT_EQ(a.z(), 0.0);
    EXPECT_NEAR(a.x(), -2.5, 1e-15);
    EXPECT_LT(test::rel_diff(from_euler_zxz(a), R), kRebuilt);
  }
}

// R rebuilt from double angles in long double (64-bit significand): a reference 2^11 finer than a
// double's rounding, so what it shows is the angles' error, not the rebuild's.
Eigen::Matrix<long double, 3, 3> rebuilt_long(int first, int second, int third, const Vec3& a) {
  const auto axis = [](int i, long double t) {
    Eigen::Matrix<long double, 3, 3> M = Eigen::Matrix<long double, 3, 3>::Identity();
    const int j = (i + 1) % 3, k = (i + 2) % 3;
    M(j, j) = M(k, k) = std::cos(t);
    M(k, j) = std::sin(t);
    M(j, k) = -M(k, j);
    return M;
  };
  return axis(first, static_cast<long double>(a.x())) * axis(second, static_cast<long double>(a.y())) *
         axis(third, static_cast<long double>(a.z()));
}

double largest_entry_error(const Eigen::Matrix<long double, 3, 3>& A, const Mat3& R) {
  return static_cast<double>((A - R.cast<long double>()).cwiseAbs().maxCoeff());
}

TEST(Rotations, ApproachingTheLockTheAnglesStillRebuildTheRotationToRounding) {
  // Rotations whose cos(pitch) (ZYX) or sin θ (ZXZ) is 1e-3 … 1e-16, given as unit quaternions, with
  // random outer angles. The rebuilt R must match the input to a few ulp: each angle, up to π, is
  // rounded by atan2 to ~1.6ε absolute, and the first one also carries the rounding of the two-term
  // sums it is taken from (~2ε), each moving entries of size 1 by as much: 8ε bounds the three (measured
  // 3–4ε). Taking yaw and roll each from entries of size cos(pitch) was off by ~ε / cos(pitch), 1e-4.
  constexpr double eps = std::numeric_limits<double>::epsilon();
  test::Random rng(11);
  double worst_zyx = 0, worst_zxz = 0;
  for (int k = 3; k <= 16; ++k) {
    const double delta = std::pow(10.0, -k);
    for (const double side : {1.0, -1.0}) {
      for (int n = 0; n < 50; ++n) {
        const double outer1 = rng.uniform(-3.1, 3.1), outer2 = rng.uniform(-3.1, 3.1);
        const Quat zyx = Quat(Eigen::AngleAxisd(outer1, Vec3::UnitZ())) *
                         Quat(Eigen::AngleAxisd(side * (pi / 2 - delta), Vec3::UnitY())) *
                         Quat(Eigen::AngleAxisd(outer2, Vec3::UnitX()));
        const Mat3 R = zyx.normalized().toRotationMatrix();
        worst_zyx = std::max(worst_zyx, largest_entry_error(rebuilt_long(2, 1, 0, euler_zyx(R)), R));
        const double theta = side > 0 ? delta : pi - delta;
        const Quat zxz = Quat(Eigen::AngleAxisd(outer1, Vec3::UnitZ())) *
                         Quat(Eigen::AngleAxisd(theta, Vec3::UnitX())) *
                         Quat(Eigen::AngleAxisd(outer2, Vec3::UnitZ()));
        const Mat3 S = zxz.normalized().toRotationMatrix();
        worst_zxz = std::max(worst_zxz, largest_entry_error(rebuilt_long(2, 0, 2, euler_zxz(S)), S));
      }
    }
  }
  EXPECT_LT(worst_zyx, 8 * eps);
  EXPECT_LT(worst_zxz, 8 * eps);
  RecordProperty("worst_zyx_in_eps", std::to_string(worst_zyx / eps));
  RecordProperty("worst_zxz_in_eps", std::to_string(worst_zxz / eps));
}

TEST(Rotations, AxisAngleOfEitherSignOfTheQuaternion) {
  test::Random rng(9);
  for (const double angle : {1e-12, 1e-6, 0.3, 2.0, pi - 1e-9, pi}) {
    const Vec3 axis = rng.vec(-1, 1).normalized();
    const Quat q(Eigen::AngleAxisd(angle, axis));
    for (const Quat& p : {q, Quat(-q.coeffs())}) {
      const AxisAngle a = axis_angle(p);
      // atan2(|vector part|, w) is accurate to ~1 ulp of the angle even for tiny angles.
      EXPECT_NEAR(a.angle, angle, 4e-16 * std::max(1.0, angle)) << angle;
      EXPECT_LT((a.axis - axis).norm(), 1e-15) << angle;
    }
  }
  const AxisAngle none = axis_angle(Quat::Identity());
  EXPECT_EQ(none.angle, 0.0);
  EXPECT_EQ(none.axis, Vec3::UnitX());
}

}  // namespace
}  // namespace tumble

namespace tumble {
namespace {

// MRPs: σ = tan(angle/4) axis, the principal set |σ| ≤ 1, and its shadow −σ/|σ|² for the same rotation.
// σ is one division from q: 1e-15 bounds its rounding; the rotations rebuilt from σ to kRebuilt, as
// the Euler angles (measured ≤ 1.7e-15). A wrong formula is off
// by O(1), a wrong set by 1/|σ|).
TEST(Rotations, ModifiedRodriguesParametersAreTheQuarterAngleTangentAlongTheAxis) {
  test::Random rng(11);
  for (int k = 0; k < 2000; ++k) {
    const Quat q(rng.rotation());
    const Vec3 sigma = mrp(q);
    const AxisAngle a = axis_angle(q);
    EXPECT_LE(sigma.norm(), 1.0 + 1e-15) << k;
    EXPECT_LT((sigma - std::tan(a.angle / 4) * a.axis).norm(), 1e-15) << k;
    EXPECT_LT(test::rel_diff(from_mrp(sigma).toRotationMatrix(), q.toRotationMatrix()), kRebuilt) << k;
    EXPECT_LT((mrp(Quat(-q.coeffs())) - sigma).norm(), 1e-16) << k;  // q and −q: one rotation, one set
    const Vec3 shadow = -sigma / sigma.squaredNorm();
    EXPECT_LT(test::rel_diff(from_mrp(shadow).toRotationMatrix(), q.toRotationMatrix()), kRebuilt) << k;
  }
  // 90° about z: σ = tan(π/8) ẑ = (√2 − 1) ẑ, to the rounding of sin, cos of π/4 and one division
  // (4 ulp of 0.41 = 2.2e-16).
  EXPECT_NEAR(mrp(Quat(Eigen::AngleAxisd(pi / 2, Vec3::UnitZ()))).z(), std::sqrt(2.0) - 1.0, 2.3e-16);
  EXPECT_EQ(mrp(Quat::Identity()), Vec3::Zero());
}

TEST(Rotations, ModifiedRodriguesParametersSwitchToTheShadowSetThroughHalfATurn) {
  // A turn about a fixed axis: σ = tan(θ/4) a grows to the unit sphere at θ = π, then continues as the
  // shadow set −tan((2π − θ)/4) a = −a / tan(θ/4): the antipode, shrinking back to 0 at θ = 2π.
  const Vec3 axis = Vec3(1.0, -2.0, 0.5).normalized();
  for (double theta = 0.05; theta < 2 * pi; theta += 0.05) {
    const Vec3 sigma = mrp(Quat(Eigen::AngleAxisd(theta, axis)));
    const double expected = theta <= pi ? std::tan(theta / 4) : -std::tan((2 * pi - theta) / 4);
    EXPECT_LT((sigma - expected * axis).norm(), 1e-15) << theta;
  }
  const Vec3 before = mrp(Quat(Eigen::AngleAxisd(pi - 1e-9, axis)));
  const Vec3 after = mrp(Quat(Eigen::AngleAxisd(pi + 1e-9, axis)));
  EXPECT_NEAR(before.norm(), 1.0, 1e-9);
  EXPECT_NEAR((before + after).norm(), 0.0, 1e-9);  // the jump to the antipode
}

// CRPs: g = tan(angle/2) axis = q_v/q_w, one division (1e-15 relative bounds its rounding, and tan's
// of the reference), the same for q and −q; none at a half turn.
TEST(Rotations, ClassicalRodriguesParametersAreTheHalfAngleTangentAlongTheAxis) {
  test::Random rng(12);
  for (int k = 0; k < 2000; ++k) {
    const Quat q(rng.rotation());
    const std::optional<Vec3> g = crp(q);
    ASSERT_TRUE(g) << k;
    const AxisAngle a = axis_angle(q);
    const Vec3 expected = std::tan(a.angle / 2) * a.axis;
    // tan near π/2 amplifies the rounding of the angle: relative to |g|(1 + |g|²).
    EXPECT_LT((*g - expected).norm(), 1e-15 * (1.0 + g->squaredNorm()) * std::max(1.0, g->norm())) << k;
    EXPECT_EQ(*crp(Quat(-q.coeffs())), *g) << k;  // q and −q: one rotation, one g
    // g = 2σ/(1 − |σ|²) (both tangents of the same angle, at half and quarter)
    const Vec3 sigma = mrp(q);
    EXPECT_LT((*g - 2.0 * sigma / (1.0 - sigma.squaredNorm())).norm(), 1e-14 * (1.0 + g->squaredNorm())) << k;
  }
  EXPECT_FALSE(crp(Quat(0.0, 1.0, 0.0, 0.0)));                                          // a half turn about x
  EXPECT_NEAR(crp(Quat(Eigen::AngleAxisd(pi / 2, Vec3::UnitZ())))->z(), 1.0, 2.3e-16);  // tan(π/4)
}

}  // namespace
}  // namespace tumble
