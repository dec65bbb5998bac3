// integrate_density() for primitive shapes: each shape is the image of a parameter box under a smooth
// map, integrated with Gauss–Legendre in the bounded parameters and the trapezoid rule in the periodic
// angles (maps and exactness: density.hpp). The point counts below are chosen for rule degree d, i.e.
// so that every polynomial integrand of total degree ≤ d in x (ρ of degree ≤ d − 2 times 1, x or x²)
// is integrated exactly; each count's comment gives the degree of the integrand in that parameter.
#include <cmath>
#include <fmt/format.h>

#include "density_moments.hpp"
#include "line_quadrature.hpp"
#include "tumble/mass/density.hpp"

namespace tumble {
namespace {

using detail::gauss_legendre;
using detail::LineRule;
using detail::MomentAccumulator;
using detail::periodic_trapezoid;

/// Gauss–Legendre points for a polynomial of degree `p` in one parameter: n = ⌈(p + 1)/2⌉.
int gauss_points(int p) { return (p + 2) / 2; }

struct Angles {
  std::vector<double> cos, sin, weight;
};

/// The trapezoid rule on [0, 2π) with n points, with cos and sin of its nodes.
Angles angles(int n) {
  const LineRule rule = periodic_trapezoid(n);
  Angles a;
  for (std::size_t k = 0; k < rule.nodes.size(); ++k) {
    a.cos.push_back(std::cos(rule.nodes[k]));
    a.sin.push_back(std::sin(rule.nodes[k]));
    a.weight.push_back(rule.weights[k]);
  }
  return a;
}

void box(MomentAccumulator& sum, const Box& s, int d) {
  // Degree ≤ d in each coordinate; dV = dx dy dz.
  const int n = gauss_points(d);
  const LineRule gx = gauss_legendre(n, -0.5 * s.size.x(), 0.5 * s.size.x());
  const LineRule gy = gauss_legendre(n, -0.5 * s.size.y(), 0.5 * s.size.y());
  const LineRule gz = gauss_legendre(n, -0.5 * s.size.z(), 0.5 * s.size.z());
  for (std::size_t i = 0; i < gx.nodes.size(); ++i) {
    for (std::size_t j = 0; j < gy.nodes.size(); ++j) {
      for (std::size_t k = 0; k < gz.nodes.size(); ++k) {
        sum.add(Vec3(gx.nodes[i], gy.nodes[j], gz.nodes[k]), gx.weights[i] * gy.weights[j] * gz.weights[k]);
      }
      sum.end_block();
    }
  }
}

/// The ellipsoidal region x = centre + semi ∘ r(√(1−u²)cos φ, √(1−u²)sin φ, u), r ∈ [0, 1],
/// u ∈ [u0, u1], dV = abc r² dr du dφ: a whole ellipsoid (u ∈ [−1, 1]) or a hemisphere.
void ball(MomentAccumulator& sum, const Vec3& semi, const Vec3& centre, double u0, double u1, int d) {
  // A monomial x^a y^b z^c (a + b + c ≤ d) is r^(a+b+c) (1−u²)^((a+b)/2) u^c cos^a φ sin^b φ times
  // the Jacobian r². φ: trigonometric degree ≤ d, so d + 1 points (an even count: then φ and φ + π are
  // both nodes and the φ sum is even in √(1−u²), hence a polynomial — or for smooth ρ an analytic
  // function — of u). u: degree ≤ d. r: degree ≤ d + 2.
  const LineRule gr = gauss_legendre(gauss_points(d + 2), 0.0, 1.0);
  const LineRule gu = gauss_legendre(gauss_points(d), u0, u1);
  const Angles phi = angles(d + 1);
  const double jacobian = semi.prod();
  for (std::size_t i = 0; i < gr.nodes.size(); ++i) {
    const double r = gr.nodes[i];
    for (std::size_t j = 0; j < gu.nodes.size(); ++j) {
      const double u = gu.nodes[j];
      const double rho_xy = r * std::sqrt((1.0 - u) * (1.0 + u));
      const double w = jacobian * r * r * gr.weights[i] * gu.weights[j];
      for (std::size_t k = 0; k < phi.cos.size(); ++k) {
        const Vec3 unit(rho_xy * phi.cos[k], rho_xy * phi.sin[k], r * u);
        sum.add(centre + semi.cwiseProduct(unit), w * phi.weight[k]);
      }
      sum.end_block();
    }
  }
}

/// Cylinder of radius R over z ∈ [z0, z1]: x = (s cos φ, s sin φ, z), dV = s ds dφ dz.
void cylinder(MomentAccumulator& sum, double R, double z0, double z1, int d) {
  // s^(a+b) times the Jacobian s: degree ≤ d + 1 in s; z: ≤ d; φ: trigonometric degree ≤ d.
  const LineRule gs = gauss_legendre(gauss_points(d + 1), 0.0, R);
  const LineRule gz = gauss_legendre(gauss_points(d), z0, z1);
  const Angles phi = angles(d + 1);
  for (std::size_t i = 0; i < gs.nodes.size(); ++i) {
    const double s = gs.nodes[i];
    for (std::size_t j = 0; j < gz.nodes.size(); ++j) {
      const double w = s * gs.weights[i] * gz.weights[j];
      for (std::size_t k = 0; k < phi.cos.size(); ++k) {
        sum.add(Vec3(s * phi.cos[k], s * phi.sin[k], gz.nodes[j]), w * phi.weight[k]);
      }
      sum.end_block();
    }
  }
}

void cone(MomentAccumulator& sum, const Cone& c, int d) {
  // x = (R(1−t)s cos φ, R(1−t)s sin φ, h t), dV = R²h (1−t)² s ds dt dφ. A monomial becomes
  // (1−t)^(a+b) t^c s^(a+b): with the Jacobian, degree ≤ d + 2 in t and ≤ d + 1 in s.
  const double R = c.radius, h = c.height;
  const LineRule gt = gauss_legendre(gauss_points(d + 2), 0.0, 1.0);
  const LineRule gs = gauss_legendre(gauss_points(d + 1), 0.0, 1.0);
  const Angles phi = angles(d + 1);
  for (std::size_t i = 0; i < gt.nodes.size(); ++i) {
    const double t = gt.nodes[i];
    const double radius = R * (1.0 - t);
    for (std::size_t j = 0; j < gs.nodes.size(); ++j) {
      const double s = gs.nodes[j];
      const double w = radius * radius * h * s * gt.weights[i] * gs.weights[j];
      for (std::size_t k = 0; k < phi.cos.size(); ++k) {
        sum.add(Vec3(radius * s * phi.cos[k], radius * s * phi.sin[k], h * t), w * phi.weight[k]);
      }
      sum.end_block();
    }
  }
}

void torus(MomentAccumulator& sum, const Torus& tor, int d) {
  // x = ((R + s cos θ)cos φ, (R + s cos θ)sin φ, s sin θ), dV = s(R + s cos θ) ds dθ dφ. A monomial
  // becomes (R + s cos θ)^(a+b) s^c sin^c θ cos^a φ sin^b φ: with the Jacobian, degree ≤ d + 2 in s,
  // trigonometric degree ≤ d + 1 in θ (d + 2 points) and ≤ d in φ (d + 1 points).
  const double R = tor.major_radius;
  const LineRule gs = gauss_legendre(gauss_points(d + 2), 0.0, tor.minor_radius);
  const Angles theta = angles(d + 2);
  const Angles phi = angles(d + 1);
  for (std::size_t i = 0; i < gs.nodes.size(); ++i) {
    const double s = gs.nodes[i];
    for (std::size_t j = 0; j < theta.cos.size(); ++j) {
      const double arm = R + s * theta.cos[j];  // distance from the z axis
      const double w = s * arm * gs.weights[i] * theta.weight[j];
      for (std::size_t k = 0; k < phi.cos.size(); ++k) {
        sum.add(Vec3(arm * phi.cos[k], arm * phi.sin[k], s * theta.sin[j]), w * phi.weight[k]);
      }
      sum.end_block();
    }
  }
}

template <class... Ts>
struct Overloaded : Ts... {
  using Ts::operator()...;
};
template <class... Ts>
Overloaded(Ts...) -> Overloaded<Ts...>;  // clang 14 does not deduce aggregates (P1816) yet

}  // namespace

DensityResult integrate_density(const Shape& shape, const DensityField& rho, int degree) {
  validate_shape(shape);
  const std::string where = shape_name(shape);
  const int d = detail::density_rule_degree(degree, rho, where);
  // Moments about the shape's centroid (the origin, or h/4 up the cone's axis).
  const Cone* cone_shape = std::get_if<Cone>(&shape);
  const Vec3 origin = cone_shape ? Vec3(0, 0, 0.25 * cone_shape->height) : Vec3::Zero();

  auto integrate = [&](int rule_degree) {
    MomentAccumulator sum(rho, origin, where);
    std::visit(
        Overloaded{
            [&](const Box& s) { box(sum, s, rule_degree); },
            [&](const Sphere& s) {
              ball(sum, Vec3::Constant(s.radius), Vec3::Zero(), -1.0, 1.0, rule_degree);
            },
            [&](const Ellipsoid& s) { ball(sum, s.semi_axes, Vec3::Zero(), -1.0, 1.0, rule_degree); },
            [&](const Cylinder& s) { cylinder(sum, s.radius, -0.5 * s.length, 0.5 * s.length, rule_degree); },
            [&](const Capsule& s) {
              const double h = 0.5 * s.length;
              const Vec3 semi = Vec3::Constant(s.radius);
              cylinder(sum, s.radius, -h, h, rule_degree);
              ball(sum, semi, Vec3(0, 0, h), 0.0, 1.0, rule_degree);    // top hemisphere
              ball(sum, semi, Vec3(0, 0, -h), -1.0, 0.0, rule_degree);  // bottom hemisphere
            },
            [&](const Cone& s) { cone(sum, s, rule_degree); },
            [&](const Torus& s) { torus(sum, s, rule_degree); },
        },
        shape);
    return sum.finish();
  };
  return detail::integrate_with_estimate(d, integrate);
}

}  // namespace tumble
