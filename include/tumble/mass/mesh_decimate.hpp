#pragma once
// Smaller meshes for pictures: a mesh of a million triangles is right for mass properties but too much
// to draw in a report. Vertex clustering (Rossignac & Borrel 1993): the vertices in each cell of a grid
// over the bounding box merge into their mean, and triangles whose corners fall into fewer than three
// cells vanish. Not for mass properties: the result need not be closed or manifold.
#include <cstddef>

#include "tumble/mass/triangle_mesh.hpp"

namespace tumble {

/// Segments per full circle when a primitive is tessellated for display.
inline constexpr int kDisplaySegments = 32;
/// The most triangles a body's display mesh keeps.
inline constexpr std::size_t kDisplayTriangles = 20000;

/// `mesh` itself if it has at most `max_triangles`; otherwise clustered on the finest grid (halving
/// 1024 cells per axis) that leaves at most that many.
TriangleMesh decimate(const TriangleMesh& mesh, std::size_t max_triangles);

/// The box whose principal moments are those of a body of mass m and principal moments Λ (edges
/// aᵢ² = 6(Λⱼ + Λₖ − Λᵢ)/m along the principal axes, centred at the origin): how a body known only by
/// its mass properties is drawn.
TriangleMesh inertia_box(double m, const Vec3& Lambda);
/// That box's edges (a flat body's zero edge drawn 1e-3 of the longest: thin, not invisible).
Vec3 inertia_box_edges(double m, const Vec3& Lambda);

}  // namespace tumble
