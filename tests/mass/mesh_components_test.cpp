// The closed surfaces of a solid mesh bound its material once: a cavity (an inward surface inside an
// outward one) is subtracted, a part inside a cavity added back, and two nested outward surfaces (the
// material counted twice) or a lone inward one are refused with the surfaces named.
#include <gtest/gtest.h>

#include "mesh_support.hpp"
#include "tumble/mass/mesh_mass.hpp"
#include "tumble/mass/shapes.hpp"
#include "tumble/mass/tessellate.hpp"

namespace tumble {
namespace {

/// The cube [−a/2, a/2]³ centred at c, outward (or inward).
TriangleMesh cube(double a, const Vec3& c = Vec3::Zero(), bool inward = false) {
  const TriangleMesh m = test::mapped(tessellate(Box{Vec3(a, a, a)}, 4), Mat3::Identity(), c);
  return inward ? test::flipped(m) : m;
}

/// The surfaces of several meshes as one mesh.
TriangleMesh merged(std::initializer_list<TriangleMesh> parts) {
  TriangleMesh out;
  for (const TriangleMesh& p : parts) {
    const auto base = static_cast<std::uint32_t>(out.vertices.size());
    out.vertices.insert(out.vertices.end(), p.vertices.begin(), p.vertices.end());
    for (auto f : p.triangles) out.triangles.push_back({f[0] + base, f[1] + base, f[2] + base});
  }
  return out;
}

double volume_of(const TriangleMesh& m) { return solid_unit_properties(m, "m.obj").properties.volume; }

std::string refusal(const TriangleMesh& m) {
  try {
    (void)solid_unit_properties(m, "m.obj");
  } catch (const MeshError& e) {
    return e.what();
  }
  return "accepted";
}

TEST(MeshSurfaces, ACavityIsSubtractedAndAPartInsideItAddedBack) {
  // Volumes of cubes are exact in binary: 8, 1, 1/8 (rounding of the signed tetrahedra: a few ε).
  EXPECT_NEAR(volume_of(merged({cube(2), cube(1, Vec3::Zero(), true)})), 7.0, 1e-14);
  EXPECT_NEAR(volume_of(merged({cube(2), cube(1, Vec3::Zero(), true), cube(0.5)})), 7.125, 1e-14);
  // Two separate solids, and the whole mesh inside out (integrated flipped, with a warning).
  EXPECT_NEAR(volume_of(merged({cube(1), cube(1, Vec3(3, 0, 0))})), 2.0, 1e-14);
  EXPECT_NEAR(volume_of(test::flipped(merged({cube(2), cube(1, Vec3::Zero(), true)}))), 7.0, 1e-14);
}

TEST(MeshSurfaces, NestedOutwardSurfacesOrALoneInwardOneAreRefused) {
  // A box is tessellated as 12 triangles whatever the segments: the second surface starts at 12.
  EXPECT_EQ(refusal(merged({cube(2), cube(1)})),
            "m.obj: the closed surface of triangle 12 (12 triangles) lies inside the closed surface of "
            "triangle 0 (12 triangles), and both face outward: the material between them would be counted "
            "twice; if the inner surface bounds a cavity, reverse its triangles (its normals must point "
            "into the cavity); if it is a part of its own, give it as another part or body");
  // Listed inner first, and off-centre: the same.
  EXPECT_NE(refusal(merged({cube(0.5, Vec3(0.3, 0.2, 0.1)), cube(2)}))
                .find("the closed surface of triangle 0 "
                      "(12 triangles) lies inside the "
                      "closed surface of triangle 12"),
            std::string::npos);
  EXPECT_EQ(refusal(merged({cube(1), cube(0.5, Vec3(3, 0, 0), true)})),
            "m.obj: the closed surface of triangle 12 (12 triangles) faces inward (a cavity's surface) but "
            "lies in no material: it would subtract a volume that is not there; reverse its triangles if "
            "it is a solid of its own");
}

}  // namespace
}  // namespace tumble
