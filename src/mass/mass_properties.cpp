#include "tumble/mass/mass_properties.hpp"

#include <cmath>
#include <fmt/format.h>

#include "tumble/error.hpp"

namespace tumble {

Mat3 parallel_axis_term(double m, const Vec3& b) {
  return m * (b.squaredNorm() * Mat3::Identity() - b * b.transpose());
}

MassProperties MassProperties::from_inertia(double mass, const Vec3& center_of_mass, const Mat3& inertia,
                                            double volume) {
  return MassProperties{mass, center_of_mass, inertia, volume};
}

MassProperties MassProperties::from_inertia_about(double mass, const Vec3& center_of_mass,
                                                  const Mat3& inertia_about_point, const Vec3& point,
                                                  double volume) {
  return MassProperties{mass, center_of_mass,
                        inertia_about_point - parallel_axis_term(mass, point - center_of_mass), volume};
}

Mat3 MassProperties::inertia_about(const Vec3& point) const {
  return inertia + parallel_axis_term(mass, point - center_of_mass);
}

MassProperties MassProperties::expressed_in(const Mat3& R) const {
  // ^qI = Rᵀ ^sI R (tutorial, "Inertia Tensor Under Rotation").
  return MassProperties{mass, R.transpose() * center_of_mass, R.transpose() * inertia * R, volume};
}

MassProperties MassProperties::transformed(const Mat3& R, const Vec3& t) const {
  return MassProperties{mass, R * center_of_mass + t, R * inertia * R.transpose(), volume};
}

namespace {
Vec3 unit_axis(const Vec3& axis) {
  const double n = axis.norm();
  if (!(n > 0.0) || !std::isfinite(n)) {
    throw InvalidArgument(
        fmt::format("axis direction ({}, {}, {}) has no direction: give a non-zero, finite vector", axis.x(),
                    axis.y(), axis.z()));
  }
  return axis / n;
}
}  // namespace

double MassProperties::moment_about_axis(const Vec3& axis, const Vec3& point) const {
  // I_l = l̂ᵀ I l̂ (tutorial, "Moment of Inertia") for the parallel axis through c, plus m d², d the
  // distance between the two parallel axes.
  const Vec3 l = unit_axis(axis);
  return l.dot(inertia * l) + mass * (point - center_of_mass).cross(l).squaredNorm();
}

double MassProperties::radius_of_gyration(const Vec3& axis, const Vec3& point) const {
  if (!(mass > 0.0)) {
    throw InvalidArgument(fmt::format("radius of gyration needs a positive mass, got {}", mass));
  }
  return std::sqrt(moment_about_axis(axis, point) / mass);
}

void MassProperties::validate(const ValidityOptions& options, const std::string& what) const {
  validated_principal_axes(options, what);
}

PrincipalAxes MassProperties::validated_principal_axes(const ValidityOptions& options,
                                                       const std::string& what) const {
  auto fail = [&](const std::string& message) {
    throw InvalidMassProperties(what.empty() ? message : what + ": " + message);
  };

  if (!std::isfinite(mass) || !center_of_mass.allFinite() || !inertia.allFinite()) {
    fail("mass properties contain a non-finite number (NaN or infinity); check the input data");
  }
  if (!(mass > 0.0)) {
    fail(fmt::format("mass is {} kg but must be positive", mass));
  }
  const double scale = inertia.cwiseAbs().maxCoeff();
  if (!(scale > 0.0)) {
    fail("inertia tensor is zero; a body of positive mass has positive moments");
  }
  const double tol = options.tolerance * scale;
  const double asymmetry = (inertia - inertia.transpose()).cwiseAbs().maxCoeff();
  if (asymmetry > tol) {
    fail(fmt::format(
        "inertia tensor is not symmetric: |I - I^T| reaches {:.6g} (I_xy={:.10g} vs I_yx={:.10g}, "
        "I_xz={:.10g} vs I_zx={:.10g}, I_yz={:.10g} vs I_zy={:.10g}); products of inertia must "
        "appear twice with the same value",
        asymmetry, inertia(0, 1), inertia(1, 0), inertia(0, 2), inertia(2, 0), inertia(1, 2), inertia(2, 1)));
  }
  // principal_axes() symmetrises I itself, so these are the axes of the symmetric part.
  const PrincipalAxes axes = tumble::principal_axes(inertia);
  const Vec3& L = axes.Lambda;
  if (!(L(0) > tol)) {
    fail(fmt::format(
        "inertia tensor is not positive definite: principal moments are {:.10g}, {:.10g}, {:.10g} "
        "kg*m^2; every principal moment of a body must be positive",
        L(0), L(1), L(2)));
  }
  if (L(2) > L(0) + L(1) + tol) {
    fail(fmt::format(
        "inertia tensor violates the triangle inequality: the largest principal moment {:.10g} "
        "exceeds the sum of the other two {:.10g} + {:.10g} = {:.10g} kg*m^2 (by {:.3g}); no mass "
        "distribution has such moments — check signs of products of inertia and units",
        L(2), L(0), L(1), L(0) + L(1), L(2) - L(0) - L(1)));
  }
  return axes;
}

MassProperties& MassProperties::operator+=(const MassProperties& part) {
  const double m = mass + part.mass;
  if (m == 0.0) {
    throw InvalidArgument("combined mass is zero: the parts cancel out and leave no body");
  }
  const Vec3 c = (mass * center_of_mass + part.mass * part.center_of_mass) / m;
  inertia = inertia + parallel_axis_term(mass, center_of_mass - c) + part.inertia +
            parallel_axis_term(part.mass, part.center_of_mass - c);
  center_of_mass = c;
  mass = m;
  volume += part.volume;
  return *this;
}

MassProperties& MassProperties::operator-=(const MassProperties& part) {
  if (!(part.mass < mass)) {
    throw InvalidArgument(
        fmt::format("cannot remove a part of mass {} kg from a body of mass {} kg: a hole must be lighter "
                    "than the body it is cut from",
                    part.mass, mass));
  }
  MassProperties negative = part;
  negative.mass = -part.mass;
  negative.inertia = -part.inertia;
  negative.volume = -part.volume;
  return *this += negative;
}

MassProperties operator+(MassProperties a, const MassProperties& b) { return a += b; }
MassProperties operator-(MassProperties a, const MassProperties& b) { return a -= b; }

}  // namespace tumble
