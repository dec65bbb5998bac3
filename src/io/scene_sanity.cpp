#include "scene_sanity.hpp"

#include <fmt/format.h>

#include <cmath>
#include <numbers>

namespace tumble::scene {

std::optional<std::string> implausible_density(double rho) {
  // Solids and liquids lie between ~10 kg/m³ (the lightest foams; air is 1.2) and 22 590 (osmium, the
  // densest element). Below, the usual slip is g/cm³ typed as kg/m³ (aluminium's 2.7 for 2700). Exactly
  // 1 is the unit density, given on purpose so that the mass is the volume (tumble inertia's default).
  if (rho < 10.0 && rho != 1.0) {
    return fmt::format(
        "density {:g} kg/m^3 is lighter than any solid (air is 1.2 kg/m^3): if it is in g/cm^3, write "
        "density = {:g} (kg/m^3)",
        rho, rho * 1000.0);
  }
  if (rho > 25000.0) {
    return fmt::format(
        "density {:g} kg/m^3 is above every element's (osmium: 22 590 kg/m^3): if it is in g/m^3 or "
        "another unit, give it in kg/m^3",
        rho);
  }
  return std::nullopt;
}

std::optional<std::string> implausible_mesh_size(double diagonal) {
  // A part drawn in millimetres and read as metres is 1000 times too large, 10⁹ times too heavy, and
  // its inertia 10¹⁵ times too large. Spacecraft, buildings and ships are larger than 20 m, so this is
  // a warning that an explicit scale (1.0 included) silences.
  if (diagonal <= 20.0) return std::nullopt;
  return fmt::format(
      "the mesh is {:.4g} m across as its coordinates are read (metres): if its file is in millimetres, "
      "add scale = 0.001 (inches: 0.0254); if it really is that large, say scale = 1.0",
      diagonal);
}

std::optional<std::string> angles_in_degrees(std::string_view key, const Eigen::VectorXd& angles) {
  // Angles are radians; one beyond a full turn is almost always a number of degrees.
  for (Eigen::Index i = 0; i < angles.size(); ++i) {
    if (std::abs(angles(i)) > 2.0 * std::numbers::pi) {
      std::string radians;
      for (Eigen::Index k = 0; k < angles.size(); ++k)
        radians += fmt::format("{}{:.6g}", k > 0 ? ", " : "", angles(k) * std::numbers::pi / 180.0);
      const std::string which = angles.size() > 1 ? fmt::format("{}[{}]", key, i) : std::string(key);
      return fmt::format(
          "{} = {:g} rad is more than a full turn: angles are in radians; if these are degrees, write "
          "{} = {}{}{}",
          which, angles(i), key, angles.size() > 1 ? "[" : "", radians, angles.size() > 1 ? "]" : "");
    }
  }
  return std::nullopt;
}

std::optional<std::string> quaternion_order(std::string_view key, const Eigen::Vector4d& wxyz) {
  // [0, 0, 0, 1] is a half-turn about z in tumble's (w, x, y, z), but the identity in the
  // (x, y, z, w) order of Eigen's storage, ROS and Unity: a w of exactly 0 with the last entry set is
  // the sign of that mix-up far more often than of a half-turn.
  if (wxyz(0) != 0.0 || wxyz(3) == 0.0) return std::nullopt;
  return fmt::format(
      "{} = [{:g}, {:g}, {:g}, {:g}] is read as [w, x, y, z] (w first): a half-turn about an axis. If it "
      "was written [x, y, z, w], reorder it to [{:g}, {:g}, {:g}, {:g}]",
      key, wxyz(0), wxyz(1), wxyz(2), wxyz(3), wxyz(3), wxyz(0), wxyz(1), wxyz(2));
}

}  // namespace tumble::scene
