// Non-uniform density ρ(x) (include/tumble/mass/density.hpp), checked against independent methods:
//  - the quadrature rules against exact monomial integrals (a!b!c!/(a+b+c+3)! on the unit tetrahedron);
//  - polynomial densities on boxes and box-shaped meshes (convex and L-shaped) against exact monomial
//    integrals evaluated in long double, and a hand-derived closed form;
//  - every primitive against integration by slicing (Boost's tanh-sinh over z of closed-form
//    cross-section moments), and uniform density against the closed forms of shapes.hpp;
//  - the graded sphere and cylinder against their closed forms;
//  - ρ = exp(κ·x) against closed forms / slicing, for convergence and the error estimate.
#include <gtest/gtest.h>

#include <boost/math/quadrature/tanh_sinh.hpp>
#include <cmath>
#include <fmt/format.h>
#include <functional>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

#include "../support/random.hpp"
#include "mass/line_quadrature.hpp"  // private to the mass layer: src/ is on the tests' include path
#include "mass/tet_quadrature.hpp"
#include "tumble/error.hpp"
#include "tumble/mass/density.hpp"
#include "tumble/mass/mesh_mass.hpp"
#include "tumble/mass/shapes.hpp"

namespace tumble {
namespace {

using std::numbers::pi;
using test::rel_diff;
constexpr double eps = std::numeric_limits<double>::epsilon();

// ---- reference moments ------------------------------------------------------------------------

using LVec = Eigen::Matrix<long double, 3, 1>;
using LMat = Eigen::Matrix<long double, 3, 3>;
long double wide(double x) { return static_cast<long double>(x); }

/// Raw moments ∫ρ, ∫ρx, ∫ρxxᵀ about the origin, in long double so that the reference's own rounding
/// (1e-19) is far below the 1e-13 the library is held to.
struct RawMoments {
  long double m = 0;
  LVec first = LVec::Zero();
  LMat second = LMat::Zero();
  long double volume = 0;

  RawMoments& operator+=(const RawMoments& o) {
    m += o.m;
    first += o.first;
    second += o.second;
    volume += o.volume;
    return *this;
  }
  /// c = M₁/m, S = M₂ − m c cᵀ, I = tr(S)I₃ − S.
  MassProperties properties() const {
    const LVec c = first / m;
    const LMat S = second - m * c * c.transpose();
    const LMat I = S.trace() * LMat::Identity() - S;
    return MassProperties{static_cast<double>(m), c.cast<double>(), I.cast<double>(),
                          static_cast<double>(volume)};
  }
};

/// Moments of a separable density ρ = Πᵢ fᵢ(xᵢ) over a box, from each axis's ∫xᵏ fᵢ, k = 0, 1, 2.
RawMoments separable(const std::array<std::array<long double, 3>, 3>& F, long double volume) {
  RawMoments r;
  r.m = F[0][0] * F[1][0] * F[2][0];
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      std::array<int, 3> k{0, 0, 0};
      ++k[i];
      ++k[j];
      r.second(i, j) = F[0][k[0]] * F[1][k[1]] * F[2][k[2]];
    }
    std::array<int, 3> k{0, 0, 0};
    ++k[i];
    r.first(i) = F[0][k[0]] * F[1][k[1]] * F[2][k[2]];
  }
  r.volume = volume;
  return r;
}

/// A polynomial density Σ coef · x^a y^b z^c.
struct Term {
  double coef;
  int a, b, c;
};
using Polynomial = std::vector<Term>;

double evaluate(const Polynomial& p, const Vec3& x) {
  double s = 0;
  for (const Term& t : p) s += t.coef * std::pow(x.x(), t.a) * std::pow(x.y(), t.b) * std::pow(x.z(), t.c);
  return s;
}

/// 1 plus every monomial of degree 1..p with a coefficient drawn from [−0.4, 0.4].
Polynomial random_polynomial(test::Random& rng, int p) {
  Polynomial poly{{1.0, 0, 0, 0}};
  for (int a = 0; a <= p; ++a) {
    for (int b = 0; a + b <= p; ++b) {
      for (int c = 0; a + b + c <= p; ++c) {
        if (a + b + c > 0) poly.push_back({rng.uniform(-0.4, 0.4), a, b, c});
      }
    }
  }
  return poly;
}

/// Exact moments of a polynomial density over the box [lo, hi]: ∫xᵏ dx = (hiᵏ⁺¹ − loᵏ⁺¹)/(k + 1).
RawMoments polynomial_on_box(const Polynomial& poly, const Vec3& lo, const Vec3& hi) {
  RawMoments total;
  for (const Term& t : poly) {
    std::array<std::array<long double, 3>, 3> F;
    const std::array<int, 3> e{t.a, t.b, t.c};
    for (int i = 0; i < 3; ++i) {
      for (int k = 0; k < 3; ++k) {
        const int n = e[i] + k + 1;
        F[i][k] =
            (std::pow(static_cast<long double>(hi(i)), n) - std::pow(static_cast<long double>(lo(i)), n)) / n;
      }
    }
    RawMoments part = separable(F, 0);
    part.m *= wide(t.coef);
    part.first *= wide(t.coef);
    part.second *= wide(t.coef);
    total += part;
  }
  total.volume = wide((hi - lo).prod());
  return total;
}

