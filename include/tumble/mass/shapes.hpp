#pragma once
// Primitive shapes with closed-form mass properties.
//
// Each shape sits in its own reference frame: centred at the origin, with its symmetry axis along z
// (the cone is the exception: base centre at the origin, apex at +z, so its centre of mass is h/4 above
// the base). Move a shape elsewhere with MassProperties::transformed().
#include <string>
#include <variant>

#include "tumble/mass/mass_spec.hpp"

namespace tumble {

struct Box {
  Vec3 size;  ///< full edge lengths along x, y, z (m)
};
struct Sphere {
  double radius;
};
struct Ellipsoid {
  Vec3 semi_axes;  ///< a, b, c along x, y, z (m)
};
struct Cylinder {
  double radius;
  double length;  ///< along z (m)
};
struct Capsule {
  double radius;
  double length;  ///< of the cylindrical part, along z; the hemispheres add 2·radius (m)
};
struct Cone {
  double radius;  ///< of the base (m)
  double height;  ///< base at z = 0, apex at z = height (m)
};
struct Torus {
  double major_radius;  ///< R: from the z axis to the centre of the tube (m)
  double minor_radius;  ///< r: radius of the tube, r < R (m)
};

using Shape = std::variant<Box, Sphere, Ellipsoid, Cylinder, Capsule, Cone, Torus>;

/// The shape's name as used on the command line and in scene files ("box", "sphere", ...).
std::string shape_name(const Shape& shape);

/// Throws InvalidArgument unless every dimension is finite and positive (and r < R for a torus).
void validate_shape(const Shape& shape);

/// Solid of uniform density (or given total mass): exact closed form.
MassProperties solid_mass_properties(const Shape& shape, const MassSpec& spec);

/// Closed thin shell: the surface carries mass with surface density ρ·t (ρ = spec density, t =
/// `thickness`), or the given total mass spread uniformly over the area. Exact in the thin-wall limit
/// t → 0 (for thick walls, subtract an inner solid from an outer one). Every shape but the ellipsoid,
/// whose surface integrals are elliptic, has a closed form; the ellipsoid throws InvalidArgument
/// (use a tessellated mesh with shell mass properties instead). `volume` is area·t.
/// Throws InvalidArgument when the thickness is not positive or exceeds inradius(shape).
MassProperties shell_mass_properties(const Shape& shape, double thickness, const MassSpec& spec);

/// The radius of the largest sphere inside the shape (m): the thickest wall a shell of it can have.
double inradius(const Shape& shape);

/// Surface area of the shape (m²).
double surface_area(const Shape& shape);

}  // namespace tumble
