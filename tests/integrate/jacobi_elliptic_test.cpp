// Jacobi elliptic functions from (k, k′): identities, agreement with Boost where Boost is well
// conditioned, and high-precision values near m = 1 where it is not.
#include "tumble/integrate/jacobi_elliptic.hpp"

#include <gtest/gtest.h>

#include <boost/math/special_functions/ellint_1.hpp>
#include <boost/math/special_functions/ellint_3.hpp>
#include <boost/math/special_functions/jacobi_elliptic.hpp>
#include <cmath>
#include <cstdio>
#include <numbers>

#include "tumble/error.hpp"

namespace tumble {
namespace {

constexpr double kEps = 2.220446049250313e-16;

TEST(JacobiElliptic, AgreesWithBoostAwayFromTheSeparatrix) {
  // For m ≤ 0.9 the modulus-only route of Boost loses nothing (k′ = √(1 − k²) is well conditioned),
  // so both evaluate the same functions to a few ulps: sums of O(10) rounded terms, 1e-14 absolute.
  for (double m : {0.0, 1e-9, 0.1, 0.5, 0.9}) {
    const JacobiElliptic f(m, 1.0 - m);
    const double k = std::sqrt(m);
    EXPECT_NEAR(f.K(), boost::math::ellint_1(k), 4 * kEps * f.K()) << m;
    for (double u = -7.0; u <= 7.0; u += 0.3) {
      double cn, dn;
      const double sn = boost::math::jacobi_elliptic(k, u, &cn, &dn);
      const JacobiValues v = f(u);
      EXPECT_NEAR(v.sn, sn, 1e-14) << "m = " << m << ", u = " << u;
      EXPECT_NEAR(v.cn, cn, 1e-14) << "m = " << m << ", u = " << u;
      EXPECT_NEAR(v.dn, dn, 1e-14) << "m = " << m << ", u = " << u;
      // The identities sn² + cn² = 1, dn² + m sn² = 1 hold to rounding.
      EXPECT_NEAR(v.sn * v.sn + v.cn * v.cn, 1.0, 4 * kEps);
      EXPECT_NEAR(v.dn * v.dn + m * v.sn * v.sn, 1.0, 4 * kEps);
      // am is continuous and sn = sin am, cn = cos am.
      EXPECT_NEAR(std::sin(v.am), v.sn, 1e-14);
      EXPECT_NEAR(std::cos(v.am), v.cn, 1e-14);
    }
  }
}

TEST(JacobiElliptic, KeepsFullAccuracyNearTheSeparatrixWhereTheModulusRouteLosesIt) {
  // Reference values: mpmath 1.3 at 40 digits, ellipk(1 − m1) and ellipfun(·, u, m = 1 − m1), with m1
  // the double given (exactly representable inputs).
  struct Ref {
    double m1, K, u, sn, cn, dn;
  };
  // clang-format off
  const Ref refs[] = {
      {1e-12, 15.201804919087715184, 3.0, 0.99505475368697181549, 0.099327927417015251857, 0.099327927421999418891},
      {1e-12, 15.201804919087715184, 10.0, 0.99999999587794275981, 0.000090797106029836922852,
       0.000090802612646251563571},
      {1e-8, 10.59663475708766031, 10.0, 0.99999999799865726976, 0.000063266780038810216275,
       0.0001183329430735682348},
  };
  // clang-format on
  for (const Ref& r : refs) {
    const JacobiElliptic f(1.0 - r.m1, r.m1);
    // K = R_F(0, k′², 1) from k′² directly: a few ulps.
    EXPECT_NEAR(f.K(), r.K, 4 * kEps * r.K) << r.m1;
    const JacobiValues v = f(r.u);
    // sn, cn, dn to a few ulps of 1 (the argument u is exact; the Landen recursion halves errors).
    EXPECT_NEAR(v.sn, r.sn, 4 * kEps) << r.m1;
    EXPECT_NEAR(v.cn, r.cn, 8 * kEps) << r.m1;
    EXPECT_NEAR(v.dn, r.dn, 8 * kEps) << r.m1;
    // Boost's modulus-only K: k = √(1 − k′²) rounds k′² to a multiple of 2⁻⁵³ ≈ 1.1e-16, a relative
    // change of up to 1.1e-16/k′² in k′², hence δK = δ(ln(4/k′)) ≈ ½·1.1e-16/k′². Measured and
    // asserted to be far worse than the k′ route at k′² = 1e-12.
    const double K_boost = boost::math::ellint_1(std::sqrt(1.0 - r.m1));
    if (r.m1 == 1e-12) {
      const double loss = std::abs(K_boost - r.K) / r.K;
      std::printf("[ measured ] K at k'^2 = 1e-12: Boost ellint_1(k) relative error %.1e\n", loss);
      EXPECT_GT(loss, 1e-7);
      EXPECT_LT(loss, 1e-4);
    }
  }
}

TEST(JacobiElliptic, DeepLandenRecursionKeepsTheSeparatrixLimit) {
  // The deepest Landen recursions of normal doubles (a dozen levels), where landen_point's common
  // denominator D grows most (jacobi_elliptic.hpp). There
  // sn u = tanh u + O(k′² u cosh²u), cn, dn = sech u + O(k′² …) (DLMF 22.10.2): for |u| ≤ 3 the
  // corrections are below 1e-90, so tanh and sech are the exact values to double precision. Bounds: a
  // few ulps, as KeepsFullAccuracyNearTheSeparatrix… (the recursion halves errors; cn, dn are small
  // here, so relative to their size).
  for (double m1 : {1e-100, 1e-300}) {
    const JacobiElliptic f(1.0 - m1, m1);
    EXPECT_GT(f.constants().steps, 8) << m1;
    for (double u : {-2.0, 0.5, 1.7, 3.0}) {
      const JacobiValues v = f(u);
      const double sech = 1.0 / std::cosh(u);
      EXPECT_NEAR(v.sn, std::tanh(u), 4 * kEps) << m1 << " " << u;
      EXPECT_NEAR(v.cn, sech, 8 * kEps * sech) << m1 << " " << u;
      EXPECT_NEAR(v.dn, sech, 8 * kEps * sech) << m1 << " " << u;
    }
  }
}

TEST(JacobiElliptic, SeparatrixLimitIsTanhAndSech) {
  const JacobiElliptic f(1.0, 0.0);
  EXPECT_TRUE(std::isinf(f.K()));
  for (double u : {-30.0, -2.0, 0.0, 0.5, 4.0, 800.0}) {
    const JacobiValues v = f(u);
    EXPECT_EQ(v.sn, std::tanh(u));
    EXPECT_EQ(v.cn, 1.0 / std::cosh(u));
    EXPECT_EQ(v.dn, v.cn);
    EXPECT_NEAR(v.am, std::atan(std::sinh(u)), 4 * kEps * std::abs(v.am) + 1e-300);  // am = gd u
  }
  // k′² = 1e-30 is not yet the separatrix but is indistinguishable from it for u ≪ K ≈ 35.9:
  // sn − tanh = O(k′² sinh u cosh u) ≈ 1e-22, below rounding. The Landen recursion has N = 7 steps
  // here; each adds a rounding of its sin and asin that the halving does not fully damp where
  // cₙ/aₙ ≈ 1 (measured 5.5 ulp), so 8ε.
  const JacobiElliptic g(1.0, 1e-30);
  for (double u : {0.5, 3.0, 10.0}) EXPECT_NEAR(g(u).sn, std::tanh(u), 8 * kEps);
}

TEST(JacobiElliptic, ReductionByHalfPeriodsIsExactAndCostsNothing) {
  // am(u + 2jK) = am u + jπ, sn(u + 2jK) = (−1)ʲ sn u. The shifted argument u + 2jK carries the
  // rounding ε·|u + 2jK|, which bounds the agreement (1e5 half-periods: |u| ≈ 2e5, ε|u| ≈ 5e-11).
  const JacobiElliptic f(0.7, 0.3);
  for (double j : {1.0, 7.0, 1e5}) {
    for (double u : {-1.0, 0.2, 1.5}) {
      const double shifted = u + 2.0 * j * f.K();
      const double tol = 8 * kEps * std::abs(shifted) * 2.0;  // |d sn/du| ≤ 1, |d am/du| ≤ 1
      const JacobiValues a = f(u), b = f(shifted);
      EXPECT_NEAR(b.am, a.am + j * std::numbers::pi, tol);
      EXPECT_NEAR(b.sn, std::fmod(j, 2.0) == 0.0 ? a.sn : -a.sn, tol);
      EXPECT_NEAR(b.dn, a.dn, tol);
    }
  }
}

TEST(JacobiElliptic, ThirdKindIntegralAgreesWithBoostEllint3) {
  // Boost's ellint_3(k, n, φ) uses the same (1 − n sin²θ) convention; well conditioned for m ≤ 0.9.
  for (double m : {0.1, 0.6, 0.9}) {
    const JacobiElliptic f(m, 1.0 - m);
    const double k = std::sqrt(m);
    for (double n : {-5.0, -0.3, 0.0, 0.4}) {
      EXPECT_NEAR(elliptic_Pi_complete(n, 1.0 - m), boost::math::ellint_3(k, n), 1e-14);
      for (double u = -1.2 * f.K(); u <= 1.2 * f.K(); u += 0.25) {
        const JacobiValues v = f(u);
        // Π(n; am u) = 2jΠ(n) + Π(n; am r), with Boost's direct evaluation at φ = am u.
        const double Pi = 2.0 * v.j * elliptic_Pi_complete(n, 1.0 - m) +
                          elliptic_Pi_incomplete(n, v.sn_r, v.cn_r, v.dn);
        EXPECT_NEAR(Pi, boost::math::ellint_3(k, n, v.am), 1e-13)
            << "m = " << m << ", n = " << n << ", u = " << u;
      }
    }
    // With n = 0 the integral is F(am u) = u.
    EXPECT_NEAR(elliptic_Pi_incomplete(0.0, f(0.8).sn_r, f(0.8).cn_r, f(0.8).dn), 0.8, 4 * kEps);
  }
}

TEST(JacobiElliptic, CompleteThirdKindIntegralIsCorrectlyRoundedAlsoForLargeNegativeN) {
  // Reference values: Boost's Carlson forms in 50-digit arithmetic (cpp_bin_float_50) for these double
  // inputs. The Carlson form R_F + (n/3) R_J (each term correctly rounded, summed in double) cancels for
  // n ≪ −1 (4.4e-14 relative at n = −1e6); Bulirsch's cel (elliptic_Pi_complete) is within half an ulp.
  struct Ref {
    double n, m1, Pi;
  };
  const Ref refs[] = {
      {-1.78, 0.3, 1.157477079768482210839836},    {-1e3, 0.3, 0.05046398798773129214813433},
      {-1e6, 1e-8, 0.001580391381443460695026952}, {-0.01, 1e-12, 15.06116018251164706625495},
      {0.4, 0.9, 2.088633792489764898787574},      {-60.0, 1e-300, 5.867981885099428469721798},
  };
  for (const Ref& r : refs)
    EXPECT_NEAR(elliptic_Pi_complete(r.n, r.m1), r.Pi, kEps * r.Pi) << r.n << " " << r.m1;
  EXPECT_TRUE(std::isinf(elliptic_Pi_complete(-1.0, 0.0)));
}

TEST(JacobiElliptic, EllipticPiAgreesWithTheLongDoubleRouteToAFewUlps) {
  // EllipticPi evaluates its incomplete part with tumble's fixed-step R_F, R_J in double (≤ 3.3ε and
  // ≤ 5.3ε measured, math/carlson.hpp); the reference below is the same formula with the incomplete
  // integrals of Boost promoted to long double (elliptic_Pi_incomplete), including the reflection
  // about K.
  for (double m1 : {0.9, 0.4, 0.1, 1e-8}) {
    const JacobiElliptic f(1.0 - m1, m1);
    const double m = f.m();
    for (double n : {-0.01, -1.78, -60.0}) {
      const EllipticPi Pi(n, f);
      const double complete = elliptic_Pi_complete(n, m1);
      for (double u = -3.1 * f.K(); u <= 3.1 * f.K(); u += 0.07 * f.K()) {
        const JacobiValues v = f(u);
        double reference = 2.0 * v.j * complete;
        if (!v.reflected) {
          reference += elliptic_Pi_incomplete(n, v.sn_r, v.cn_r, v.dn);
        } else {
          const double b = m - n, n_reflected = b / (1.0 - n), c_Pi = -n * m1 / (b * (1.0 - n));
          const double Pi_v = elliptic_Pi_incomplete(n_reflected, v.sn_v, v.cn_v, v.dn_v);
          const double tail = m / b * v.v + c_Pi * Pi_v;
          reference += std::copysign(complete - tail, v.r);
        }
        // A few ulps of the incomplete part and the rounding of the sum. The incomplete part is
        // s R_F + (n/3) s³ R_J, two terms each as large as F(φ | m) ≤ K that cancel for n ≪ −1 (to
        // Π(n; φ) ~ F/√(1 − n)): a few ε of K, not of the result (measured: 1.8e-15 at m₁ = 1e-8,
        // n = −60, where K = 10.6 and the result 0.46).
        EXPECT_NEAR(Pi(v), reference, 8 * kEps * (complete + std::abs(reference) + f.K()))
            << "m1 = " << m1 << ", n = " << n << ", u = " << u;
      }
    }
  }
}

TEST(JacobiElliptic, RejectsParametersOutsideTheUnitInterval) {
  EXPECT_THROW(JacobiElliptic(1.5, -0.5), InvalidArgument);
  EXPECT_THROW(JacobiElliptic(0.5, 0.6), InvalidArgument);
  EXPECT_THROW(JacobiElliptic(std::nan(""), 0.5), InvalidArgument);
}

}  // namespace
}  // namespace tumble