/// Exact moments of ρ = ρ₀ exp(κ·x) over the box [lo, hi], from the antiderivatives
///   ∫e^{kx} = e^{kx}/k,  ∫x e^{kx} = e^{kx}(x/k − 1/k²),  ∫x² e^{kx} = e^{kx}(x²/k − 2x/k² + 2/k³).
RawMoments exponential_on_box(double rho0, const Vec3& kappa, const Vec3& lo, const Vec3& hi) {
  std::array<std::array<long double, 3>, 3> F;
  for (int i = 0; i < 3; ++i) {
    const long double k = wide(kappa(i));
    auto anti = [&](long double x) {
      const long double e = std::exp(k * x);
      return std::array<long double, 3>{e / k, e * (x / k - 1 / (k * k)),
                                        e * (x * x / k - 2 * x / (k * k) + 2 / (k * k * k))};
    };
    const auto a = anti(wide(lo(i))), b = anti(wide(hi(i)));
    for (int n = 0; n < 3; ++n) F[i][n] = b[n] - a[n];
  }
  RawMoments r = separable(F, wide((hi - lo).prod()));
  r.m *= wide(rho0);
  r.first *= wide(rho0);
  r.second *= wide(rho0);
  return r;
}

// ---- integration by slicing (independent of the library's parametric maps) --------------------

double integrate(const std::function<double(double)>& f, double a, double b) {
  // Not const: Boost 1.74 declares integrate() const but defines it non-const.
  static boost::math::quadrature::tanh_sinh<double> rule;
  return rule.integrate(f, a, b, 1e-15);
}
double safe_sqrt(double x) { return std::sqrt(std::max(0.0, x)); }

/// Cross-section at height z, symmetric under x → −x and y → −y: (area A, ∫x² dA, ∫y² dA).
struct Slices {
  std::function<Vec3(double)> section;
  std::vector<double> breaks;  // z range, split where the profile is not smooth
};

Vec3 disk(double r) { return Vec3(pi * r * r, pi * std::pow(r, 4) / 4, pi * std::pow(r, 4) / 4); }

/// Moments of ρ = ρ₀(g(z) + αx) with g(z) = 1 + βz + γz². On a symmetric section the odd moments in x
/// and y vanish, so per slice: ∫ρ = ρ₀gA, ∫ρx = ρ₀αQx, ∫ρx² = ρ₀gQx, ∫ρy² = ρ₀gQy, ∫ρxz = zρ₀αQx,
/// ∫ρz = zρ₀gA, ∫ρz² = z²ρ₀gA, and ∫ρy = ∫ρxy = ∫ρyz = 0.
MassProperties by_slicing(const Slices& s, double rho0, double alpha, double beta, double gamma) {
  auto part = [&](const std::function<double(double, const Vec3&)>& f) {
    double sum = 0;
    for (size_t i = 0; i + 1 < s.breaks.size(); ++i) {
      sum += integrate([&](double z) { return f(z, s.section(z)); }, s.breaks[i], s.breaks[i + 1]);
    }
    return rho0 * sum;
  };
  auto g = [&](double z) { return 1 + beta * z + gamma * z * z; };
  RawMoments r;
  r.m = wide(part([&](double z, const Vec3& q) { return g(z) * q(0); }));
  r.first(0) = wide(part([&](double, const Vec3& q) { return alpha * q(1); }));
  r.first(2) = wide(part([&](double z, const Vec3& q) { return z * g(z) * q(0); }));
  r.second(0, 0) = wide(part([&](double z, const Vec3& q) { return g(z) * q(1); }));
  r.second(1, 1) = wide(part([&](double z, const Vec3& q) { return g(z) * q(2); }));
  r.second(2, 2) = wide(part([&](double z, const Vec3& q) { return z * z * g(z) * q(0); }));
  r.second(0, 2) = r.second(2, 0) = wide(part([&](double z, const Vec3& q) { return z * alpha * q(1); }));
  r.volume = wide(part([](double, const Vec3& q) { return q(0); }) / rho0);
  return r.properties();
}

