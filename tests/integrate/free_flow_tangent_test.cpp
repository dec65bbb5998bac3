// The exact torque-free flow on dual numbers (integrate/free_flow_tangent.hpp), checked against
//  - central differences of EulerPoinsot itself (the flow on double), for ω_b(0), q(0) and Λ;
//  - each other: the closed form (Jacobi functions and Π differentiated with respect to their argument
//    and parameter) and the Taylor series of the same flow on dual numbers agree to rounding.
#include <gtest/gtest.h>

#include <cstdio>

#include "integrate/free_flow_tangent.hpp"
#include "tumble/math/quaternion.hpp"

namespace tumble {
namespace {

using T = TangentScalar;

/// The 7 numbers of a flow state (q's four, ω_b's three) along slot j, or their values (j = −1).
Eigen::Matrix<double, 7, 1> numbers(const detail::FlowState<T>& s, int j) {
  Eigen::Matrix<double, 7, 1> r;
  for (int k = 0; k < 4; ++k) r(k) = j < 0 ? s.q.coeffs()(k).v : s.q.coeffs()(k).d[j];
  for (int k = 0; k < 3; ++k) r(4 + k) = j < 0 ? s.omega_b(k).v : s.omega_b(k).d[j];
  return r;
}
Eigen::Matrix<double, 7, 1> numbers(const EulerPoinsot::State& s) {
  Eigen::Matrix<double, 7, 1> r;
  r << s.q.coeffs(), s.omega_b;
  return r;
}

/// Seeds: slots 0–2 ω_b(0), 3–5 Λ, 6–8 a turn of q(0) about world axes (q ← exp(δθ) q).
struct Seeded {
  Vec3T<T> Lambda, omega;
  QuatT<T> q;
  Seeded(const Vec3& L, const Quat& q0, const Vec3& w) {
    for (int k = 0; k < 3; ++k) {
      omega(k) = T::variable(w(k), k);
      Lambda(k) = T::variable(L(k), 3 + k);
    }
    const Vec3T<T> theta(T::variable(0.0, 6), T::variable(0.0, 7), T::variable(0.0, 8));
    q = quat_mul<T>(quat_exp<T>(theta), q0.cast<T>());
    for (int k = 0; k < 4; ++k) q.coeffs()(k).v = q0.coeffs()(k);
  }
};

/// Central differences of EulerPoinsot at tau along the nine seeds, step eps. Each side's q takes the
/// sign of the unperturbed one (q and −q are one attitude, and a perturbed flow's closed form, of
/// another kind where a moment's change breaks a symmetry, may give either).
Eigen::Matrix<double, 7, 9> central(const Vec3& L, const Quat& q0, const Vec3& w, double tau, double eps) {
  const Quat q_tau = EulerPoinsot(L, q0, w).q(tau);
  Eigen::Matrix<double, 7, 9> J;
  for (int j = 0; j < 9; ++j) {
    Eigen::Matrix<double, 7, 1> side[2];
    for (int s = 0; s < 2; ++s) {
      const double e = s == 0 ? eps : -eps;
      Vec3 L1 = L, w1 = w;
      Quat q1 = q0;
      if (j < 3) w1(j) += e;
      if (j >= 3 && j < 6) L1(j - 3) += e;
      if (j >= 6) q1 = quat_exp<double>(e * Vec3::Unit(j - 6)) * q0;
      side[s] = numbers(EulerPoinsot(L1, q1, w1).state(tau));
      if (side[s].head<4>().dot(q_tau.coeffs()) < 0) side[s].head<4>() *= -1.0;
    }
    J.col(j) = (side[0] - side[1]) / (2 * eps);
  }
  return J;
}

Eigen::Matrix<double, 7, 9> dual(const FreeFlowTangent& flow, double tau) {
  const detail::FlowState<T> s = flow.at(tau);
  Eigen::Matrix<double, 7, 9> J;
  for (int j = 0; j < 9; ++j) J.col(j) = numbers(s, j);
  return J;
}

/// A body, its initial state and what the closed form makes of it.
struct Case {
  const char* what;
  Vec3 Lambda, omega;
  bool closed_form;
};

const Quat kQ0 = Quat(Eigen::AngleAxisd(0.6, Vec3(1, 2, -0.5).normalized()));

// Generic triaxial motions: the closed form is differentiated. Both poles, the moments in any order
// (a signed permutation sorts them), components of either sign (the signs σ₁, σ₃ and the phase beyond
// K), a motion 1e-6 from the separatrix (m₁ ≈ 1e-7: K and the phase are steep in m there).
const Case kTriaxial[] = {
    {"about the major axis", {1.5, 2.5, 4.0}, {0.8, -1.2, 2.0}, true},
    {"about the minor axis", {1.5, 2.5, 4.0}, {2.0, 1.2, -0.5}, true},
    {"moments unsorted", {4.0, 1.5, 2.5}, {0.8, -1.2, 2.0}, true},
    {"negative components", {1.5, 2.5, 4.0}, {-0.8, 1.2, -2.0}, true},
    {"near the separatrix", {1.5, 2.5, 4.0}, {0.2, 6.0, 0.2 * 0.5 * std::sqrt(1.5 / 6.0) * (1 + 1e-6)}, true},
};
// Where the closed form is not differentiable, the Taylor series gives the derivatives: two equal
// moments (a moment's derivative breaks the symmetry the closed form assumes), three, a spin exactly
// about the major axis (m = 0), a state exactly on the separatrix, the steady spin about the
// intermediate axis.
const Case kDegenerate[] = {
    {"axisymmetric", {2.5, 2.5, 4.0}, {0.8, -1.2, 2.0}, false},
    {"sphere", {2.5, 2.5, 2.5}, {0.8, -1.2, 2.0}, false},
    {"spin about the major axis", {1.5, 2.5, 4.0}, {0.0, 0.0, 2.0}, false},
    {"on the separatrix", {1.0, 2.0, 3.0}, {1.0, 0.5, 1.0 / std::sqrt(3.0)}, false},
    {"about the intermediate axis", {1.5, 2.5, 4.0}, {0.0, 3.0, 0.0}, false},
};

/// |dual − central| against the central differences' own error, |fd(ε) − fd(2ε)| (truncation ε²|x‴|/6,
/// 4× at 2ε) plus their rounding, ~1e-16·|x|/ε with |x| ~ 1 and ε = 1e-6: 1e-9.
void expect_matches_central_differences(const Case& c, double tau) {
  const Seeded x(c.Lambda, kQ0, c.omega);
  const FreeFlowTangent flow(x.Lambda, x.q, x.omega);
  EXPECT_EQ(flow.closed_form(), c.closed_form) << c.what;
  const Eigen::Matrix<double, 7, 9> S = dual(flow, tau);
  const Eigen::Matrix<double, 7, 9> fd = central(c.Lambda, kQ0, c.omega, tau, 1e-6);
  const Eigen::Matrix<double, 7, 9> fd2 = central(c.Lambda, kQ0, c.omega, tau, 2e-6);
  EXPECT_LT((S - fd).cwiseAbs().maxCoeff(),
            (fd - fd2).cwiseAbs().maxCoeff() + 1e-9 * (1 + fd.cwiseAbs().maxCoeff()))
      << c.what << " at tau = " << tau << "\n"
      << S - fd;
  EXPECT_GT(S.cwiseAbs().maxCoeff(), 0.1) << c.what;
}

TEST(FreeFlowTangent, TheClosedFormsDerivativesAreThoseOfTheFlow) {
  for (const Case& c : kTriaxial) {
    for (double tau : {0.0, 0.01, 0.7, 5.0, -2.0}) expect_matches_central_differences(c, tau);
  }
}

TEST(FreeFlowTangent, WhereTheClosedFormIsNotDifferentiableTheTaylorSeriesIs) {
  for (const Case& c : kDegenerate) {
    for (double tau : {0.01, 0.7, 2.0, -0.3}) expect_matches_central_differences(c, tau);
  }
}

TEST(FreeFlowTangent, TheClosedFormAndTheTaylorSeriesAgreeToRounding) {
  // Two methods on dual numbers, one flow: Jacobi functions and Π differentiated through the Landen
  // recursion, Carlson's R_J and Bulirsch's Π(n | m), against the series of Euler's equation summed in
  // short steps. Their derivatives agree to the rounding of either (~1e-13 relative over these times;
  // the derivatives grow like τ, and near the separatrix like the flip's amplification).
  for (const Case& c : kTriaxial) {
    const Seeded x(c.Lambda, kQ0, c.omega);
    const FreeFlowTangent closed(x.Lambda, x.q, x.omega);
    const FreeFlowTangent series(x.Lambda, x.q, x.omega, FreeFlowTangent::Method::taylor_series);
    ASSERT_TRUE(closed.closed_form());
    ASSERT_FALSE(series.closed_form());
    for (double tau : {0.3, 3.0}) {
      const Eigen::Matrix<double, 7, 9> a = dual(closed, tau), b = dual(series, tau);
      EXPECT_LT((a - b).cwiseAbs().maxCoeff(), 1e-12 * (1 + a.cwiseAbs().maxCoeff()))
          << c.what << " at tau = " << tau << "\n"
          << a - b;
    }
  }
}

TEST(FreeFlowTangent, TheValuesAreEulerPoinsotsBitForBit) {
  for (const Case& c : kTriaxial) {
    const Seeded x(c.Lambda, kQ0, c.omega);
    const EulerPoinsot flow(c.Lambda, kQ0, c.omega);
    for (const auto method : {FreeFlowTangent::Method::closed_form_where_differentiable,
                              FreeFlowTangent::Method::taylor_series}) {
      EXPECT_EQ(numbers(FreeFlowTangent(x.Lambda, x.q, x.omega, method).at(1.3), -1),
                numbers(flow.state(1.3)))
          << c.what;
    }
  }
}

}  // namespace
}  // namespace tumble
