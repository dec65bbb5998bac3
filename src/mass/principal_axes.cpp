// Principal axes: I = U Λ Uᵀ (tutorial, "Principal Axes"), with a canonical U.
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <array>
#include <cmath>
#include <utility>

#include "tumble/mass/mass_properties.hpp"

namespace tumble {
namespace {

/// Flip v so that its largest-magnitude component is positive (ties: the lowest index).
Vec3 canonical_sign(Vec3 v) {
  const double largest = v.cwiseAbs().maxCoeff();
  for (int i = 0; i < 3; ++i) {
    if (std::abs(v(i)) >= largest * (1.0 - 1e-12)) {
      return v(i) < 0.0 ? Vec3(-v) : v;
    }
  }
  return v;
}

/// A unit vector perpendicular to the unit vector n, chosen canonically: the reference coordinate
/// axis most perpendicular to n (smallest |n_k|, ties to the lowest k), with its n-component removed.
Vec3 canonical_perpendicular(const Vec3& n) {
  int k = 0;
  for (int i = 1; i < 3; ++i) {
    if (std::abs(n(i)) < std::abs(n(k)) - 1e-12) k = i;
  }
  const Vec3 e = Vec3::Unit(k);
  return (e - e.dot(n) * n).normalized();
}

/// The eigenvalues (ascending) and eigenvectors of the symmetric `S`.
std::pair<Vec3, Mat3> eigen_decomposition(const Mat3& S) {
  if (S(0, 1) == 0.0 && S(0, 2) == 0.0 && S(1, 2) == 0.0 && S.diagonal().allFinite()) {
    // Diagonal (a body table's row, principal moments given along the reference axes): the moments and
    // the coordinate axes, in ascending order, as the solver would give them (up to the signs that
    // principal_axes() fixes; tested), without its work: a tenth of a table row's set-up.
    std::array<int, 3> k{0, 1, 2};  // the axes by ascending moment, equal ones in axis order
    for (int i = 1; i < 3; ++i) {
      for (int j = i; j > 0 && S(k[j], k[j]) < S(k[j - 1], k[j - 1]); --j) std::swap(k[j], k[j - 1]);
    }
    Mat3 V;
    V << Vec3::Unit(k[0]), Vec3::Unit(k[1]), Vec3::Unit(k[2]);
    return {Vec3(S(k[0], k[0]), S(k[1], k[1]), S(k[2], k[2])), V};
  }
  // The iterative (QR) solver, not computeDirect(): the closed-form 3×3 route loses accuracy in the
  // eigenvectors of nearly repeated moments. Eigenvalues come out ascending.
  const Eigen::SelfAdjointEigenSolver<Mat3> solver(S);
  return {solver.eigenvalues(), solver.eigenvectors()};
}

}  // namespace

PrincipalAxes principal_axes(const Mat3& I, const PrincipalAxesOptions& options) {
  const auto [lambda, V] = eigen_decomposition(0.5 * (I + I.transpose()));
  const double tol = options.repeated_tolerance * lambda.cwiseAbs().maxCoeff();
  const bool low_pair = lambda(1) - lambda(0) <= tol;
  const bool high_pair = lambda(2) - lambda(1) <= tol;

  Mat3 U;
  if (low_pair && high_pair) {
    U.setIdentity();  // sphere-like: every direction is principal; keep the reference axes
  } else if (low_pair) {
    const Vec3 u3 = canonical_sign(V.col(2));
    const Vec3 u1 = canonical_perpendicular(u3);
    U << u1, u3.cross(u1), u3;
  } else if (high_pair) {
    const Vec3 u1 = canonical_sign(V.col(0));
    const Vec3 u2 = canonical_perpendicular(u1);
    U << u1, u2, u1.cross(u2);
  } else {
    const Vec3 u1 = canonical_sign(V.col(0));
    const Vec3 u2 = canonical_sign(V.col(1));
    U << u1, u2, u1.cross(u2);
  }

  // Moments as Rayleigh quotients λᵢ = uᵢᵀ I uᵢ of the chosen axes; a repeated group gets its mean
  // so that equal moments compare equal downstream (axisymmetric and spherical code paths).
  const Mat3 sym = 0.5 * (I + I.transpose());
  Vec3 Lambda(U.col(0).dot(sym * U.col(0)), U.col(1).dot(sym * U.col(1)), U.col(2).dot(sym * U.col(2)));
  if (low_pair && high_pair) {
    Lambda.setConstant(Lambda.mean());
  } else if (low_pair) {
    Lambda(0) = Lambda(1) = 0.5 * (Lambda(0) + Lambda(1));
  } else if (high_pair) {
    Lambda(1) = Lambda(2) = 0.5 * (Lambda(1) + Lambda(2));
  }
  return PrincipalAxes{Lambda, U};
}

}  // namespace tumble
