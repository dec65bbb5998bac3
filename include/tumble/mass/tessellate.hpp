#pragma once
// Triangle meshes of the primitive shapes, for tests, benchmarks and examples.
#include "tumble/mass/shapes.hpp"
#include "tumble/mass/triangle_mesh.hpp"

namespace tumble {

/// A closed, manifold, consistently outward-oriented (counter-clockwise seen from outside) mesh of the
/// shape's surface, in the shape's own placement (shapes.hpp: centred at the origin, axis along z; the
/// cone's base at z = 0). Every vertex lies on the exact surface, so the mesh bounds an inscribed
/// polyhedron whose mass properties converge to the closed forms like 1/segments².
///
/// `segments` (≥ 3) is the number of divisions of every full circle: around the z axis, and around
/// the tube of a torus. Meridians get segments/2 divisions from pole to pole (segments/4 for each
/// hemisphere of a capsule, at least one). Flat faces and the straight sides of cylinders and cones
/// are exact with one band; the box is exact with 12 triangles whatever `segments` is.
/// Throws InvalidArgument for an invalid shape (validate_shape) or segments < 3.
TriangleMesh tessellate(const Shape& shape, int segments);

}  // namespace tumble
