// The quaternion products the equations use in place of Eigen's (math/quaternion.hpp): the product with
// a pure quaternion leaves out only terms that are exactly zero, and rotate is Eigen's q * v written
// out, so both must equal what they replace bit for bit (== treats −0 and +0 as equal, the one
// difference quat_mul_pure's comment allows).
#include <gtest/gtest.h>

#include "../support/random.hpp"
#include "tumble/math/quaternion.hpp"

namespace tumble {
namespace {

void expect_same(const Quat& a, const Quat& b) {
  EXPECT_EQ(a.w(), b.w());
  EXPECT_EQ(a.x(), b.x());
  EXPECT_EQ(a.y(), b.y());
  EXPECT_EQ(a.z(), b.z());
}

TEST(Quaternion, ProductsWithAPureQuaternionEqualTheFullProduct) {
  test::Random rng(7);
  for (int trial = 0; trial < 1000; ++trial) {
    // Not unit: the products are bilinear and must not assume |q| = 1.
    const Quat q(rng.uniform(-2, 2), rng.uniform(-2, 2), rng.uniform(-2, 2), rng.uniform(-2, 2));
    const Vec3 u = rng.vec(-10, 10);
    expect_same(quat_mul_pure<double>(q, u), quat_mul<double>(q, pure<double>(u)));
    expect_same(pure_mul_quat<double>(u, q), quat_mul<double>(pure<double>(u), q));
  }
}

TEST(Quaternion, RotateIsEigensRotationAndRotateInverseItsTranspose) {
  test::Random rng(8);
  for (int trial = 0; trial < 1000; ++trial) {
    const Quat q(rng.rotation());
    const Vec3 v = rng.vec(-10, 10);
    const Vec3 Rv = q * v, RTv = q.conjugate() * v;
    for (int k = 0; k < 3; ++k) {
      EXPECT_EQ(rotate<double>(q, v)(k), Rv(k));
      EXPECT_EQ(rotate_inverse<double>(q, v)(k), RTv(k));
    }
    // And they are the rotation matrix and its transpose, to rounding (|v| ≤ 17, a few ulp of it).
    EXPECT_LT((rotate<double>(q, v) - q.toRotationMatrix() * v).norm(), 1e-13);
    EXPECT_LT((rotate_inverse<double>(q, v) - q.toRotationMatrix().transpose() * v).norm(), 1e-13);
  }
}

}  // namespace
}  // namespace tumble
