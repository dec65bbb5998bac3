#include "tumble/mass/mass_spec.hpp"

#include <cmath>
#include <fmt/format.h>
#include <limits>

#include "tumble/error.hpp"

namespace tumble {

MassSpec MassSpec::density(double rho) {
  if (!std::isfinite(rho) || !(rho > 0.0)) {
    throw InvalidArgument(fmt::format("density {} kg/m^3 is invalid: give a positive number", rho));
  }
  return MassSpec(Kind::density, rho);
}

MassSpec MassSpec::mass(double m) {
  if (!std::isfinite(m) || !(m > 0.0)) {
    throw InvalidArgument(fmt::format("mass {} kg is invalid: give a positive number", m));
  }
  return MassSpec(Kind::mass, m);
}

MassProperties MassSpec::apply(const MassProperties& unit, double mass_per_measure_unit) const {
  if (!(unit.mass > 0.0)) {
    throw InvalidArgument(
        fmt::format("the shape has no extent (measure {}), so it cannot carry mass", unit.mass));
  }
  const double factor = kind_ == Kind::density ? value_ * mass_per_measure_unit : value_ / unit.mass;
  MassProperties out{unit.mass * factor, unit.center_of_mass, unit.inertia * factor, unit.volume};
  // Found by fuzzing (fuzz/fuzz_mass.cpp): extreme densities, masses, thicknesses or sizes overflowed
  // to inf, or underflowed to 0 or to subnormal numbers that keep no digits (then even the principal
  // moments came out unordered), and were returned as if they were numbers. A real body's inertia has a
  // positive trace (2∫r² dm); it must keep double's full precision: at least DBL_MIN / ε.
  constexpr double kMinTrace = std::numeric_limits<double>::min() / std::numeric_limits<double>::epsilon();
  if (!std::isfinite(out.mass) || !(out.mass >= std::numeric_limits<double>::min()) ||
      !out.center_of_mass.allFinite() || !out.inertia.allFinite() || !(out.inertia.trace() >= kMinTrace)) {
    throw InvalidArgument(fmt::format(
        "mass properties out of the range of double: {} {} on a {} of {:.6g} gives a mass of {:.6g} kg and "
        "an inertia of trace {:.6g} kg m^2; give values in SI units (kg, m) of a realistic size",
        kind_ == Kind::density ? "density" : "mass", value_,
        mass_per_measure_unit == 1.0 ? "measure" : "shell measure", unit.mass, out.mass,
        out.inertia.trace()));
  }
  return out;
}

}  // namespace tumble
