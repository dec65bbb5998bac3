#pragma once
// Numbers in a scene that are valid but probably not what was meant: a density in g/cm³, a mesh in
// millimetres read as metres, Euler angles in degrees, a quaternion written (x, y, z, w). Each check
// returns the warning's text (what was found, the unit probably meant, how to say so), or nothing.
// Private to tumble_io; the scene reader adds the location and collects them in Scene::warnings.
#include <optional>
#include <string>
#include <string_view>

#include "tumble/math/types.hpp"

namespace tumble::scene {

/// A uniform density ρ (kg/m³) outside what solids have.
std::optional<std::string> implausible_density(double rho);

/// A mesh read without `scale` whose bounding box has this diagonal (m).
std::optional<std::string> implausible_mesh_size(double diagonal);

/// Angles (rad) of `key` (euler_zyx, euler_zxz, angle) that look like degrees.
std::optional<std::string> angles_in_degrees(std::string_view key, const Eigen::VectorXd& angles);

/// A quaternion as written [w, x, y, z] that looks like one written (x, y, z, w).
std::optional<std::string> quaternion_order(std::string_view key, const Eigen::Vector4d& wxyz);

}  // namespace tumble::scene
