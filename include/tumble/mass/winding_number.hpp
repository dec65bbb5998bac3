#pragma once
// Whether a point is inside a closed surface: its generalised winding number, the solid angle the
// surface subtends at the point over 4π. Robust on any closed, consistently oriented mesh (no ray to
// graze an edge): 1 inside an outward-facing surface, 0 outside, −1 inside an inward-facing one.
#include "tumble/mass/triangle_mesh.hpp"

namespace tumble {

/// The solid angle (sr, signed by the winding) that the triangle a, b, c subtends at the origin, by Van
/// Oosterom and Strackee's tan(Ω/2) = a·(b × c) / (|a||b||c| + (a·b)|c| + (a·c)|b| + (b·c)|a|).
double triangle_solid_angle(const Vec3& a, const Vec3& b, const Vec3& c);

/// The winding number of `mesh` about p (p not on it): Σ solid angles / 4π.
double winding_number(const TriangleMesh& mesh, const Vec3& p);

}  // namespace tumble
