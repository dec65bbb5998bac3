#pragma once
// Welding: one vertex per position.
#include "tumble/mass/triangle_mesh.hpp"

namespace tumble {

/// The same mesh with vertices at bit-identical positions merged into one (+0 and −0 count as equal,
/// nothing else is rounded: welding is exact and never closes a real gap). Triangles are renumbered;
/// the vertices keep the order in which they first occur; unreferenced vertices are kept.
TriangleMesh weld_identical_vertices(const TriangleMesh& mesh);

}  // namespace tumble