/// The slicing description of each primitive (as in shapes_test.cpp).
Slices slices_of(const Shape& shape) {
  if (const auto* b = std::get_if<Box>(&shape)) {
    const double x = b->size.x(), y = b->size.y(), z = b->size.z();
    return {[=](double) { return Vec3(x * y, y * x * x * x / 12, x * y * y * y / 12); }, {-z / 2, z / 2}};
  }
  if (const auto* s = std::get_if<Sphere>(&shape)) {
    const double r = s->radius;
    return {[=](double z) { return disk(safe_sqrt(r * r - z * z)); }, {-r, r}};
  }
  if (const auto* e = std::get_if<Ellipsoid>(&shape)) {
    const Vec3 ax = e->semi_axes;
    return {[=](double z) {
              const double f = safe_sqrt(1 - z * z / (ax.z() * ax.z()));
              const double a = ax.x() * f, b = ax.y() * f;  // elliptical section
              return Vec3(pi * a * b, pi * a * a * a * b / 4, pi * a * b * b * b / 4);
            },
            {-ax.z(), ax.z()}};
  }
  if (const auto* c = std::get_if<Cylinder>(&shape)) {
    const double r = c->radius, h = c->length;
    return {[=](double) { return disk(r); }, {-h / 2, h / 2}};
  }
  if (const auto* c = std::get_if<Capsule>(&shape)) {
    const double r = c->radius, h = c->length;
    return {[=](double z) {
              const double e = std::abs(z) - h / 2;
              return disk(e <= 0 ? r : safe_sqrt(r * r - e * e));
            },
            {-h / 2 - r, -h / 2, h / 2, h / 2 + r}};
  }
  if (const auto* c = std::get_if<Cone>(&shape)) {
    const double r = c->radius, h = c->height;
    return {[=](double z) { return disk(r * (1 - z / h)); }, {0, h}};
  }
  const auto& t = std::get<Torus>(shape);
  const double R = t.major_radius, r = t.minor_radius;
  return {[=](double z) {
            const double w = safe_sqrt(r * r - z * z), ro = R + w, ri = R - w;  // annulus
            const double q = pi * (std::pow(ro, 4) - std::pow(ri, 4)) / 4;
            return Vec3(pi * (ro * ro - ri * ri), q, q);
          },
          {-r, r}};
}

std::vector<Shape> all_shapes() {
  return {Box{Vec3(0.6, 0.9, 1.3)}, Sphere{0.7},        Ellipsoid{Vec3(0.5, 0.8, 1.1)},
          Cylinder{0.4, 1.2},       Capsule{0.35, 0.9}, Cone{0.6, 1.4},
          Torus{0.8, 0.3}};
}

// ---- meshes -----------------------------------------------------------------------------------

/// The prism over a counter-clockwise polygon in the xy plane, from z0 to z1, with outward normals.
/// The caps are fanned from polygon vertex 0, so vertex 0 must see every other vertex (true for a
/// convex polygon, and for an L whose reflex corner comes first).
TriangleMesh prism(const std::vector<Eigen::Vector2d>& polygon, double z0, double z1) {
  TriangleMesh mesh;
  const auto n = static_cast<std::uint32_t>(polygon.size());
  for (const auto& p : polygon) mesh.vertices.emplace_back(p.x(), p.y(), z0);  // bottom: 0..n−1
  for (const auto& p : polygon) mesh.vertices.emplace_back(p.x(), p.y(), z1);  // top: n..2n−1
  for (std::uint32_t i = 1; i + 1 < n; ++i) {
    mesh.triangles.push_back({0, i + 1, i});          // bottom, seen from −z
    mesh.triangles.push_back({n, n + i, n + i + 1});  // top, seen from +z
  }
  for (std::uint32_t i = 0; i < n; ++i) {
    const std::uint32_t j = (i + 1) % n;  // side quad b_i b_j t_j t_i, outward for a CCW polygon
    mesh.triangles.push_back({i, j, n + j});
    mesh.triangles.push_back({i, n + j, n + i});
  }
  return mesh;
}

/// The 12-triangle mesh of the box [lo, hi].
TriangleMesh box_mesh(const Vec3& lo, const Vec3& hi) {
  return prism({{lo.x(), lo.y()}, {hi.x(), lo.y()}, {hi.x(), hi.y()}, {lo.x(), hi.y()}}, lo.z(), hi.z());
}

TriangleMesh inside_out(TriangleMesh mesh) {
  for (auto& t : mesh.triangles) std::swap(t[1], t[2]);
  return mesh;
}

// ---- comparison -------------------------------------------------------------------------------

/// The metric of DensityResult::estimated_error: max of |Δm|/m, max|ΔI|/max|I|, |Δc|/k, k the
/// radius of gyration √(tr I / 2m).
double relative_error(const MassProperties& got, const MassProperties& ref) {
  const double k = std::sqrt(ref.inertia.trace() / (2 * ref.mass));
  return std::max({std::abs(got.mass - ref.mass) / ref.mass, rel_diff(got.inertia, ref.inertia),
                   (got.center_of_mass - ref.center_of_mass).norm() / k});
}

