// The tutorial's section IV identities, checked against an independent method: a rigid body made of
// point masses, whose inertia is the defining sum I = Σ mᵢ((rᵢ·rᵢ)I₃ − rᵢrᵢᵀ) evaluated directly.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <vector>

#include "../support/random.hpp"
#include "tumble/error.hpp"
#include "tumble/mass/mass_properties.hpp"

namespace tumble {
namespace {

using test::rel_diff;

struct PointCloud {
  std::vector<double> m;
  std::vector<Vec3> x;

  double mass() const {
    double s = 0;
    for (double mi : m) s += mi;
    return s;
  }
  Vec3 center() const {
    Vec3 s = Vec3::Zero();
    for (size_t i = 0; i < m.size(); ++i) s += m[i] * x[i];
    return s / mass();
  }
  /// The definition, about `point`, in the axes of the frame whose rotation is R (columns = axes).
  Mat3 inertia_about(const Vec3& point, const Mat3& R = Mat3::Identity()) const {
    Mat3 I = Mat3::Zero();
    for (size_t i = 0; i < m.size(); ++i) {
      const Vec3 r = R.transpose() * (x[i] - point);
      I += m[i] * (r.dot(r) * Mat3::Identity() - r * r.transpose());
    }
    return I;
  }
  MassProperties properties() const {
    return MassProperties::from_inertia(mass(), center(), inertia_about(center()));
  }
};

PointCloud random_cloud(test::Random& rng, int n, const Vec3& offset) {
  PointCloud c;
  for (int i = 0; i < n; ++i) {
    c.m.push_back(rng.uniform(0.1, 2.0));
    c.x.push_back(offset + rng.vec(-1.0, 1.0));
  }
  return c;
}

// Sums of ~50 terms of size O(1..10): rounding leaves ~1e-14 relative; 1e-12 leaves a margin of 100.
constexpr double kRounding = 1e-12;

TEST(MassProperties, TranslationMatchesDefinitionAboutAnyPoint) {
  test::Random rng(1);
  for (int trial = 0; trial < 50; ++trial) {
    const PointCloud cloud = random_cloud(rng, 50, rng.vec(-3, 3));
    const MassProperties mp = cloud.properties();
    const Vec3 b = rng.vec(-5, 5);
    EXPECT_LT(rel_diff(mp.inertia_about(b), cloud.inertia_about(b)), kRounding);
    // ^tI = ^sI + m((b·b)I₃ − bbᵀ) and back to the centre of mass.
    const MassProperties back =
        MassProperties::from_inertia_about(mp.mass, mp.center_of_mass, mp.inertia_about(b), b);
    EXPECT_LT(rel_diff(back.inertia, mp.inertia), kRounding);
  }
}

TEST(MassProperties, InertiaAboutCentreIsTheMinimumOverParallelAxes) {
  // The parallel-axis term is positive semidefinite, so every moment about the centre of mass is
  // smaller than the moment about a parallel axis elsewhere.
  test::Random rng(2);
  const MassProperties mp = rng.body();
  for (int trial = 0; trial < 20; ++trial) {
    const Vec3 axis = rng.vec(-1, 1);
    const Vec3 p = rng.vec(-2, 2);
    EXPECT_LE(mp.moment_about_axis(axis), mp.moment_about_axis(axis, p) * (1 + 1e-15));
  }
}

TEST(MassProperties, RotationMatchesDefinitionInRotatedFrame) {
  test::Random rng(3);
  for (int trial = 0; trial < 50; ++trial) {
    const PointCloud cloud = random_cloud(rng, 50, rng.vec(-3, 3));
    const MassProperties mp = cloud.properties();
    const Mat3 R = rng.rotation();
    const MassProperties q = mp.expressed_in(R);  // ^qI = Rᵀ ^sI R
    EXPECT_LT(rel_diff(q.inertia, cloud.inertia_about(cloud.center(), R)), kRounding);
    EXPECT_LT((q.center_of_mass - R.transpose() * mp.center_of_mass).norm(), kRounding);
    // Invariants of a similarity transform: trace and determinant.
    EXPECT_NEAR(q.inertia.trace(), mp.inertia.trace(), kRounding * mp.inertia.trace());
    EXPECT_NEAR(q.inertia.determinant(), mp.inertia.determinant(),
                kRounding * std::abs(mp.inertia.determinant()));
  }
}

TEST(MassProperties, TransformedPlacesThePartInTheParentFrame) {
  test::Random rng(4);
  const PointCloud cloud = random_cloud(rng, 40, Vec3::Zero());
  const Mat3 R = rng.rotation();
  const Vec3 t = rng.vec(-4, 4);
  PointCloud moved = cloud;
  for (auto& x : moved.x) x = R * x + t;
  const MassProperties placed = cloud.properties().transformed(R, t);
  EXPECT_LT(rel_diff(placed.inertia, moved.properties().inertia), kRounding);
  EXPECT_LT((placed.center_of_mass - moved.center()).norm(), kRounding);
}

TEST(MassProperties, CombiningPartsEqualsTheWholeAndSubtractingRecoversAPart) {
  test::Random rng(5);
  for (int trial = 0; trial < 30; ++trial) {
    const PointCloud a = random_cloud(rng, 30, rng.vec(-2, 2));
    const PointCloud b = random_cloud(rng, 20, rng.vec(-2, 2));
    PointCloud whole = a;
    whole.m.insert(whole.m.end(), b.m.begin(), b.m.end());
    whole.x.insert(whole.x.end(), b.x.begin(), b.x.end());
    const MassProperties sum = a.properties() + b.properties();
    EXPECT_NEAR(sum.mass, whole.mass(), kRounding * whole.mass());
    EXPECT_LT((sum.center_of_mass - whole.center()).norm(), kRounding);
    EXPECT_LT(rel_diff(sum.inertia, whole.properties().inertia), kRounding);
    // A hole: the whole minus one part is the other part.
    const MassProperties rest = whole.properties() - b.properties();
    EXPECT_NEAR(rest.mass, a.mass(), kRounding * a.mass());
    EXPECT_LT((rest.center_of_mass - a.center()).norm(), 1e-11);
    EXPECT_LT(rel_diff(rest.inertia, a.properties().inertia), 1e-11);
  }
}

TEST(MassProperties, SubtractingAHeavierPartIsAnError) {
  const MassProperties small{1.0, Vec3::Zero(), Mat3::Identity(), 0};
  const MassProperties big{2.0, Vec3::Zero(), Mat3::Identity(), 0};
  EXPECT_THROW(small - big, InvalidArgument);
}

TEST(MassProperties, MomentAboutAxisAndRadiusOfGyrationMatchDefinition) {
  test::Random rng(6);
  for (int trial = 0; trial < 50; ++trial) {
    const PointCloud cloud = random_cloud(rng, 50, rng.vec(-2, 2));
    const MassProperties mp = cloud.properties();
    const Vec3 axis = rng.vec(-1, 1);
    const Vec3 p = rng.vec(-3, 3);
    const Vec3 l = axis.normalized();
    double direct = 0;  // I_l = Σ m |(x − p) × l̂|²
    for (size_t i = 0; i < cloud.m.size(); ++i)
      direct += cloud.m[i] * (cloud.x[i] - p).cross(l).squaredNorm();
    EXPECT_NEAR(mp.moment_about_axis(axis, p), direct, kRounding * direct);
    // l̂ᵀ I l̂ with I about p is the same number (tutorial: I_l = l̂ᵀ I l̂).
    EXPECT_NEAR(l.dot(mp.inertia_about(p) * l), direct, kRounding * direct);
    EXPECT_NEAR(mp.radius_of_gyration(axis, p), std::sqrt(direct / mp.mass), kRounding);
  }
  const MassProperties mp = random_cloud(rng, 5, Vec3::Zero()).properties();
  EXPECT_THROW(mp.moment_about_axis(Vec3::Zero()), InvalidArgument);
}

// ---- principal axes --------------------------------------------------------------------------

void expect_proper_diagonalisation(const Mat3& I, const PrincipalAxes& pa) {
  const double scale = I.cwiseAbs().maxCoeff();
  EXPECT_NEAR(pa.U.determinant(), 1.0, 1e-14);
  EXPECT_LT((pa.U.transpose() * pa.U - Mat3::Identity()).cwiseAbs().maxCoeff(), 1e-14);
  const Mat3 D = pa.U.transpose() * I * pa.U;  // = Λ (tutorial: ^bI = UᵀUΛUᵀU = Λ)
  EXPECT_LT((D - Mat3(pa.Lambda.asDiagonal())).cwiseAbs().maxCoeff(), 1e-13 * scale);
  EXPECT_LE(pa.Lambda(0), pa.Lambda(1));
  EXPECT_LE(pa.Lambda(1), pa.Lambda(2));
}

TEST(PrincipalAxes, DiagonaliseRandomBodiesWithAProperRotation) {
  test::Random rng(7);
  for (int trial = 0; trial < 200; ++trial) {
    const MassProperties mp = rng.body();
    expect_proper_diagonalisation(mp.inertia, mp.principal_axes());
  }
}

TEST(PrincipalAxes, SphereKeepsTheReferenceAxes) {
  test::Random rng(8);
  const Mat3 R = rng.rotation();
  const Mat3 I = R * Vec3(2.5, 2.5, 2.5).asDiagonal() * R.transpose();
  const PrincipalAxes pa = principal_axes(I);
  EXPECT_EQ(pa.U, Mat3::Identity());
  EXPECT_EQ(pa.Lambda(0), pa.Lambda(2));
  EXPECT_NEAR(pa.Lambda(0), 2.5, 1e-15 * 2.5 * 4);
}

TEST(PrincipalAxes, AxisymmetricBodiesAreCanonicalAndStable) {
  test::Random rng(9);
  for (int trial = 0; trial < 100; ++trial) {
    const Mat3 R = rng.rotation();
    // Prolate (unique axis has the smallest moment) and oblate (largest) bodies.
    for (const Vec3& moments : {Vec3(1.0, 3.0, 3.0), Vec3(2.0, 2.0, 3.5)}) {
      const Mat3 I = R * moments.asDiagonal() * R.transpose();
      const PrincipalAxes pa = principal_axes(I);
      expect_proper_diagonalisation(I, pa);
      const bool prolate = moments(0) < moments(1);
      const Vec3 unique = prolate ? pa.U.col(0) : pa.U.col(2);
      const Vec3 expected = prolate ? R.col(0) : R.col(2);
      EXPECT_NEAR(std::abs(unique.dot(expected)), 1.0, 1e-13);
      EXPECT_EQ(prolate ? pa.Lambda(1) : pa.Lambda(0), prolate ? pa.Lambda(2) : pa.Lambda(1));
      // Well conditioned: a rounding-level perturbation of I moves U by rounding only, even though
      // the eigenvectors inside the repeated plane are arbitrary for the eigen-solver.
      Mat3 J = I;
      J(0, 1) += 1e-15;
      J(1, 0) += 1e-15;
      J(2, 2) -= 2e-15;
      EXPECT_LT((principal_axes(J).U - pa.U).cwiseAbs().maxCoeff(), 1e-12);
    }
  }
}

TEST(PrincipalAxes, ADiagonalTensorHasTheSolversAxesWithoutItsWork) {
  // principal_axes() takes a diagonal tensor's moments and coordinate axes straight (a body table's
  // rows give their moments so); the solver gives the same axes in the same order, up to sign, which
  // the canonical choice that follows fixes either way. Distinct, repeated and nearly repeated moments.
  for (const Vec3& d : {Vec3(1, 2, 3), Vec3(3, 1, 2), Vec3(2, 3, 1), Vec3(3, 2, 1), Vec3(0.5, 0.5, 0.8),
                        Vec3(0.8, 0.5, 0.5), Vec3(0.5, 0.8, 0.5), Vec3(2, 2, 2), Vec3(1, 1 + 1e-13, 1.5),
                        Vec3(1.7, 0.3, 1.7 * (1 + 1e-14)), Vec3(1e-3, 4e2, 3e2)}) {
    const Mat3 D = d.asDiagonal();
    const Eigen::SelfAdjointEigenSolver<Mat3> solver(D);
    const PrincipalAxes pa = principal_axes(D);
    Vec3 sorted = d;
    std::sort(sorted.data(), sorted.data() + 3);
    EXPECT_EQ(solver.eigenvalues(), sorted) << d.transpose();
    EXPECT_EQ(solver.eigenvectors().cwiseAbs().cwiseAbs2(), solver.eigenvectors().cwiseAbs())  // 0s and 1s
        << d.transpose();
    const bool distinct = sorted(1) - sorted(0) > 1e-10 * sorted(2) &&
                          sorted(2) - sorted(1) > 1e-10 * sorted(2);
    if (distinct) {  // each axis the solver's, of the same moment
      EXPECT_EQ(pa.U.cwiseAbs(), solver.eigenvectors().cwiseAbs()) << d.transpose();
      EXPECT_EQ(pa.Lambda, sorted) << d.transpose();
    }
    expect_proper_diagonalisation(D, pa);
    // A signed permutation, each moment the diagonal entry along its axis (a repeated group's mean).
    EXPECT_EQ(pa.U.cwiseAbs().colwise().sum(), Eigen::RowVector3d::Ones()) << d.transpose();
    for (int i = 0; i < 3; ++i)
      EXPECT_NEAR(pa.Lambda(i), pa.U.col(i).dot(D * pa.U.col(i)), 1e-10 * sorted(2));
  }
}

TEST(PrincipalAxes, DistinctMomentsFollowTheSignConvention) {
  test::Random rng(10);
  for (int trial = 0; trial < 100; ++trial) {
    const MassProperties mp = rng.body();
    const PrincipalAxes pa = mp.principal_axes();
    for (int c = 0; c < 2; ++c) {
      Eigen::Index k;
      pa.U.col(c).cwiseAbs().maxCoeff(&k);
      EXPECT_GT(pa.U(k, c), 0.0);
    }
    // Same input, same output (deterministic), and the columns of −U·diag(1,1,... ) are not chosen.
    EXPECT_EQ(mp.principal_axes().U, pa.U);
  }
}

// ---- validity --------------------------------------------------------------------------------

std::string validation_message(const MassProperties& mp) {
  try {
    mp.validate({}, "body 'probe'");
  } catch (const InvalidMassProperties& e) {
    return e.what();
  }
  return "";
}

TEST(Validity, AcceptsPhysicalBodiesIncludingFlatPlates) {
  test::Random rng(11);
  for (int i = 0; i < 50; ++i) EXPECT_NO_THROW(rng.body().validate());
  // A thin square plate lies exactly on λ₃ = λ₁ + λ₂.
  const MassProperties plate{1.0, Vec3::Zero(), Vec3(1.0 / 12, 1.0 / 12, 1.0 / 6).asDiagonal(), 0};
  EXPECT_NO_THROW(plate.validate());
}

TEST(Validity, EachViolationIsNamedWithItsNumbers) {
  const Mat3 good = Vec3(1.0, 2.0, 2.5).asDiagonal();
  EXPECT_NE(validation_message({-1.0, Vec3::Zero(), good, 0}).find("mass is -1 kg"), std::string::npos);
  Mat3 asym = good;
  asym(0, 1) = 0.1;
  EXPECT_NE(validation_message({1.0, Vec3::Zero(), asym, 0}).find("not symmetric"), std::string::npos);
  const std::string pd = validation_message({1.0, Vec3::Zero(), Vec3(-0.5, 2.0, 2.0).asDiagonal(), 0});
  EXPECT_NE(pd.find("not positive definite"), std::string::npos);
  EXPECT_NE(pd.find("-0.5"), std::string::npos);
  const std::string tri = validation_message({1.0, Vec3::Zero(), Vec3(1.0, 1.0, 2.5).asDiagonal(), 0});
  EXPECT_NE(tri.find("triangle inequality"), std::string::npos) << tri;
  EXPECT_NE(tri.find("2.5"), std::string::npos) << tri;
  EXPECT_NE(tri.find("body 'probe': "), std::string::npos) << tri;
  Mat3 nan = good;
  nan(2, 2) = std::nan("");
  EXPECT_NE(validation_message({1.0, Vec3::Zero(), nan, 0}).find("non-finite"), std::string::npos);
}

}  // namespace
}  // namespace tumble
