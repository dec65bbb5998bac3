// Moments of ρ summed over quadrature points, and the error estimate of integrate_density().
#include "density_moments.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>

#include "tumble/error.hpp"

namespace tumble::detail {

MomentAccumulator::MomentAccumulator(const DensityField& rho, const Vec3& origin, std::string where)
    : rho_(rho), origin_(origin), where_(std::move(where)) {}

void MomentAccumulator::bad_density(const Vec3& x, double rho) const {
  const std::string element = element_kind_ == nullptr ? std::string()
                                                       : fmt::format(", in {} {}", element_kind_, element_);
  throw InvalidArgument(fmt::format(
      "{}: the density function returned {} kg/m^3 at the quadrature point x = ({:.17g}, {:.17g}, "
      "{:.17g}) m{}; it must return a finite number at every point of the body (for a non-convex "
      "mesh, everywhere in its convex hull) — fix the density function there",
      where_, rho, x.x(), x.y(), x.z(), element));
}

MassProperties MomentAccumulator::finish() {
  end_block();
  const Terms t = sum_.total();
  const double volume = t[0], m0 = t[1];
  if (!(m0 > 0.0)) {
    throw InvalidArgument(
        fmt::format("{}: the density integrates to a total mass of {} kg, which is not positive; the density "
                    "must be non-negative and positive somewhere in the body",
                    where_, m0));
  }
  const Vec3 m1(t[2], t[3], t[4]);
  Mat3 m2;
  m2 << t[5], t[8], t[9],  //
      t[8], t[6], t[10],   //
      t[9], t[10], t[7];
  // S = ∫ρ (x − c)(x − c)ᵀ = M₂ − M₁M₁ᵀ/M₀ (the parallel-axis shift of the second moment), then
  // I = ∫ρ((r·r)I₃ − r rᵀ) = tr(S) I₃ − S.
  const Vec3 shift = m1 / m0;
  const Mat3 S = m2 - m0 * shift * shift.transpose();
  const Mat3 I = S.trace() * Mat3::Identity() - S;
  return MassProperties{m0, origin_ + shift, 0.5 * (I + I.transpose()), volume};
}

int density_rule_degree(int degree, const DensityField& rho, const std::string& where) {
  if (degree < kMinDensityDegree || degree > kMaxDensityDegree) {
    throw InvalidArgument(
        fmt::format("{}: quadrature degree {} is out of the supported range [{}, {}]; degree d integrates "
                    "densities that are polynomials of degree d - 2 exactly (d = 2 for uniform density) — "
                    "choose a degree in that range",
                    where, degree, kMinDensityDegree, kMaxDensityDegree));
  }
  if (!rho) {
    throw InvalidArgument(
        fmt::format("{}: the density function is empty; pass a callable returning kg/m^3 at a point", where));
  }
  return degree % 2 == 0 ? degree + 1 : degree;  // rules come in odd degrees
}

double relative_difference(const MassProperties& other, const MassProperties& reference) {
  const double m = reference.mass;
  const double dm = std::abs(other.mass - m) / m;
  const double dI = (other.inertia - reference.inertia).cwiseAbs().maxCoeff() /
                    reference.inertia.cwiseAbs().maxCoeff();
  // Radius of gyration about the centre: tr I = 2∫ρ|r|² dV, so k² = tr I / 2m is the mean |r|².
  const double k = std::sqrt(reference.inertia.trace() / (2.0 * m));
  const double dc = (other.center_of_mass - reference.center_of_mass).norm() / k;
  return std::max({dm, dI, dc});
}

DensityResult integrate_with_estimate(int d, const std::function<MassProperties(int)>& integrate) {
  const MassProperties low = integrate(d);
  const MassProperties high = integrate(d + 2);
  return DensityResult{high, relative_difference(low, high), d + 2, {}};
}

}  // namespace tumble::detail