void expect_close(const MassProperties& got, const MassProperties& ref, double tol, const std::string& what) {
  EXPECT_NEAR(got.mass, ref.mass, tol * ref.mass) << what;
  const double k = std::sqrt(ref.inertia.trace() / (2 * ref.mass));
  EXPECT_LT((got.center_of_mass - ref.center_of_mass).norm(), tol * k) << what;
  EXPECT_LT(rel_diff(got.inertia, ref.inertia), tol) << what;
  EXPECT_NEAR(got.volume, ref.volume, tol * ref.volume) << what;
}

// Exact rules on polynomial data, then a few dozen operations on O(1) numbers. The returned rule's
// negative weights amplify rounding by Σ|w| ≤ 25 up to degree 9 (density.hpp), so errors stay near
// 25 · 1e-16 · (a few) ≈ 1e-14; 1e-13 leaves a margin.
constexpr double kRounding = 1e-13;
// The slicing reference integrates to tanh-sinh's 1e-15 target (as in shapes_test.cpp); 1e-12 leaves a
// wide margin over it and over rounding.
constexpr double kSlicing = 1e-12;

// ---- the rules themselves ---------------------------------------------------------------------

double factorial(int n) { return n <= 1 ? 1.0 : n * factorial(n - 1); }

TEST(DensityQuadrature, GrundmannMollerIsExactForEveryMonomialUpToItsDegree) {
  // Unit tetrahedron (0, e_x, e_y, e_z): ∫ x^a y^b z^c dV = a! b! c! / (a + b + c + 3)!.
  for (int d = 1; d <= kMaxDensityDegree + 2; d += 2) {
    const detail::TetRule rule = detail::grundmann_moller_tet(d);
    const int s = (d - 1) / 2;
    EXPECT_EQ(rule.weights.size(), static_cast<size_t>(factorial(s + 4) / (24 * factorial(s))));
    for (int a = 0; a <= d + 1; ++a) {
      for (int b = 0; a + b <= d + 1; ++b) {
        for (int c = 0; a + b + c <= d + 1; ++c) {
          double q = 0, magnitude = 0;
          for (size_t k = 0; k < rule.weights.size(); ++k) {
            const Eigen::Vector4d& l = rule.barycentric[k];
            const double f = std::pow(l(1), a) * std::pow(l(2), b) * std::pow(l(3), c);
            q += rule.weights[k] * f / 6.0;
            magnitude += std::abs(rule.weights[k] * f) / 6.0;
          }
          const double exact = factorial(a) * factorial(b) * factorial(c) / factorial(a + b + c + 3);
          // Recursive summation of n products: |error| ≤ (n + 2) ε Σ|w_k f_k| (Higham, Accuracy and
          // Stability, §4.2); a wrong weight or node would be off by orders of magnitude more.
          const double bound = (rule.weights.size() + 2) * eps * magnitude;
          if (a + b + c <= d) {
            EXPECT_NEAR(q, exact, bound) << "degree " << d << " monomial " << a << b << c;
          } else if (a == d + 1) {
            // x^(d+1) is not integrated exactly: the degree claim is tight.
            EXPECT_GT(std::abs(q - exact), 1e3 * bound) << "degree " << d;
          }
        }
      }
    }
  }
}

TEST(DensityQuadrature, GaussLegendreIsExactUpToDegreeTwoNMinusOne) {
  for (int n = 1; n <= 12; ++n) {
    const detail::LineRule rule = detail::gauss_legendre(n, -0.3, 1.1);
    ASSERT_EQ(rule.nodes.size(), static_cast<size_t>(n));
    for (int p = 0; p <= 2 * n; ++p) {
      double q = 0;
      for (int k = 0; k < n; ++k) q += rule.weights[k] * std::pow(rule.nodes[k], p);
      const double exact = (std::pow(1.1, p + 1) - std::pow(-0.3, p + 1)) / (p + 1);
      // Positive weights, terms ≤ 1.1^p: rounding a few ε relative to Σ|w f| ≤ 1.4 · 1.1^p.
      const double bound = 16 * n * eps * 1.4 * std::pow(1.1, p);
      if (p < 2 * n) {
        EXPECT_NEAR(q, exact, bound) << n << " points, x^" << p;
      } else {
        EXPECT_GT(std::abs(q - exact), 10 * bound) << n << " points, x^" << p;
      }
    }
  }
}

// ---- polynomial densities: exact --------------------------------------------------------------

