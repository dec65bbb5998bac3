// The dual-number type (math/dual.hpp): derivatives by the chain rule through each operation, checked
// against derivatives in closed form; through Eigen and through tumble's own equation templates (Euler's
// equation: its Jacobian in closed form); and on SIMD packs, lane by lane the same bits as on double.
#include <gtest/gtest.h>

#include <cmath>

#include "../support/random.hpp"
#include "tumble/dynamics/newton_euler.hpp"
#include "tumble/math/dual.hpp"
#include "tumble/math/simd.hpp"

namespace tumble {
namespace {

using D2 = Dual<double, 2>;
using D3 = Dual<double, 3>;

TEST(Dual, EachFunctionCarriesItsDerivative) {
  // f(x, y) = atan2(y, x) e^{sin x} / √(x² + y²) + hypot(x, y) log(y) cos(x y) − |x − 3|, at (0.7, 1.9),
  // against its partial derivatives written out by hand. The rules are exact; the two sides round in
  // different orders: 1e-14 relative.
  const double x0 = 0.7, y0 = 1.9;
  const D2 x = D2::variable(x0, 0), y = D2::variable(y0, 1);
  const D2 f = atan2(y, x) * exp(sin(x)) / sqrt(x * x + y * y) + hypot(x, y) * log(y) * cos(x * y) -
               abs(x - 3.0);
  const double r2 = x0 * x0 + y0 * y0, r = std::sqrt(r2), a = std::atan2(y0, x0), e = std::exp(std::sin(x0));
  const double g = std::log(y0), c = std::cos(x0 * y0), s = std::sin(x0 * y0);
  const double value = a * e / r + r * g * c - std::abs(x0 - 3.0);
  // ∂/∂x: atan2 gives −y/r², e^{sin x} gives cos x e^{sin x}, 1/r gives −x/r³; hypot gives x/r; cos(xy) gives −y sin(xy).
  const double fx = (-y0 / r2) * e / r + a * std::cos(x0) * e / r + a * e * (-x0 / (r2 * r)) +
                    (x0 / r) * g * c + r * g * (-y0 * s) + 1.0;
  const double fy = (x0 / r2) * e / r + a * e * (-y0 / (r2 * r)) + (y0 / r) * g * c + r * (1.0 / y0) * c +
                    r * g * (-x0 * s);
  EXPECT_NEAR(f.v, value, 1e-14 * std::abs(value));
  EXPECT_NEAR(f.d[0], fx, 1e-14 * std::abs(fx));
  EXPECT_NEAR(f.d[1], fy, 1e-14 * std::abs(fy));
}

TEST(Dual, ThroughEigenARotationsDerivativeIsTheSkewOfItsAxis) {
  // d/dθ (R_z(θ) v) = ẑ × R_z(θ) v: Eigen's AngleAxis and quaternion product on the dual scalar.
  const double theta = 0.8;
  const Vec3 v(0.3, -1.2, 2.0);
  const Dual<double, 1> t = Dual<double, 1>::variable(theta, 0);
  const Eigen::Quaternion<Dual<double, 1>> q(
      Eigen::AngleAxis<Dual<double, 1>>(t, Vec3T<Dual<double, 1>>::UnitZ()));
  const Vec3T<Dual<double, 1>> w = q * v.cast<Dual<double, 1>>();
  const Vec3 expected = Vec3::UnitZ().cross(Eigen::AngleAxisd(theta, Vec3::UnitZ()) * v);
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(w[k].d[0], expected[k], 1e-15) << k;
}

TEST(Dual, EulersEquationGivesItsJacobianInClosedForm) {
  // ω̇ = Λ⁻¹(τ − ω × Λω): ∂ω̇/∂ω = Λ⁻¹([Λω]× − [ω]× Λ), and ∂ω̇/∂Λ_k from the same template with the
  // moments as the variables. One instantiation of tumble's euler_body, no tangent written by hand.
  const Vec3 Lambda(1.0, 2.0, 3.5), omega(0.4, -2.0, 1.1), tau(0.1, 0.2, -0.3);
  Vec3T<D3> w;
  for (int k = 0; k < 3; ++k) w[k] = D3::variable(omega[k], k);
  const Vec3T<D3> rate = euler_body<D3>(mass_constants<D3>(D3(2.0), Lambda.cast<D3>()), w, tau.cast<D3>());
  const Mat3 J = Lambda.cwiseInverse().asDiagonal() *
                 (skew(Vec3(Lambda.cwiseProduct(omega))) - skew(omega) * Lambda.asDiagonal());
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) EXPECT_NEAR(rate[i].d[j], J(i, j), 1e-15) << i << "," << j;
  // ∂ω̇/∂Λ: component i is (τ − ω × Λω)_i / Λ_i; d/dΛ_k of it: −(ω × e_k ω_k)_i / Λ_i − δ_ik ω̇_i / Λ_i.
  Vec3T<D3> L;
  for (int k = 0; k < 3; ++k) L[k] = D3::variable(Lambda[k], k);
  const Vec3T<D3> by_moments =
      euler_body<D3>(mass_constants<D3>(D3(2.0), L), omega.cast<D3>(), tau.cast<D3>());
  const Vec3 rate0 = euler_body<double>(mass_constants<double>(2.0, Lambda), omega, tau);
  for (int k = 0; k < 3; ++k) {
    const Vec3 dL = -omega.cross(Vec3::Unit(k) * omega[k]).cwiseQuotient(Lambda);
    for (int i = 0; i < 3; ++i) {
      const double expected = dL[i] - (i == k ? rate0[i] / Lambda[i] : 0.0);
      EXPECT_NEAR(by_moments[i].d[k], expected, 1e-15) << i << "," << k;
    }
  }
}

TEST(Dual, OnPacksEachLaneIsTheScalarDualBitForBit) {
  using Pack = xsimd::batch<double>;
  using DP = Dual<Pack, 3>;
  constexpr std::size_t W = Pack::size;
  test::Random rng(11);
  alignas(64) double Lx[W], Ly[W], Lz[W], wx[W], wy[W], wz[W];
  for (std::size_t l = 0; l < W; ++l) {
    Lx[l] = rng.uniform(0.5, 2.0), Ly[l] = rng.uniform(0.5, 2.0), Lz[l] = rng.uniform(0.5, 2.0);
    wx[l] = rng.uniform(-3, 3), wy[l] = rng.uniform(-3, 3), wz[l] = rng.uniform(-3, 3);
  }
  const Vec3T<DP> Lp(DP(Pack::load_aligned(Lx)), DP(Pack::load_aligned(Ly)), DP(Pack::load_aligned(Lz)));
  const Vec3T<DP> wp(DP::variable(Pack::load_aligned(wx), 0), DP::variable(Pack::load_aligned(wy), 1),
                     DP::variable(Pack::load_aligned(wz), 2));
  // A rate and a norm on top of it: + − × ÷ and √ are correctly rounded on packs as on double, so the
  // lanes are the scalar's bits. The transcendental functions are xsimd's, not libm's: within 4 ulp.
  const Vec3T<DP> rp = euler_body<DP>(mass_constants<DP>(DP(1.0), Lp), wp, Vec3T<DP>::Zero());
  const DP gp = rp.x() * sqrt(rp.squaredNorm() + 1.0) / (rp.y() * rp.y() + 2.0);
  const DP hp = atan2(rp.y(), rp.x()) + sincos(rp.z()).first;
  for (std::size_t l = 0; l < W; ++l) {
    const Vec3T<D3> w(D3::variable(wx[l], 0), D3::variable(wy[l], 1), D3::variable(wz[l], 2));
    const Vec3T<D3> r = euler_body<D3>(
        mass_constants<D3>(D3(1.0), Vec3T<D3>(D3(Lx[l]), D3(Ly[l]), D3(Lz[l]))), w, Vec3T<D3>::Zero());
    const D3 g = r.x() * sqrt(r.squaredNorm() + 1.0) / (r.y() * r.y() + 2.0);
    const D3 h = atan2(r.y(), r.x()) + sincos(r.z()).first;
    EXPECT_EQ(gp.v.get(l), g.v) << "lane " << l;
    EXPECT_NEAR(hp.v.get(l), h.v, 4 * 2.220446049250313e-16 * std::abs(h.v)) << "lane " << l;
    for (std::size_t j = 0; j < 3; ++j) {
      EXPECT_EQ(gp.d[j].get(l), g.d[j]) << "lane " << l << ", direction " << j;
      EXPECT_NEAR(hp.d[j].get(l), h.d[j], 4 * 2.220446049250313e-16 * std::abs(h.d[j]))
          << "lane " << l << ", " << j;
    }
  }
}

}  // namespace
}  // namespace tumble
