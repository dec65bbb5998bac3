#pragma once
// The integration kernels behind integrate_solid_mesh and the thin-shell path (internal).
#include "tumble/mass/mass_properties.hpp"
#include "tumble/mass/triangle_mesh.hpp"

namespace tumble::detail {

/// ∫1, ∫r and ∫r rᵀ over a region, r = x − ref, about a reference point near the mesh.
struct RegionMoments {
  Vec3 ref = Vec3::Zero();
  double measure = 0.0;        ///< volume (signed, for solids) or area
  Vec3 first = Vec3::Zero();   ///< ∫ r
  Mat3 second = Mat3::Zero();  ///< C_ref = ∫ r rᵀ
};

/// Centre of the axis-aligned bounding box of the vertices (the origin of an empty mesh).
Vec3 bounding_box_centre(const TriangleMesh& mesh);

/// Signed-tetrahedron integrals of the solid bounded by a closed mesh (negative if inside-out).
/// Throws MeshError if a triangle refers to a vertex that does not exist.
RegionMoments solid_moments(const TriangleMesh& mesh);

/// Surface integrals over the triangles (unit surface density).
RegionMoments surface_moments(const TriangleMesh& mesh);

/// Mass properties of unit density from moments: m = measure, c = ref + ∫r / m and
/// I = tr(C) I₃ − C − m((d·d)I₃ − ddᵀ), d = c − ref (parallel-axis shift from ref to c).
MassProperties unit_properties(const RegionMoments& moments);

}  // namespace tumble::detail