TEST(Density, BoxWithCubicDensityMatchesHandDerivedClosedForm) {
  // ρ = ρ₀(1 + αx + βy² + γxy + δz³) on the box [−A, A]×[−B, B]×[−C, C], V = 8ABC. Over a symmetric
  // interval odd powers integrate to 0, ∫x² = V A²/3 (per unit of the other two), ∫x⁴ = V A⁴/5:
  //   m    = ρ₀V(1 + βB²/3)
  //   m cx = ∫ρx = ρ₀αVA²/3,   m cy = 0,   m cz = ∫ρz = ρ₀δVC⁴/5
  //   ∫ρx² = ρ₀V(A²/3 + βA²B²/9),  ∫ρy² = ρ₀V(B²/3 + βB⁴/5),  ∫ρz² = ρ₀V(C²/3 + βB²C²/9)
  //   ∫ρxy = ρ₀γVA²B²/9,  ∫ρxz = ∫ρyz = 0
  // and I = tr(S)I₃ − S with S = ∫ρxxᵀ − m c cᵀ.
  const double A = 0.4, B = 0.25, C = 0.6, rho0 = 2700;
  const double alpha = 0.8, beta = -1.5, gamma = 2.0, delta = 1.2;
  const double V = 8 * A * B * C;
  auto rho = [&](const Vec3& x) {
    return rho0 *
           (1 + alpha * x.x() + beta * x.y() * x.y() + gamma * x.x() * x.y() + delta * std::pow(x.z(), 3));
  };
  const double m = rho0 * V * (1 + beta * B * B / 3);
  const Vec3 c(rho0 * alpha * V * A * A / 3 / m, 0, rho0 * delta * V * std::pow(C, 4) / 5 / m);
  Mat3 J;
  J << rho0 * V * (A * A / 3 + beta * A * A * B * B / 9), rho0 * gamma * V * A * A * B * B / 9, 0,
      rho0 * gamma * V * A * A * B * B / 9, rho0 * V * (B * B / 3 + beta * std::pow(B, 4) / 5), 0, 0, 0,
      rho0 * V * (C * C / 3 + beta * B * B * C * C / 9);
  const Mat3 S = J - m * c * c.transpose();
  const MassProperties exact{m, c, S.trace() * Mat3::Identity() - S, V};

  // Degree 5: exact for ρ of degree ≤ 3.
  const DensityResult r = integrate_density(Box{Vec3(2 * A, 2 * B, 2 * C)}, rho, 5);
  EXPECT_EQ(r.degree, 7);
  expect_close(r.properties, exact, kRounding, "box, cubic density");
  EXPECT_LT(r.estimated_error, kRounding);  // both rules exact: the estimate is rounding
  // The same body as a 12-triangle mesh.
  const DensityResult rm = integrate_density(box_mesh(Vec3(-A, -B, -C), Vec3(A, B, C)), rho, 5);
  expect_close(rm.properties, exact, kRounding, "cube mesh, cubic density");
  EXPECT_LT(rm.estimated_error, kRounding);
}

TEST(Density, PolynomialDensityOnOffCentreCubeMeshIsExactAtEveryDegree) {
  test::Random rng(11);
  const Vec3 lo(-0.3, -0.6, 0.1), hi(0.9, 0.2, 0.8);  // off-centre: the fan apex is not the origin
  const TriangleMesh mesh = box_mesh(lo, hi);
  ASSERT_EQ(mesh.triangles.size(), 12u);
  for (int degree = kMinDensityDegree; degree <= kMaxDensityDegree; ++degree) {
    const Polynomial poly = random_polynomial(rng, degree - 2);  // the highest degree claimed exact
    const MassProperties exact = polynomial_on_box(poly, lo, hi).properties();
    const DensityResult r = integrate_density(
        mesh, [&](const Vec3& x) { return evaluate(poly, x); }, degree);
    // Up to degree 9 the rounding argument of kRounding holds; beyond, Σ|w| of the returned rule
    // (54 at 11 ... 545 at 17) multiplies the rounding, so the bound scales with it: Σ|w|·1e-15.
    const double sum_abs_w = [&] {
      double s = 0;
      for (double w : detail::grundmann_moller_tet(r.degree).weights) s += std::abs(w);
      return s;
    }();
    const double tol = std::max(kRounding, sum_abs_w * 1e-15);
    expect_close(r.properties, exact, tol, fmt::format("cube mesh, degree {}", degree));
    EXPECT_LT(r.estimated_error, tol) << degree;
  }
}

TEST(Density, PolynomialDensityOnNonConvexMeshIsExactAndSampledInTheConvexHull) {
  // An L-shaped prism with long thin arms: the union of the boxes [0,1]×[0,¼] and [0,¼]×[¼,1]
  // (× [z0, z1]). Its centroid (19/56, 19/56) lies in the notch, outside the solid, so the signed fan
  // folds back and ρ is also sampled outside the solid — but only in the convex hull
  // {0 ≤ x, y ≤ 1, x + y ≤ 5/4}, and the outside contributions cancel exactly.
  const double z0 = -0.2, z1 = 0.5;
  const TriangleMesh mesh =
      prism({{0.25, 0.25}, {0.25, 1}, {0, 1}, {0, 0}, {1, 0}, {1, 0.25}}, z0, z1);  // reflex corner first
  test::Random rng(12);
  const Polynomial poly = random_polynomial(rng, 3);
  RawMoments exact = polynomial_on_box(poly, Vec3(0, 0, z0), Vec3(1, 0.25, z1));
  exact += polynomial_on_box(poly, Vec3(0, 0.25, z0), Vec3(0.25, 1, z1));

  bool sampled_outside = false;
  double hull_violation = 0;
  auto rho = [&](const Vec3& x) {
    hull_violation = std::max(
        {hull_violation, -x.x(), -x.y(), x.x() - 1, x.y() - 1, x.x() + x.y() - 1.25, z0 - x.z(), x.z() - z1});
    if (x.x() > 0.25 && x.y() > 0.25) sampled_outside = true;
    return evaluate(poly, x);
  };
  const DensityResult r = integrate_density(mesh, rho, 5);
  expect_close(r.properties, exact.properties(), kRounding, "L-shaped mesh");
  EXPECT_TRUE(sampled_outside) << "the fan of an L-shape reaches outside the solid";
  EXPECT_LE(hull_violation, 1e-15);  // inside the hull up to rounding of the coordinates
}

