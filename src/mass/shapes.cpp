// Closed-form mass properties of the primitive shapes, solid and thin-shell.
//
// Every function first builds the unit-density ("per unit measure") properties — mass equal to the
// volume for solids, to the area for shells — and MassSpec scales them. Composite shapes (capsule, cone
// shell, box shell) are assembled from simpler pieces with MassProperties::operator+, so the
// parallel-axis bookkeeping lives in one place.
#include "tumble/mass/shapes.hpp"

#include <boost/math/special_functions/ellint_1.hpp>
#include <boost/math/special_functions/ellint_2.hpp>
#include <cmath>
#include <fmt/format.h>
#include <numbers>

#include "tumble/error.hpp"

namespace tumble {
namespace {

using std::numbers::pi;

template <class... Ts>
struct Overloaded : Ts... {
  using Ts::operator()...;
};
template <class... Ts>
Overloaded(Ts...) -> Overloaded<Ts...>;  // Clang 14 does not deduce aggregate bases without it

/// Unit-density body with principal moments `k` (per unit mass) about its centre, placed at c.
MassProperties unit_body(double measure, const Vec3& k, const Vec3& c = Vec3::Zero(), double volume = 0.0) {
  return MassProperties{measure, c, Mat3(measure * k.asDiagonal()), volume};
}

Mat3 flip_z() { return Vec3(1.0, -1.0, -1.0).asDiagonal(); }  // rotation by π about x

// ---- solids (unit density) -------------------------------------------------------------------

MassProperties solid_hemisphere(double r) {
  // Flat face at z = 0, dome towards +z. About the sphere centre every axis has 2/5 m r²; the centre of
  // mass is 3r/8 above the face, so the transverse moments about it lose m (3r/8)².
  const double V = 2.0 / 3.0 * pi * r * r * r;
  const double zc = 3.0 * r / 8.0;
  const double k = 0.4 * r * r;
  return unit_body(V, Vec3(k - zc * zc, k - zc * zc, k), Vec3(0, 0, zc), V);
}

MassProperties solid_cylinder(double r, double h) {
  const double V = pi * r * r * h;
  const double kx = (3.0 * r * r + h * h) / 12.0;  // I_xx = m(3r² + h²)/12
  return unit_body(V, Vec3(kx, kx, 0.5 * r * r), Vec3::Zero(), V);
}

MassProperties solid_unit(const Shape& shape) {
  return std::visit(
      Overloaded{
          [](const Box& s) {
            const double V = s.size.prod();
            const Vec3 q = s.size.cwiseProduct(s.size);  // I_xx = m(b² + c²)/12
            return unit_body(V, Vec3(q.y() + q.z(), q.x() + q.z(), q.x() + q.y()) / 12.0, Vec3::Zero(), V);
          },
          [](const Sphere& s) {
            const double V = 4.0 / 3.0 * pi * std::pow(s.radius, 3);
            return unit_body(V, Vec3::Constant(0.4 * s.radius * s.radius), Vec3::Zero(), V);
          },
          [](const Ellipsoid& s) {
            const double V = 4.0 / 3.0 * pi * s.semi_axes.prod();
            const Vec3 q = s.semi_axes.cwiseProduct(s.semi_axes);  // I_xx = m(b² + c²)/5
            return unit_body(V, Vec3(q.y() + q.z(), q.x() + q.z(), q.x() + q.y()) / 5.0, Vec3::Zero(), V);
          },
          [](const Cylinder& s) { return solid_cylinder(s.radius, s.length); },
          [](const Capsule& s) {
            const Vec3 top(0, 0, 0.5 * s.length);
            return solid_cylinder(s.radius, s.length) +
                   solid_hemisphere(s.radius).transformed(Mat3::Identity(), top) +
                   solid_hemisphere(s.radius).transformed(flip_z(), -top);
          },
          [](const Cone& s) {
            // Base at z = 0, apex at z = h: centre of mass h/4 above the base; I_zz = 3/10 m r²,
            // transverse about the centre of mass m(3r²/20 + 3h²/80).
            const double r = s.radius, h = s.height;
            const double V = pi * r * r * h / 3.0;
            const double kx = 3.0 * r * r / 20.0 + 3.0 * h * h / 80.0;
            return unit_body(V, Vec3(kx, kx, 0.3 * r * r), Vec3(0, 0, 0.25 * h), V);
          },
          [](const Torus& s) {
            // Pappus: V = 2π²Rr²; I_zz = m(R² + 3r²/4), I_xx = m(R²/2 + 5r²/8).
            const double R = s.major_radius, r = s.minor_radius;
            const double V = 2.0 * pi * pi * R * r * r;
            const double kx = 0.5 * R * R + 5.0 / 8.0 * r * r;
            return unit_body(V, Vec3(kx, kx, R * R + 0.75 * r * r), Vec3::Zero(), V);
          },
      },
      shape);
}

// ---- thin shells (unit surface density) --------------------------------------------------------

MassProperties rectangle_plate(double a, double b, const Vec3& centre, int normal_axis) {
  // A plate a × b in the plane perpendicular to `normal_axis`; a along the next axis cyclically.
  const double A = a * b;
  Vec3 k;
  const int i = (normal_axis + 1) % 3, j = (normal_axis + 2) % 3;
  k(normal_axis) = (a * a + b * b) / 12.0;
  k(i) = b * b / 12.0;  // about the in-plane axis along a, only the extent b counts
  k(j) = a * a / 12.0;
  return unit_body(A, k, centre);
}

MassProperties disk(double r, double z) {
  const double A = pi * r * r;  // I_zz = m r²/2, transverse m r²/4
  return unit_body(A, Vec3(0.25 * r * r, 0.25 * r * r, 0.5 * r * r), Vec3(0, 0, z));
}

MassProperties cylinder_wall(double r, double h) {
  const double A = 2.0 * pi * r * h;  // I_zz = m r², transverse m(r²/2 + h²/12)
  const double kx = 0.5 * r * r + h * h / 12.0;
  return unit_body(A, Vec3(kx, kx, r * r));
}

MassProperties hemisphere_shell(double r) {
  // Flat side at z = 0: centre of mass r/2 above it; about the sphere centre every axis has 2/3 m r².
  const double A = 2.0 * pi * r * r;
  const double zc = 0.5 * r;
  const double k = 2.0 / 3.0 * r * r;
  return unit_body(A, Vec3(k - zc * zc, k - zc * zc, k), Vec3(0, 0, zc));
}

MassProperties shell_unit(const Shape& shape) {
  return std::visit(
      Overloaded{
          [](const Box& s) {
            const double a = s.size.x(), b = s.size.y(), c = s.size.z();
            MassProperties sum = rectangle_plate(a, b, Vec3(0, 0, 0.5 * c), 2);
            sum += rectangle_plate(a, b, Vec3(0, 0, -0.5 * c), 2);
            sum += rectangle_plate(b, c, Vec3(0.5 * a, 0, 0), 0);
            sum += rectangle_plate(b, c, Vec3(-0.5 * a, 0, 0), 0);
            sum += rectangle_plate(c, a, Vec3(0, 0.5 * b, 0), 1);
            sum += rectangle_plate(c, a, Vec3(0, -0.5 * b, 0), 1);
            return sum;
          },
          [](const Sphere& s) {
            const double r = s.radius;  // I = 2/3 m r²
            return unit_body(4.0 * pi * r * r, Vec3::Constant(2.0 / 3.0 * r * r));
          },
          [](const Ellipsoid&) -> MassProperties {
            throw InvalidArgument(
                "a thin ellipsoidal shell has no closed form (its surface integrals are elliptic); "
                "tessellate the ellipsoid into a mesh and use shell mass properties of the mesh");
          },
          [](const Cylinder& s) {
            const double r = s.radius, h = s.length;
            return cylinder_wall(r, h) + disk(r, 0.5 * h) + disk(r, -0.5 * h);
          },
          [](const Capsule& s) {
            const Vec3 top(0, 0, 0.5 * s.length);
            return cylinder_wall(s.radius, s.length) +
                   hemisphere_shell(s.radius).transformed(Mat3::Identity(), top) +
                   hemisphere_shell(s.radius).transformed(flip_z(), -top);
          },
          [](const Cone& s) {
            // Lateral surface: area πrs (s the slant), centre of mass h/3 above the base; I_zz = m r²/2,
            // about the apex transverse m(r²/4 + h²/2), so about its centre m(r²/4 + h²/18).
            const double r = s.radius, h = s.height;
            const double A = pi * r * std::hypot(r, h);
            const double kx = 0.25 * r * r + h * h / 18.0;
            return unit_body(A, Vec3(kx, kx, 0.5 * r * r), Vec3(0, 0, h / 3.0)) + disk(r, 0.0);
          },
          [](const Torus& s) {
            // Area 4π²Rr; the area element ∝ (R + r cos θ): I_zz = m(R² + 3r²/2),
            // I_xx = m(R²/2 + 5r²/4).
            const double R = s.major_radius, r = s.minor_radius;
            const double kx = 0.5 * R * R + 1.25 * r * r;
            return unit_body(4.0 * pi * pi * R * r, Vec3(kx, kx, R * R + 1.5 * r * r));
          },
      },
      shape);
}

void require_positive(const Shape& shape, const char* what, double value) {
  if (!std::isfinite(value) || !(value > 0.0)) {
    throw InvalidArgument(
        fmt::format("{} {} is {} m: give a positive, finite length", shape_name(shape), what, value));
  }
}

}  // namespace

std::string shape_name(const Shape& shape) {
  static constexpr const char* names[] = {"box",     "sphere", "ellipsoid", "cylinder",
                                          "capsule", "cone",   "torus"};
  return names[shape.index()];
}

void validate_shape(const Shape& shape) {
  std::visit(Overloaded{
                 [&](const Box& s) {
                   require_positive(shape, "size x", s.size.x());
                   require_positive(shape, "size y", s.size.y());
                   require_positive(shape, "size z", s.size.z());
                 },
                 [&](const Sphere& s) { require_positive(shape, "radius", s.radius); },
                 [&](const Ellipsoid& s) {
                   require_positive(shape, "semi-axis a", s.semi_axes.x());
                   require_positive(shape, "semi-axis b", s.semi_axes.y());
                   require_positive(shape, "semi-axis c", s.semi_axes.z());
                 },
                 [&](const Cylinder& s) {
                   require_positive(shape, "radius", s.radius);
                   require_positive(shape, "length", s.length);
                 },
                 [&](const Capsule& s) {
                   require_positive(shape, "radius", s.radius);
                   require_positive(shape, "length", s.length);
                 },
                 [&](const Cone& s) {
                   require_positive(shape, "radius", s.radius);
                   require_positive(shape, "height", s.height);
                 },
                 [&](const Torus& s) {
                   require_positive(shape, "major radius", s.major_radius);
                   require_positive(shape, "minor radius", s.minor_radius);
                   if (s.minor_radius > s.major_radius) {
                     throw InvalidArgument(
                         fmt::format("torus minor radius {} m exceeds major radius {} m: the tube would "
                                     "overlap itself; give minor radius <= major radius",
                                     s.minor_radius, s.major_radius));
                   }
                 },
             },
             shape);
}

MassProperties solid_mass_properties(const Shape& shape, const MassSpec& spec) {
  validate_shape(shape);
  return spec.apply(solid_unit(shape));
}

double inradius(const Shape& shape) {
  validate_shape(shape);
  return std::visit(
      Overloaded{
          [](const Box& s) { return 0.5 * s.size.minCoeff(); },
          [](const Sphere& s) { return s.radius; },
          [](const Ellipsoid& s) { return s.semi_axes.minCoeff(); },
          [](const Cylinder& s) { return std::min(s.radius, 0.5 * s.length); },
          [](const Capsule& s) { return s.radius; },
          // The sphere inscribed in the cone touches its base and its side: the inradius of the
          // triangle through its axis, r·h / (r + √(r² + h²)) (area over half the perimeter).
          [](const Cone& s) { return s.radius * s.height / (s.radius + std::hypot(s.radius, s.height)); },
          [](const Torus& s) { return s.minor_radius; },
      },
      shape);
}

MassProperties shell_mass_properties(const Shape& shape, double thickness, const MassSpec& spec) {
  validate_shape(shape);
  if (!std::isfinite(thickness) || !(thickness > 0.0)) {
    throw InvalidArgument(
        fmt::format("shell thickness {} m is invalid: give a positive wall thickness", thickness));
  }
  // A wall thicker than this has no inside left: a 5 m wall on a 1 m sphere is not a shell.
  if (const double r = inradius(shape); thickness > r) {
    throw InvalidArgument(fmt::format(
        "shell thickness {} m does not fit inside the {}: its walls can be at most {} m thick (the radius "
        "of the largest sphere inside it); for a thick-walled body subtract an inner solid as a hole",
        thickness, shape_name(shape), r));
  }
  MassProperties unit = shell_unit(shape);
  unit.volume = unit.mass * thickness;  // thin-wall limit: material volume = area · t
  return spec.apply(unit, thickness);
}

double surface_area(const Shape& shape) {
  validate_shape(shape);
  if (const auto* e = std::get_if<Ellipsoid>(&shape)) {
    // Legendre's formula (a ≥ b ≥ c): S = 2πc² + 2πab/sin φ · (E(φ,k) sin²φ + F(φ,k) cos²φ),
    // cos φ = c/a, k² = a²(b² − c²) / (b²(a² − c²)).
    Vec3 s = e->semi_axes;
    std::sort(s.data(), s.data() + 3, std::greater<>());
    const double a = s(0), b = s(1), c = s(2);
    if (a == c) return 4.0 * pi * a * a;
    const double phi = std::acos(c / a);
    const double k = std::sqrt(a * a * (b * b - c * c) / (b * b * (a * a - c * c)));
    const double sp = std::sin(phi), cp = std::cos(phi);
    return 2.0 * pi * c * c +
           2.0 * pi * a * b / sp *
               (boost::math::ellint_2(k, phi) * sp * sp + boost::math::ellint_1(k, phi) * cp * cp);
  }
  return shell_unit(shape).mass;  // unit surface density: mass = area
}

}  // namespace tumble
