// The 12-number tangent space of a body's state (dynamics/tangent.hpp): perturbed() and
// tangent_between() are inverses, and a δθ turns the body about world axes, the rest held fixed.
#include <gtest/gtest.h>

#include "../support/random.hpp"
#include "tumble/dynamics/tangent.hpp"

namespace tumble {
namespace {

ReferenceFrameState random_state(test::Random& rng) {
  return {rng.vec(-2, 2), Quat(rng.rotation()), rng.vec(-3, 3), rng.vec(-5, 5)};
}

TEST(Tangent, MovingAlongATangentAndBackGivesIt) {
  // Turns up to 3 rad (below π, where the logarithm is single-valued): the round trip loses only
  // rounding, a few ulps of the largest component (1e-14 absolute for components of order 1).
  test::Random rng(5);
  for (int trial = 0; trial < 200; ++trial) {
    const ReferenceFrameState x = random_state(rng);
    Tangent delta;
    for (int k = 0; k < 12; ++k) delta[k] = rng.uniform(-1, 1);
    delta.segment<3>(3) *= rng.uniform(1e-9, 3.0) / delta.segment<3>(3).norm();
    const Tangent back = tangent_between(x, perturbed(x, delta));
    EXPECT_LT((back - delta).cwiseAbs().maxCoeff(), 1e-14) << "trial " << trial;
  }
}

TEST(Tangent, AnAttitudeTangentTurnsTheBodyAboutWorldAxesAndNothingElse) {
  // δθ = (0, 0, φ) turns every body-fixed direction about world z by φ: R e_k → R_z(φ) R e_k.
  test::Random rng(6);
  const ReferenceFrameState x = random_state(rng);
  Tangent delta = Tangent::Zero();
  delta[5] = 0.3;
  const ReferenceFrameState y = perturbed(x, delta);
  const Mat3 expected = Eigen::AngleAxisd(0.3, Vec3::UnitZ()).toRotationMatrix() *
                        x.orientation.toRotationMatrix();
  EXPECT_LT((y.orientation.toRotationMatrix() - expected).cwiseAbs().maxCoeff(), 1e-15);
  EXPECT_EQ(y.position, x.position);
  EXPECT_EQ(y.velocity, x.velocity);
  EXPECT_EQ(y.omega_w, x.omega_w);
  // The sign of a quaternion is not a state: q and −q are the same attitude, zero apart.
  ReferenceFrameState z = x;
  z.orientation.coeffs() *= -1.0;
  EXPECT_LT(tangent_between(x, z).cwiseAbs().maxCoeff(), 1e-15);
}

}  // namespace
}  // namespace tumble