TEST(Density, InsideOutMeshIsFlippedAndGivesTheSameBody) {
  const TriangleMesh mesh = box_mesh(Vec3(0.1, 0.2, 0.3), Vec3(0.7, 1.1, 0.9));
  auto rho = [](const Vec3& x) { return 500 * (1 + x.x() * x.y() - 0.5 * x.z() * x.z()); };
  const DensityResult outward = integrate_density(mesh, rho, 4);
  const DensityResult flipped = integrate_density(inside_out(mesh), rho, 4);
  expect_close(flipped.properties, outward.properties, kRounding, "inside-out cube");
  EXPECT_GT(flipped.properties.mass, 0);
  EXPECT_TRUE(outward.warnings.empty());
  ASSERT_EQ(flipped.warnings.size(), 1u);
  EXPECT_NE(flipped.warnings[0].find("inside-out"), std::string::npos) << flipped.warnings[0];
}

TEST(Density, UniformDensityEqualsTheClosedFormOfEveryPrimitive) {
  const double rho0 = 7850;
  for (const Shape& shape : all_shapes()) {
    // Degree 2 is enough for a constant ρ (the inertia integrand is quadratic).
    const DensityResult r = integrate_density(
        shape, [&](const Vec3&) { return rho0; }, 2);
    const MassProperties exact = solid_mass_properties(shape, MassSpec::density(rho0));
    expect_close(r.properties, exact, kRounding, shape_name(shape));
    EXPECT_LT(r.estimated_error, kRounding) << shape_name(shape);
  }
}

TEST(Density, QuadraticDensityOnEveryPrimitiveMatchesSlicing) {
  // ρ = ρ₀(1 + αx + βz + γz²): exact at degree 4. αx shifts the centre of mass sideways and, with z,
  // creates the product of inertia I_xz — so the test sees every entry the maps produce.
  const double rho0 = 1000, alpha = 0.6, beta = -0.4, gamma = 0.3;
  auto rho = [&](const Vec3& x) { return rho0 * (1 + alpha * x.x() + beta * x.z() + gamma * x.z() * x.z()); };
  for (const Shape& shape : all_shapes()) {
    const DensityResult r = integrate_density(shape, rho, 4);
    expect_close(r.properties, by_slicing(slices_of(shape), rho0, alpha, beta, gamma), kSlicing,
                 shape_name(shape));
    EXPECT_LT(r.estimated_error, kRounding) << shape_name(shape);
    EXPECT_GT(std::abs(r.properties.inertia(0, 2)), 1e-3 * r.properties.inertia.maxCoeff())
        << shape_name(shape) << ": the product of inertia is really exercised";
  }
}

TEST(Density, SphereWithRadialDensityMatchesClosedForm) {
  // ρ = ρ₀(1 + k r²): m = ∫4πr²ρ dr = 4πρ₀(R³/3 + kR⁵/5); every axis has I = (2/3)∫ρ r² dV
  // = (8π/3)ρ₀(R⁵/5 + kR⁷/7). Degree 4 is exact (ρ is quadratic).
  const double R = 0.35, rho0 = 1200, k = 3.0;
  const DensityResult r = integrate_density(
      Sphere{R}, [&](const Vec3& x) { return rho0 * (1 + k * x.squaredNorm()); }, 4);
  const double m = 4 * pi * rho0 * (std::pow(R, 3) / 3 + k * std::pow(R, 5) / 5);
  const double I = 8 * pi / 3 * rho0 * (std::pow(R, 5) / 5 + k * std::pow(R, 7) / 7);
  expect_close(r.properties,
               MassProperties{m, Vec3::Zero(), Mat3(I * Mat3::Identity()), 4 * pi / 3 * R * R * R}, kRounding,
               "graded sphere");
}

