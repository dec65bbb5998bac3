// Closed-form primitives checked against independent integrations of the definitions:
//  - solids by slicing: m = ∫A(z)dz and the second moments of each cross-section, integrated with
//    Boost's tanh-sinh quadrature (handles the √ endpoint behaviour of round profiles);
//  - thin shells as the derivative of the solid under a uniform outward offset (the thin-wall limit:
//    shell(t) = solid(offset t) − solid + O(t²)), and surfaces of revolution by their ring integrals.
#include <gtest/gtest.h>

#include <boost/math/quadrature/tanh_sinh.hpp>
#include <cmath>
#include <functional>
#include <numbers>

#include "../support/random.hpp"
#include "tumble/error.hpp"
#include "tumble/mass/shapes.hpp"

namespace tumble {
namespace {

using std::numbers::pi;
using test::rel_diff;

double integrate(const std::function<double(double)>& f, double a, double b) {
  // Not const: Boost 1.74 declares integrate() const but defines it non-const.
  static boost::math::quadrature::tanh_sinh<double> rule;
  return rule.integrate(f, a, b, 1e-15);
}

/// A solid described by its cross-sections z ↦ (area A, ∫x² dA, ∫y² dA), each centred on the z axis.
struct Slices {
  std::function<Vec3(double)> section;
  std::vector<double> breaks;  // z range, split where the profile is not smooth
};

MassProperties by_slicing(const Slices& s) {
  auto part = [&](const std::function<double(double, const Vec3&)>& g) {
    double sum = 0;
    for (size_t i = 0; i + 1 < s.breaks.size(); ++i) {
      sum += integrate([&](double z) { return g(z, s.section(z)); }, s.breaks[i], s.breaks[i + 1]);
    }
    return sum;
  };
  const double m = part([](double, const Vec3& q) { return q(0); });
  const double zc = part([](double z, const Vec3& q) { return z * q(0); }) / m;
  const double xx = part([](double, const Vec3& q) { return q(1); });
  const double yy = part([](double, const Vec3& q) { return q(2); });
  const double zz = part([](double z, const Vec3& q) { return z * z * q(0); }) - m * zc * zc;
  return MassProperties{m, Vec3(0, 0, zc), Vec3(yy + zz, xx + zz, xx + yy).asDiagonal(), m};
}

Vec3 disk(double r) { return Vec3(pi * r * r, pi * std::pow(r, 4) / 4, pi * std::pow(r, 4) / 4); }
double safe_sqrt(double x) { return std::sqrt(std::max(0.0, x)); }

// Quadrature to 1e-15 of smooth (or √-endpoint) integrands, then a few dozen operations: 1e-12
// relative leaves a wide margin over both.
constexpr double kQuadrature = 1e-12;

void expect_same(const MassProperties& a, const MassProperties& b, double tol, const char* what) {
  EXPECT_NEAR(a.mass, b.mass, tol * b.mass) << what;
  EXPECT_LT((a.center_of_mass - b.center_of_mass).norm(), tol * std::cbrt(b.volume)) << what;
  EXPECT_LT(rel_diff(a.inertia, b.inertia), tol) << what;
  EXPECT_NEAR(a.volume, b.volume, tol * b.volume) << what;
}

TEST(Shapes, SolidsMatchIntegrationBySlicing) {
  const auto unit = MassSpec::density(1.0);
  {
    const double a = 0.3, b = 0.5, c = 0.7;
    expect_same(solid_mass_properties(Box{Vec3(a, b, c)}, unit),
                by_slicing({[&](double) { return Vec3(a * b, b * a * a * a / 12, a * b * b * b / 12); },
                            {-c / 2, c / 2}}),
                kQuadrature, "box");
  }
  {
    const double r = 0.4;
    expect_same(solid_mass_properties(Sphere{r}, unit),
                by_slicing({[&](double z) { return disk(safe_sqrt(r * r - z * z)); }, {-r, r}}), kQuadrature,
                "sphere");
  }
  {
    const double a = 0.3, b = 0.5, c = 0.8;
    auto section = [&](double z) {
      const double f = safe_sqrt(1 - z * z / (c * c));
      const double ai = a * f, bi = b * f;  // elliptical cross-section
      return Vec3(pi * ai * bi, pi * ai * ai * ai * bi / 4, pi * ai * bi * bi * bi / 4);
    };
    expect_same(solid_mass_properties(Ellipsoid{Vec3(a, b, c)}, unit), by_slicing({section, {-c, c}}),
                kQuadrature, "ellipsoid");
  }
  {
    const double r = 0.2, h = 0.9;
    expect_same(solid_mass_properties(Cylinder{r, h}, unit),
                by_slicing({[&](double) { return disk(r); }, {-h / 2, h / 2}}), kQuadrature, "cylinder");
  }
  {
    const double r = 0.25, h = 0.6;
    auto section = [&](double z) {
      const double e = std::abs(z) - h / 2;
      return disk(e <= 0 ? r : safe_sqrt(r * r - e * e));
    };
    expect_same(solid_mass_properties(Capsule{r, h}, unit),
                by_slicing({section, {-h / 2 - r, -h / 2, h / 2, h / 2 + r}}), kQuadrature, "capsule");
  }
  {
    const double r = 0.3, h = 1.1;
    expect_same(solid_mass_properties(Cone{r, h}, unit),
                by_slicing({[&](double z) { return disk(r * (1 - z / h)); }, {0, h}}), kQuadrature, "cone");
    EXPECT_DOUBLE_EQ(solid_mass_properties(Cone{r, h}, unit).center_of_mass.z(), h / 4);
  }
  {
    const double R = 0.5, r = 0.15;
    auto section = [&](double z) {
      const double w = safe_sqrt(r * r - z * z), ro = R + w, ri = R - w;  // annulus
      const double s4 = pi * (std::pow(ro, 4) - std::pow(ri, 4)) / 4;
      return Vec3(pi * (ro * ro - ri * ri), s4, s4);
    };
    expect_same(solid_mass_properties(Torus{R, r}, unit), by_slicing({section, {-r, r}}), kQuadrature,
                "torus");
  }
}

/// Thin-wall limit: shell per unit thickness = d/dε of the solid grown outward by ε.
/// Central difference: truncation O(ε²) = 1e-8 relative for ε = 1e-4·size, rounding 1e-16/ε = 1e-12.
void expect_shell_is_derivative(const Shape& shell, const std::function<Shape(double)>& grown,
                                const char* what) {
  const auto unit = MassSpec::density(1.0);
  const double eps = 1e-5;
  const MassProperties plus = solid_mass_properties(grown(eps), unit);
  const MassProperties minus = solid_mass_properties(grown(-eps), unit);
  const double dm = (plus.mass - minus.mass) / (2 * eps);
  // d/dε of the inertia about the (fixed, by symmetry) centre.
  const Mat3 dI = (plus.inertia - minus.inertia) / (2 * eps);
  // Surface density ρ·t = 16 · 0.0625 = 1 exactly, with a wall that fits inside every shape here.
  const MassProperties s = shell_mass_properties(shell, 0.0625, MassSpec::density(16.0));
  EXPECT_NEAR(s.mass, dm, 1e-7 * dm) << what;
  EXPECT_LT(rel_diff(s.inertia, dI), 1e-7) << what;
  EXPECT_NEAR(surface_area(shell), s.mass, 1e-14 * s.mass) << what;
}

TEST(Shapes, ShellsAreTheThinWallLimitOfSolids) {
  expect_shell_is_derivative(
      Box{Vec3(0.3, 0.5, 0.7)}, [](double e) { return Box{Vec3(0.3 + 2 * e, 0.5 + 2 * e, 0.7 + 2 * e)}; },
      "box");
  expect_shell_is_derivative(
      Sphere{0.4}, [](double e) { return Sphere{0.4 + e}; }, "sphere");
  expect_shell_is_derivative(
      Cylinder{0.2, 0.9},
      [](double e) {
        return Cylinder{0.2 + e, 0.9 + 2 * e};
      },
      "cylinder");
  expect_shell_is_derivative(
      Capsule{0.25, 0.6},
      [](double e) {
        return Capsule{0.25 + e, 0.6};
      },
      "capsule");
  expect_shell_is_derivative(
      Torus{0.5, 0.15},
      [](double e) {
        return Torus{0.5, 0.15 + e};
      },
      "torus");
}

TEST(Shapes, AShellWallMustFitInsideItsShape) {
  // The largest sphere inside each shape. The cone's touches the base and the side: in the section
  // through the axis it is the incircle of the triangle (base 2r, height h), radius = area / half
  // perimeter = r·h / (r + √(r² + h²)); for r = 3, h = 4 that is 12 / 8 = 1.5 exactly.
  EXPECT_EQ(inradius(Box{Vec3(0.3, 0.1, 0.7)}), 0.05);
  EXPECT_EQ(inradius(Sphere{2.0}), 2.0);
  EXPECT_EQ(inradius(Cylinder{0.5, 0.4}), 0.2);
  EXPECT_EQ(inradius(Cylinder{0.1, 0.4}), 0.1);
  EXPECT_EQ(inradius(Capsule{0.25, 3.0}), 0.25);
  EXPECT_EQ(inradius(Cone{3.0, 4.0}), 1.5);
  EXPECT_EQ(inradius(Torus{0.5, 0.15}), 0.15);
  // A wall of exactly the inradius fits; a thicker one is refused, saying how thick it may be.
  EXPECT_NO_THROW(shell_mass_properties(Sphere{1.0}, 1.0, MassSpec::density(1.0)));
  try {
    shell_mass_properties(Sphere{1.0}, 5.0, MassSpec::density(1.0));
    ADD_FAILURE() << "a 5 m wall on a 1 m sphere was accepted";
  } catch (const InvalidArgument& e) {
    EXPECT_EQ(
        std::string(e.what()),
        "shell thickness 5 m does not fit inside the sphere: its walls can be at most 1 m thick (the radius "
        "of the largest sphere inside it); for a thick-walled body subtract an inner solid as a hole");
  }
  EXPECT_THROW(shell_mass_properties(Cone{3.0, 4.0}, 1.6, MassSpec::density(1.0)), InvalidArgument);
}

TEST(Shapes, ConeShellMatchesRingIntegrals) {
  // Lateral surface z ∈ [0, h], radius ρ(z) = r(1 − z/h), ring area 2πρ·(s/h)dz with s the slant;
  // each ring has I_zz = ρ² dm and transverse (ρ²/2 + z²) dm. Plus the base disk at z = 0.
  const double r = 0.3, h = 1.1, s = std::hypot(r, h);
  auto rho = [&](double z) { return r * (1 - z / h); };
  auto dA = [&](double z) { return 2 * pi * rho(z) * s / h; };
  const double A = integrate(dA, 0, h);
  const double Az = integrate([&](double z) { return z * dA(z); }, 0, h);
  const double Arr = integrate([&](double z) { return rho(z) * rho(z) * dA(z); }, 0, h);
  const double Azz = integrate([&](double z) { return z * z * dA(z); }, 0, h);
  const double Ab = pi * r * r;  // base: ∫ρ² dA = πr⁴/2, at z = 0
  const double m = A + Ab, zc = Az / m;
  const double Izz = Arr + Ab * r * r / 2;
  const double Ixx = Arr / 2 + Azz + Ab * r * r / 4 - m * zc * zc;
  const MassProperties shell = shell_mass_properties(Cone{r, h}, 0.0625, MassSpec::density(16.0));  // ρt = 1
  EXPECT_NEAR(shell.mass, m, kQuadrature * m);
  EXPECT_NEAR(shell.center_of_mass.z(), zc, kQuadrature * h);
  EXPECT_NEAR(shell.inertia(2, 2), Izz, kQuadrature * Izz);
  EXPECT_NEAR(shell.inertia(0, 0), Ixx, kQuadrature * Ixx);
  EXPECT_NEAR(shell.inertia(1, 1), Ixx, kQuadrature * Ixx);
}

TEST(Shapes, DensityAndTotalMassAgree) {
  const Shape s = Capsule{0.1, 0.3};
  const MassProperties by_density = solid_mass_properties(s, MassSpec::density(2700.0));
  const MassProperties by_mass = solid_mass_properties(s, MassSpec::mass(by_density.mass));
  EXPECT_NEAR(by_mass.mass, by_density.mass, 1e-15 * by_density.mass);
  EXPECT_LT(rel_diff(by_mass.inertia, by_density.inertia), 1e-15 * 4);
  // A shell of given mass does not depend on the thickness; with a density it scales with it.
  const MassProperties thin = shell_mass_properties(s, 0.001, MassSpec::mass(2.0));
  const MassProperties thick = shell_mass_properties(s, 0.002, MassSpec::mass(2.0));
  EXPECT_EQ(thin.inertia, thick.inertia);
  EXPECT_NEAR(thick.volume, 2 * thin.volume, 1e-16);
  const MassProperties d1 = shell_mass_properties(s, 0.001, MassSpec::density(1000.0));
  const MassProperties d2 = shell_mass_properties(s, 0.002, MassSpec::density(1000.0));
  EXPECT_NEAR(d2.mass, 2 * d1.mass, 1e-15 * d2.mass);
}

TEST(Shapes, EveryPrimitiveIsAValidBody) {
  const std::vector<Shape> shapes = {
      Box{Vec3(0.1, 0.2, 0.3)}, Sphere{0.1},       Ellipsoid{Vec3(0.1, 0.2, 0.3)},
      Cylinder{0.1, 0.5},       Capsule{0.1, 0.2}, Cone{0.2, 0.1},
      Torus{0.3, 0.05}};
  for (const Shape& s : shapes) {
    EXPECT_NO_THROW(solid_mass_properties(s, MassSpec::density(1000)).validate()) << shape_name(s);
    if (!std::holds_alternative<Ellipsoid>(s)) {
      EXPECT_NO_THROW(shell_mass_properties(s, 1e-3, MassSpec::density(1000)).validate()) << shape_name(s);
    }
  }
}

TEST(Shapes, EllipsoidSurfaceAreaMatchesSpheroidClosedForms) {
  // Oblate spheroid a = b > c: S = 2πa²(1 + (1 − e²)/e · atanh e), e² = 1 − c²/a².
  const double a = 0.5, c = 0.2, e = std::sqrt(1 - c * c / (a * a));
  const double oblate = 2 * pi * a * a * (1 + (1 - e * e) / e * std::atanh(e));
  EXPECT_NEAR(surface_area(Ellipsoid{Vec3(a, a, c)}), oblate, 1e-14 * oblate);
  // Prolate a = b < c: S = 2πa²(1 + c/(a e) · asin e), e² = 1 − a²/c².
  const double cp = 0.9, ep = std::sqrt(1 - a * a / (cp * cp));
  const double prolate = 2 * pi * a * a * (1 + cp / (a * ep) * std::asin(ep));
  EXPECT_NEAR(surface_area(Ellipsoid{Vec3(cp, a, a)}), prolate, 1e-14 * prolate);
  EXPECT_NEAR(surface_area(Ellipsoid{Vec3(a, a, a)}), 4 * pi * a * a, 1e-15);
}

TEST(Shapes, BadDimensionsAreRejectedWithTheirName) {
  auto message = [](const Shape& s) {
    try {
      solid_mass_properties(s, MassSpec::density(1.0));
    } catch (const InvalidArgument& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_NE(message(Box{Vec3(0.1, -0.2, 0.3)}).find("box size y is -0.2"), std::string::npos);
  EXPECT_NE(message(Sphere{std::nan("")}).find("sphere radius is nan"), std::string::npos);
  EXPECT_NE(message(Torus{0.1, 0.2}).find("exceeds major radius"), std::string::npos);
  EXPECT_THROW(MassSpec::density(0.0), InvalidArgument);
  EXPECT_THROW(MassSpec::mass(-1.0), InvalidArgument);
  EXPECT_THROW(shell_mass_properties(Sphere{1.0}, 0.0, MassSpec::density(1.0)), InvalidArgument);
  EXPECT_THROW(shell_mass_properties(Ellipsoid{Vec3(1, 2, 3)}, 0.01, MassSpec::density(1.0)),
               InvalidArgument);
}

}  // namespace
}  // namespace tumble
