// Carlson's R_J with a fixed number of duplication steps (math/carlson.hpp): accuracy over the domain
// the step counts are tuned for, against Boost in long double; closed forms; and the double,
// reference-pack and xsimd instantiations lane by lane.
#include "tumble/math/carlson.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <boost/math/special_functions/ellint_1.hpp>
#include <boost/math/special_functions/ellint_3.hpp>
#include <boost/math/special_functions/ellint_rd.hpp>
#include <boost/math/special_functions/ellint_rj.hpp>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <iterator>
#include <random>
#include <vector>

#include "../support/ref_pack.hpp"
#include "tumble/math/simd.hpp"

namespace tumble {
namespace {

constexpr double kEps = 2.220446049250313e-16;

using SimdPack = xsimd::batch<double>;
constexpr std::size_t W = SimdPack::size;
using RefPackW = test::RefPack<W>;

/// |a − b|/|b| in units of ε, b in long double (Boost's value: a few long-double ulps, ε/2048 each).
double relative_error(double a, long double b) {
  return static_cast<double>(std::abs(static_cast<long double>(a) - b) / std::abs(b)) / kEps;
}

/// The arguments as elliptic_pi forms them at a Landen point (sn, cn, dn at |arg| ≤ K/2): m₁ = k′²,
/// x = cn² ∈ [k′/(1 + k′), 1], y = dn² = x + m₁ s² with s² = 1 − x, z = 1, and for R_J
/// p = 1 + N s² (n = −N ≤ 0) or, at a reflected point, p = 1 − n′ s² with n′ = (m + N)/(1 + N) ∈ [m, 1)
/// (x ≤ p ≤ y there). N up to 1e12, m₁ down to 1e-16, and the corners: m₁ = 1e-16 with the smallest
/// x, N = 0 (p = z: e_m = 0) and N = 1e12, s → 0 (x → 1).
struct Arguments {
  double x, y, p, p_reflected;
  int rj_steps;  // carlson_rj_steps(N, m₁), for both p
};

/// R_J with the most steps any characteristic of the domain needs (N = 1e12): for checks of the
/// formula itself rather than of the step counts.
constexpr int kMostSteps = 28;
double rj_most(double x, double y, double z, double p) {
  return carlson_rj(x, y, z, p, double(kMostSteps), kMostSteps);
}

std::vector<Arguments> domain() {
  std::mt19937_64 rng(20240611);
  auto uniform = [&] { return static_cast<double>(rng() >> 11) * 0x1p-53; };
  auto log_uniform = [&](double lo, double hi) { return lo * std::pow(hi / lo, uniform()); };
  std::vector<Arguments> points;
  for (int i = 0; i < 4000; ++i) {
    const double m1 = i % 5 == 0 ? 1e-16 : i % 5 == 1 ? 1.0 : log_uniform(1e-16, 1.0);
    const double k1 = std::sqrt(m1), x_min = k1 / (1.0 + k1);  // cn²(K/2)
    double x = log_uniform(x_min, 1.0);
    if (i % 6 == 0) x = x_min;
    if (i % 6 == 1) x = 1.0 - log_uniform(1e-20, 1.0 - x_min);  // s → 0 (x = 1 below s² = ε/2)
    const double s2 = 1.0 - x, y = x + m1 * s2;
    const double N = i % 7 == 0 ? 0.0 : i % 7 == 1 ? 1e12 : log_uniform(1e-6, 1e12);
    points.push_back({x, y, 1.0 + N * s2, 1.0 - ((1.0 - m1) + N) / (1.0 + N) * s2, carlson_rj_steps(N, m1)});
  }
  return points;
}

TEST(Carlson, RJIsAccurateOverTheTunedDomain) {
  // Each R_J with the step count of its flow (carlson_rj_steps), the count the exact flow uses; lanes
  // of one pack have different counts. Rounding: each duplication step rounds √, λ and the new
  // variables (a few roundings on each), and the variables carry the error of the earlier steps; R_J
  // adds its sum of M terms (compensated). The truncation of the series is ≤ 0.05ε here (carlson.hpp).
  // Measured on 1.6e6 points of this domain with the counts from N alone: ≤ 5.3ε (mean 0.57ε), the
  // same on the SIMD pack (its own atan). Bound: 6ε (on these 4000 points the worst is ~3.8ε).
  const std::vector<Arguments> points = domain();
  double worst_rj = 0, worst_rj_reflected = 0, worst_simd = 0;
  for (std::size_t i = 0; i < points.size(); i += W) {
    alignas(64) double x[W], y[W], p[W], q[W], steps[W], rj_p[W], rj_reflected[W];
    int max_steps = 0;
    for (std::size_t l = 0; l < W; ++l) {
      const Arguments& a = points[(i + l) % points.size()];
      x[l] = a.x, y[l] = a.y, p[l] = a.p, q[l] = a.p_reflected, steps[l] = a.rj_steps;
      max_steps = std::max(max_steps, a.rj_steps);
    }
    const SimdPack px = SimdPack::load_aligned(x), py = SimdPack::load_aligned(y), one(1.0);
    const SimdPack ps = SimdPack::load_aligned(steps);
    carlson_rj<SimdPack>(px, py, one, SimdPack::load_aligned(p), ps, max_steps).store_aligned(rj_p);
    carlson_rj<SimdPack>(px, py, one, SimdPack::load_aligned(q), ps, max_steps).store_aligned(rj_reflected);
    for (std::size_t l = 0; l < W; ++l) {
      const long double X = static_cast<long double>(x[l]), Y = static_cast<long double>(y[l]);
      const long double RJ = boost::math::ellint_rj(X, Y, 1.0L, static_cast<long double>(p[l]));
      const long double RJ_reflected = boost::math::ellint_rj(X, Y, 1.0L, static_cast<long double>(q[l]));
      const int n_steps = static_cast<int>(steps[l]);
      const double e_rj = relative_error(carlson_rj(x[l], y[l], 1.0, p[l], steps[l], n_steps), RJ);
      const double e_rj_reflected =
          relative_error(carlson_rj(x[l], y[l], 1.0, q[l], steps[l], n_steps), RJ_reflected);
      const double e_simd =
          std::max(relative_error(rj_p[l], RJ), relative_error(rj_reflected[l], RJ_reflected));
      EXPECT_LE(e_rj, 6.0) << "R_J(" << x[l] << ", " << y[l] << ", 1, " << p[l] << ")";
      EXPECT_LE(e_rj_reflected, 6.0) << "R_J(" << x[l] << ", " << y[l] << ", 1, " << q[l] << ")";
      EXPECT_LE(e_simd, 6.0) << "SIMD pack at x = " << x[l] << ", y = " << y[l];
      worst_rj = std::max(worst_rj, e_rj);
      worst_rj_reflected = std::max(worst_rj_reflected, e_rj_reflected);
      worst_simd = std::max(worst_simd, e_simd);
    }
  }
  std::printf(
      "[ measured ] relative errors on %zu points: R_J %.2f eps (p >= 1), %.2f eps (reflected, p <= 1), "
      "SIMD pack %.2f eps\n",
      points.size(), worst_rj, worst_rj_reflected, worst_simd);
}

TEST(Carlson, SeriesTruncationIsOfEighthOrder) {
  // With no duplication step carlson_rj is its series alone, at arguments spread by δ about 1: the 7th-
  // order series (carlson.hpp) leaves O(δ⁸), so halving δ divides the error by 2⁸ = 256 (a 5th-order
  // series: 2⁶ = 64; a wrong 7th-order term: 2⁷ = 128). carlson_rj_steps counts the steps for this
  // order. At these δ the truncation (≥ 1e3 ε) dwarfs rounding, so the ratios are the order's, up to
  // the next order's share (±15 % here). Three directions of spread, so that every E_k takes part.
  struct Direction {
    double x, y, p;  // x = 1 + δ·x etc., z = 1; p ≥ x, y, z keeps δ ≥ 0
  };
  for (const Direction d :
       {Direction{-1.0, 0.5, 0.8}, Direction{-1.0, -0.3, 1.0}, Direction{-0.2, -1.0, 0.4}}) {
    const auto truncation = [&](double delta) {
      const double x = 1.0 + d.x * delta, y = 1.0 + d.y * delta, p = 1.0 + d.p * delta;
      const long double reference = boost::math::ellint_rj(
          static_cast<long double>(x), static_cast<long double>(y), 1.0L, static_cast<long double>(p));
      return relative_error(carlson_rj(x, y, 1.0, p, 0.0, 0), reference);
    };
    const double e1 = truncation(0.2), e2 = truncation(0.1), e3 = truncation(0.05);
    std::printf("[ measured ] series alone: relative error %.3g, %.3g, %.3g eps at delta = 0.2, 0.1, 0.05\n",
                e1, e2, e3);
    EXPECT_GT(e3, 1e3);  // truncation, not rounding
    for (const double ratio : {e1 / e2, e2 / e3}) {
      EXPECT_GT(ratio, 200.0) << d.x << " " << d.y << " " << d.p;
      EXPECT_LT(ratio, 330.0) << d.x << " " << d.y << " " << d.p;
    }
  }
}

TEST(Carlson, ClosedForms) {
  using L = long double;
  for (double x : {1e-8, 0.3, 1.0, 7.0}) {
    // Equal arguments: R_J(x, x, x, x) = x^{−3/2} (DLMF 19.20.5).
    EXPECT_LE(relative_error(rj_most(x, x, x, x), 1 / (L(x) * std::sqrt(L(x)))), 3.0) << x;
  }
  // R_J(x, y, z, z) = R_D(x, y, z) (p = z: every e_m = 0, R_C = 1 exactly).
  EXPECT_LE(relative_error(rj_most(0.3, 0.5, 1.0, 1.0), boost::math::ellint_rd(L(0.3), L(0.5), L(1))), 4.0);
  // R_J(x, x, x, p) = 3(x^{−1/2} − R_C(x, p))/(p − x), R_C(x, p) = atan(√((p − x)/x))/√(p − x) for p > x
  // (DLMF 19.20.15 with y = x, 19.2.18).
  for (double p : {0.5, 4.0, 1e6}) {
    const L x = 0.25L, P = static_cast<L>(p), rc = std::atan(std::sqrt((P - x) / x)) / std::sqrt(P - x);
    EXPECT_LE(relative_error(rj_most(0.25, 0.25, 0.25, p), 3 * (1 / std::sqrt(x) - rc) / (P - x)), 4.0) << p;
  }
  // Legendre's integral of the third kind (DLMF 19.25.14) against Boost in long double, φ and m where
  // the Landen points put them (|φ| ≤ am(K/2)) and Boost's modulus-only form is well conditioned
  // (m ≤ 0.9): Π(n; φ | m) = F + (n/3) s³ R_J(c², Δ², 1, 1 − n s²), with F = F(φ | m) from Boost rounded
  // to double (the flow has it exactly: it is the Jacobi argument). The bound adds the rounding of s,
  // c, Δ², F and of the sum to R_J's (measured ≤ 1.8ε). Only moderate n: for n ≪ −1 the sum itself
  // cancels (Π ~ 1/√N against F ~ 1), and its error grows like √N ε (measured 20ε at n = −1e3, 330ε at
  // −1e6) whatever R_J.
  for (double m : {0.0, 0.3, 0.9}) {
    for (double phi : {0.1, 0.5, 0.7}) {
      const double s = std::sin(phi), c = std::cos(phi), d2 = c * c + (1.0 - m) * s * s;
      const L k = std::sqrt(L(m)), phi_l = static_cast<L>(phi);
      const double F = static_cast<double>(boost::math::ellint_1(k, phi_l));
      for (double n : {-0.5, -10.0}) {
        const int steps = carlson_rj_steps(-n, 1.0 - m);
        const double Pi = F + n / 3.0 * s * s * s *
                                  carlson_rj(c * c, d2, 1.0, 1.0 - n * s * s, double(steps), steps);
        EXPECT_LE(relative_error(Pi, boost::math::ellint_3(k, L(n), phi_l)), 6.0)
            << m << ", " << phi << ", " << n;
      }
    }
  }
}

/// ulps between two finite doubles of the same sign.
std::uint64_t ulps(double a, double b) {
  const auto i = std::bit_cast<std::int64_t>(a), j = std::bit_cast<std::int64_t>(b);
  return static_cast<std::uint64_t>(i > j ? i - j : j - i);
}

TEST(Carlson, DoublesReferencePackAndSimdPackAgreeLaneByLane) {
  // Lanes mix magnitudes (x from 1e-8 to 1, p from x to 1e12), and lanes where p = z (e_m = 0: the
  // Taylor branch of R_C, whose atan branch sees e = 1 instead of 0/0) sit beside lanes where e_m ≈ 1.
  // A template that branched on one lane's value would give the other lanes a wrong step count or
  // branch: far more than the ulps allowed below. Each lane has the R_J step count of its own p, the
  // pack runs the largest: a lane must still compute the bits of its own count.
  constexpr std::size_t kPacks = 6;
  const double xs[] = {1e-8, 3e-5, 0.02, 0.4, 0.9999, 1.0, 0.7};
  const double ps[] = {1.0, 1e12, 2.5, 1.0, 1e4, -1.0, 1.0 + 1e-9, 37.0, 1.0, 3e8, -1.0};  // −1: reflected
  alignas(64) double x[kPacks * W], y[kPacks * W], z[kPacks * W], p[kPacks * W], steps[kPacks * W];
  for (std::size_t i = 0; i < kPacks * W; ++i) {
    x[i] = xs[i % std::size(xs)];
    y[i] = x[i] + (1.0 - x[i]) * std::pow(10.0, -static_cast<double>(i % 9) * 2);  // dn² = cn² + m₁ s²
    z[i] = 1.0;
    const double p_i = ps[i % std::size(ps)];
    p[i] = p_i > 0.0 ? p_i : x[i] + 0.5 * (y[i] - x[i]);  // p ≥ 1 = z, or x ≤ p ≤ y
    // Any count serves a bit-for-bit check; this is a flow's with m₁ = y − x (= m₁ s², here).
    steps[i] = carlson_rj_steps(std::max(0.0, p[i] - 1.0), y[i] - x[i]);
  }
  for (std::size_t i = 0; i < kPacks * W; i += W) {
    alignas(64) double ref_rj[W], simd_rj[W];
    const int max_steps = static_cast<int>(*std::max_element(steps + i, steps + i + W));
    using RL = Lanes<RefPackW>;
    const RefPackW rx = RL::load(x + i), ry = RL::load(y + i), rz = RL::load(z + i), rp = RL::load(p + i);
    RL::store(ref_rj, carlson_rj<RefPackW>(rx, ry, rz, rp, RL::load(steps + i), max_steps));
    using SL = Lanes<SimdPack>;
    const SimdPack sx = SL::load(x + i), sy = SL::load(y + i), sz = SL::load(z + i), sp = SL::load(p + i);
    SL::store(simd_rj, carlson_rj<SimdPack>(sx, sy, sz, sp, SL::load(steps + i), max_steps));
    for (std::size_t l = 0; l < W; ++l) {
      const std::size_t k = i + l;
      const double rj = carlson_rj(x[k], y[k], z[k], p[k], steps[k], static_cast<int>(steps[k]));
      ASSERT_TRUE(std::isfinite(rj)) << k;
      // The reference pack applies the same scalar operations: bit for bit.
      EXPECT_EQ(std::bit_cast<std::uint64_t>(ref_rj[l]), std::bit_cast<std::uint64_t>(rj))
          << "R_J, lane " << k;
      // R_J's R_C uses xsimd's own atan polynomial, which may round the last bit differently from
      // glibc's: a few terms of the sum, each off by an ulp or so.
      EXPECT_LE(ulps(simd_rj[l], rj), 4u) << "R_J, lane " << k << ": " << simd_rj[l] << " vs " << rj;
    }
  }
}

}  // namespace
}  // namespace tumble
