#pragma once
// An indexed triangle mesh: the boundary of a solid, or a thin-walled surface.
#include <array>
#include <cstdint>
#include <vector>

#include "tumble/math/types.hpp"

namespace tumble {

struct TriangleMesh {
  std::vector<Vec3> vertices;                           ///< positions (m), in the body reference frame
  std::vector<std::array<std::uint32_t, 3>> triangles;  ///< vertex indices, counter-clockwise seen
                                                        ///< from outside (outward normals)
};

}  // namespace tumble
