#pragma once
// How much mass a shape carries: a density or a total mass.
#include <string>

#include "tumble/mass/mass_properties.hpp"

namespace tumble {

/// Either a uniform density ρ (kg/m³) or a total mass m (kg). Geometry is integrated once with unit
/// density and scaled: mass and inertia are proportional to ρ, the centre of mass does not depend on it.
class MassSpec {
 public:
  static MassSpec density(double rho);  ///< kg/m³; throws InvalidArgument unless finite and > 0
  static MassSpec mass(double m);       ///< kg; throws InvalidArgument unless finite and > 0

  bool is_density() const { return kind_ == Kind::density; }
  double value() const { return value_; }

  /// Scale `unit` — the properties of the region with unit density per `measure` (volume for solids,
  /// area for shells) — to this density or mass. `mass_per_measure_unit` multiplies the density: the
  /// wall thickness t for a thin shell (surface density ρ·t), 1 for a solid. `unit.volume` is kept.
  MassProperties apply(const MassProperties& unit, double mass_per_measure_unit = 1.0) const;

 private:
  enum class Kind { density, mass };
  MassSpec(Kind kind, double value) : kind_(kind), value_(value) {}
  Kind kind_;
  double value_;
};

}  // namespace tumble