TEST(Density, LinearlyGradedCylinderShiftsItsCentreOfMassAsTheClosedFormSays) {
  // Cylinder radius R, length L, ρ = ρ₀(1 + g z): m = ρ₀πR²L (∫z = 0); m c_z = ρ₀ g πR² ∫z²dz
  // = ρ₀ g πR² L³/12, so c_z = gL²/12. About the centre: I_zz = ∫ρ(x² + y²) = ρ₀πR⁴L/2 (the g term
  // is odd in z) and I_xx = ∫ρ(y² + z²) − m c_z² = ρ₀(πR⁴L/4 + πR²L³/12) − m c_z².
  const double R = 0.15, L = 0.8, rho0 = 900, g = 1.7;
  {
    const DensityResult r = integrate_density(
        Cylinder{R, L}, [&](const Vec3& x) { return rho0 * (1 + g * x.z()); }, 3);
    const double m = rho0 * pi * R * R * L, cz = g * L * L / 12;
    const double Ixx = rho0 * (pi * std::pow(R, 4) * L / 4 + pi * R * R * std::pow(L, 3) / 12) - m * cz * cz;
    const double Izz = rho0 * pi * std::pow(R, 4) * L / 2;
    expect_close(r.properties,
                 MassProperties{m, Vec3(0, 0, cz), Vec3(Ixx, Ixx, Izz).asDiagonal(), pi * R * R * L},
                 kRounding, "cylinder graded along z");
  }
  {
    // Graded across: ρ = ρ₀(1 + g x), c_x = g∫x² dA / A = gR²/4; I_yy = ∫ρ(x² + z²) − m c_x²,
    // I_zz = ∫ρ(x² + y²) − m c_x², with ∫x² dV = πR⁴L/4 and ∫z² dV = πR²L³/12.
    const DensityResult r = integrate_density(
        Cylinder{R, L}, [&](const Vec3& x) { return rho0 * (1 + g * x.x()); }, 3);
    const double m = rho0 * pi * R * R * L, cx = g * R * R / 4;
    const double x2 = rho0 * pi * std::pow(R, 4) * L / 4, z2 = rho0 * pi * R * R * std::pow(L, 3) / 12;
    const Vec3 diag(x2 + z2, x2 + z2 - m * cx * cx, 2 * x2 - m * cx * cx);
    expect_close(r.properties, MassProperties{m, Vec3(cx, 0, 0), diag.asDiagonal(), pi * R * R * L},
                 kRounding, "cylinder graded along x");
  }
}

// ---- non-polynomial density: convergence and the error estimate -------------------------------

/// Runs degrees 3, 5, ..., 15 against `exact` and checks: the estimate falls with the degree until it
/// reaches rounding, and bounds the true error of the returned result.
void expect_converges(const std::function<DensityResult(int)>& run, const MassProperties& exact, double floor,
                      const std::string& what) {
  double previous = std::numeric_limits<double>::infinity();
  bool reached_floor = false;
  for (int degree = 3; degree <= kMaxDensityDegree; degree += 2) {
    const DensityResult r = run(degree);
    const double truth = relative_error(r.properties, exact);
    EXPECT_LE(truth, std::max(r.estimated_error, floor)) << what << ", degree " << degree;
    if (previous > floor) {
      EXPECT_LT(r.estimated_error, previous) << what << ", degree " << degree;
    }
    reached_floor = reached_floor || r.estimated_error <= floor;
    previous = r.estimated_error;
  }
  EXPECT_TRUE(reached_floor) << what << ": exp(κ·x) is entire, so convergence is exponential";
}

TEST(Density, ExponentialDensityConvergesAndTheEstimateBoundsTheError) {
  const double rho0 = 800;
  const Vec3 kappa(1.5, -2.0, 0.7);
  auto rho = [&](const Vec3& x) { return rho0 * std::exp(kappa.dot(x)); };
  // The exact references carry ~1e-16 (long double closed forms) and ~1e-15 (tanh-sinh); rounding in
  // the rules adds Σ|w|·ε ≲ 1e-13 at the top degree: the floor below which differences are noise.
  const double floor = 1e-13;
  {
    const Vec3 half(0.6, 0.4, 0.5);
    const MassProperties exact = exponential_on_box(rho0, kappa, -half, half).properties();
    expect_converges([&](int d) { return integrate_density(Box{2 * half}, rho, d); }, exact, floor, "box");
    const Vec3 lo(-0.3, -0.6, 0.1), hi(0.9, 0.2, 0.8);
    const MassProperties exact_mesh = exponential_on_box(rho0, kappa, lo, hi).properties();
    expect_converges([&](int d) { return integrate_density(box_mesh(lo, hi), rho, d); }, exact_mesh, floor,
                     "cube mesh");
  }
  {
    // Sphere with ρ = ρ₀ exp(k z): slices are disks of radius √(R² − z²) at density ρ₀e^{kz}; the
    // reference integrates in z with tanh-sinh (g(z) = e^{kz} in the slicing helper's notation).
    const double R = 0.6, k = 2.5;
    auto rho_z = [&](const Vec3& x) { return rho0 * std::exp(k * x.z()); };
    const Slices ball = slices_of(Sphere{R});
    auto part = [&](const std::function<double(double, const Vec3&)>& f) {
      return rho0 * integrate([&](double z) { return std::exp(k * z) * f(z, ball.section(z)); }, -R, R);
    };
    RawMoments raw;
    raw.m = wide(part([](double, const Vec3& q) { return q(0); }));
    raw.first(2) = wide(part([](double z, const Vec3& q) { return z * q(0); }));
    raw.second(0, 0) = raw.second(1, 1) = wide(part([](double, const Vec3& q) { return q(1); }));
    raw.second(2, 2) = wide(part([](double z, const Vec3& q) { return z * z * q(0); }));
    raw.volume = wide(4 * pi / 3 * R * R * R);
    expect_converges([&](int d) { return integrate_density(Sphere{R}, rho_z, d); }, raw.properties(), floor,
                     "sphere");
  }
}

// ---- bad input ---------------------------------------------------------------------------------

template <class E, class F>
std::string message_of(F&& f) {
  try {
    f();
  } catch (const E& e) {
    return e.what();
  }
  ADD_FAILURE() << "expected an exception";
  return {};
}

TEST(Density, DegreeOutsideTheSupportedRangeIsAnError) {
  auto one = [](const Vec3&) { return 1.0; };
  const TriangleMesh cube = box_mesh(Vec3::Zero(), Vec3::Ones());
  for (int degree : {-1, 0, 1, kMaxDensityDegree + 1, 100}) {
    const std::string msg = message_of<InvalidArgument>([&] { integrate_density(Sphere{1.0}, one, degree); });
    EXPECT_NE(msg.find(fmt::format("quadrature degree {} is out of the supported range [2, 15]", degree)),
              std::string::npos)
        << msg;
    EXPECT_NE(message_of<InvalidArgument>([&] {
                integrate_density(cube, one, degree, "cube.stl");
              }).find("mesh 'cube.stl': quadrature degree"),
              std::string::npos);
  }
}

TEST(Density, NonFiniteDensityNamesThePoint) {
  const TriangleMesh cube = box_mesh(Vec3::Zero(), Vec3::Ones());
  for (const double bad :
       {std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity()}) {
    Vec3 first_bad = Vec3::Constant(-1);
    auto rho = [&](const Vec3& x) {
      if (x.x() > 0.6) {
        first_bad = x;
        return bad;
      }
      return 1.0;
    };
    const std::string msg_shape = message_of<InvalidArgument>([&] {
      integrate_density(Cylinder{1.0, 2.0}, rho, 5);
    });
    EXPECT_NE(msg_shape.find(fmt::format("cylinder: the density function returned {} kg/m^3", bad)),
              std::string::npos)
        << msg_shape;
    EXPECT_NE(msg_shape.find(fmt::format("x = ({:.17g}, {:.17g}, {:.17g}) m", first_bad.x(), first_bad.y(),
                                         first_bad.z())),
              std::string::npos)
        << msg_shape;
    const std::string msg_mesh =
        message_of<InvalidArgument>([&] { integrate_density(cube, rho, 5, "cube.stl"); });
    EXPECT_NE(msg_mesh.find(fmt::format("x = ({:.17g}, {:.17g}, {:.17g}) m", first_bad.x(), first_bad.y(),
                                        first_bad.z())),
              std::string::npos)
        << msg_mesh;
    EXPECT_NE(msg_mesh.find("in the fan tetrahedron of triangle"), std::string::npos) << msg_mesh;
  }
}

TEST(Density, NonPositiveTotalMassIsAnError) {
  for (const double value : {0.0, -3.0}) {
    const std::string msg = message_of<InvalidArgument>([&] {
      integrate_density(
          Torus{1.0, 0.2}, [&](const Vec3&) { return value; }, 3);
    });
    EXPECT_NE(msg.find("torus: the density integrates to a total mass of"), std::string::npos) << msg;
    EXPECT_NE(msg.find("which is not positive"), std::string::npos) << msg;
  }
}

TEST(Density, EmptyDensityFunctionAndInvalidShapeAreErrors) {
  const std::string msg =
      message_of<InvalidArgument>([] { integrate_density(Sphere{1.0}, DensityField{}, 4); });
  EXPECT_NE(msg.find("sphere: the density function is empty"), std::string::npos) << msg;
  EXPECT_THROW(integrate_density(
                   Sphere{-1.0}, [](const Vec3&) { return 1.0; }, 4),
               InvalidArgument);
}

TEST(Density, OpenMeshIsAMeshError) {
  TriangleMesh open = box_mesh(Vec3::Zero(), Vec3::Ones());
  open.triangles.pop_back();  // a hole: two boundary edges... three, around the missing triangle
  EXPECT_THROW(integrate_density(
                   open, [](const Vec3&) { return 1.0; }, 4, "open.stl"),
               MeshError);
}

}  // namespace
}  // namespace tumble
