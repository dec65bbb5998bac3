// Every mesh defect that keeps a mesh from bounding a solid gives a MeshError that names it, counts
// it, lists the first indices and says how to fix it.
#include <gtest/gtest.h>

#include <cmath>

#include "mesh_support.hpp"
#include "tumble/error.hpp"
#include "tumble/mass/mesh_check.hpp"
#include "tumble/mass/mesh_mass.hpp"
#include "tumble/mass/tessellate.hpp"

namespace tumble {
namespace {

/// The corner tetrahedron 0 = origin, 1 = x̂, 2 = ŷ, 3 = ẑ with outward faces:
/// 0: (0,2,1) z = 0,  1: (0,1,3) y = 0,  2: (1,2,3) slanted,  3: (0,3,2) x = 0.
TriangleMesh tetrahedron() {
  return TriangleMesh{{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)},
                      {{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {0, 3, 2}}};
}

/// The message of the MeshError that solid_mass_properties throws (fails the test if none).
std::string solid_error(const TriangleMesh& mesh, const std::string& name = "part.stl") {
  try {
    (void)solid_mass_properties(mesh, MassSpec::density(1000.0), name);
  } catch (const MeshError& e) {
    return e.what();
  }
  ADD_FAILURE() << "no MeshError";
  return "";
}

#define EXPECT_CONTAINS(text, part) \
  EXPECT_NE(std::string(text).find(part), std::string::npos) << "message: " << (text)

TEST(MeshCheck, TetrahedronIsASolidAndMatchesItsClosedForm) {
  const MeshReport r = check_mesh(tetrahedron());
  EXPECT_TRUE(r.solid());
  EXPECT_EQ(describe_solid_defects(r), "");
  // Corner tetrahedron: V = 1/6, c = (1/4, 1/4, 1/4), ∫x² dV = 1/60, ∫xy dV = 1/120 about the origin.
  const MeshMassResult m = solid_mass_properties(tetrahedron(), MassSpec::density(1.0));
  const double V = 1.0 / 6.0;
  Mat3 C_origin;
  C_origin << 2, 1, 1, 1, 2, 1, 1, 1, 2;
  C_origin /= 120.0;
  const Vec3 c = Vec3::Constant(0.25);
  const Mat3 I = test::inertia_from_second_moment(C_origin) - parallel_axis_term(V, c);
  // Four triangles, a few operations each: 1e-14 is a margin of ~50 over double rounding.
  test::expect_close(m.properties, MassProperties{V, c, I, V}, 1e-14, 1.0);
  EXPECT_NEAR(m.surface_area, 1.5 + std::sqrt(3.0) / 2, 1e-15);
}

TEST(MeshCheck, OpenMeshNamesItsBoundaryEdgesAndTheirTriangles) {
  TriangleMesh open = tetrahedron();
  open.triangles.pop_back();  // remove the x = 0 face (0,3,2)
  const std::string msg = solid_error(open);
  EXPECT_CONTAINS(msg, "part.stl: cannot compute solid mass properties");
  EXPECT_CONTAINS(msg,
                  "the mesh has 3 boundary edges (an open surface), first: edge (0,2) of "
                  "triangle 0, edge (3,0) of triangle 1, edge (2,3) of triangle 2; close the holes");
  EXPECT_CONTAINS(msg, "thin-walled part (shell mass properties)");
  EXPECT_THROW((void)solid_mass_properties(open, MassSpec::density(1.0), "part.stl"), NotASolidError);
}

TEST(MeshCheck, ManyBoundaryEdgesAreCountedAndTheFirstFiveListed) {
  // A cylinder without its top cap: the rim has `segments` boundary edges.
  TriangleMesh mesh = tessellate(Cylinder{0.5, 1.0}, 12);
  const std::size_t top = mesh.triangles.size() - 12;  // the last band is the top fan
  mesh.triangles.resize(top);
  const MeshReport r = check_mesh(mesh);
  EXPECT_EQ(r.boundary_edge_count, 12U);
  ASSERT_EQ(r.boundary_edges.size(), MeshReport::listed);
  for (std::size_t i = 0; i < r.boundary_edges.size(); ++i) {
    // The wall's upper triangles (a, c, d) are the odd ones of the band: 24 + 2i + 1... of the band
    // that starts after the bottom fan (12 triangles).
    EXPECT_EQ(r.boundary_edges[i].triangle, 12 + 2 * i + 1);
  }
  const std::string msg = solid_error(mesh);
  EXPECT_CONTAINS(msg, "12 boundary edges");
  EXPECT_CONTAINS(msg, "of triangle 21, ...; close the holes");
}

TEST(MeshCheck, FlippedTriangleNamesTheTrianglePairs) {
  TriangleMesh mesh = tetrahedron();
  std::swap(mesh.triangles[2][1], mesh.triangles[2][2]);  // (1,3,2)
  const std::string msg = solid_error(mesh);
  EXPECT_CONTAINS(msg,
                  "the mesh is inconsistently oriented: 3 edges are traversed in the same "
                  "direction by both of their triangles, first: edge (2,1) in triangles 0 and 2, "
                  "edge (1,3) in triangles 1 and 2, edge (3,2) in triangles 2 and 3; flip one");
}

TEST(MeshCheck, NonManifoldEdgeListsAllItsTriangles) {
  TriangleMesh mesh = tetrahedron();
  mesh.vertices.emplace_back(0.5, -1.0, 0.0);
  mesh.triangles.push_back({0, 1, 4});  // a fin on edge (0,1)
  const MeshReport r = check_mesh(mesh);
  EXPECT_EQ(r.non_manifold_edge_count, 1U);
  const std::string msg = solid_error(mesh);
  EXPECT_CONTAINS(msg,
                  "the mesh has 1 non-manifold edge (shared by more than two triangles), "
                  "first: edge (0,1) of triangles {0, 1, 4}; separate the bodies");
  EXPECT_CONTAINS(msg, "2 boundary edges");  // the fin's free edges
}

TEST(MeshCheck, DegenerateTrianglesRepeatedIndexAndZeroArea) {
  // Split edge (0,1) of the y = 0 face at its midpoint 4 and close the T-junction with the sliver
  // (0,1,4): the mesh stays closed and consistent, but the sliver has zero area. Then add a triangle
  // with a repeated index.
  TriangleMesh mesh = tetrahedron();
  mesh.vertices.emplace_back(0.5, 0.0, 0.0);
  mesh.triangles[1] = {0, 4, 3};
  mesh.triangles.push_back({4, 1, 3});
  mesh.triangles.push_back({0, 1, 4});  // triangle 5: the sliver
  EXPECT_TRUE(check_mesh(mesh).boundary_edge_count == 0 && check_mesh(mesh).misoriented_edge_count == 0);
  mesh.triangles.push_back({2, 2, 3});  // triangle 6
  const std::string msg = solid_error(mesh);
  EXPECT_CONTAINS(msg,
                  "the mesh has 2 degenerate triangles (a repeated vertex or zero area), first: "
                  "triangle 5 (vertices 0, 1, 4), triangle 6 (vertices 2, 2, 3); remove them");
  EXPECT_EQ(msg.find("boundary"), std::string::npos) << msg;  // repeated-index triangles add no edges
}

TEST(MeshCheck, DegenerateTrianglesWhoseRemovalLeavesAClosedSurfaceAreLeftOutWithANotice) {
  // The tetrahedron with a triangle of a repeated index and a back-to-back pair of zero-area triangles
  // on three collinear points (closed and consistent among themselves, as CAD exports leave them): the
  // surface without them is the tetrahedron's, whose solid is well defined: the same numbers, bit for
  // bit (a left-out triangle adds no term), and a notice naming the triangles.
  TriangleMesh mesh = tetrahedron();
  mesh.vertices.emplace_back(0.1, 0.1, 0.1);
  mesh.vertices.emplace_back(0.2, 0.2, 0.2);
  mesh.vertices.emplace_back(0.3, 0.3, 0.3);
  mesh.triangles.push_back({1, 1, 2});  // triangle 4
  mesh.triangles.push_back({4, 5, 6});  // triangle 5
  mesh.triangles.push_back({4, 6, 5});  // triangle 6
  ASSERT_EQ(check_mesh(mesh).degenerate_count, 3u);
  const MeshMassResult clean = solid_mass_properties(tetrahedron(), MassSpec::density(1000.0), "part.stl");
  const MeshMassResult r = solid_mass_properties(mesh, MassSpec::density(1000.0), "part.stl");
  EXPECT_EQ(r.properties.mass, clean.properties.mass);
  EXPECT_NEAR(r.properties.volume, 1.0 / 6.0, 1e-16);
  EXPECT_EQ(r.properties.center_of_mass, clean.properties.center_of_mass);
  EXPECT_EQ(r.properties.inertia, clean.properties.inertia);
  ASSERT_EQ(r.warnings.size(), 1u);
  EXPECT_CONTAINS(r.warnings[0],
                  "part.stl: left out 3 degenerate (zero-area) triangles (4, 5, 6), which add nothing to the "
                  "solid: the surface without them is closed");
}

TEST(MeshCheck, IndexOutOfRange) {
  TriangleMesh mesh = tetrahedron();
  mesh.triangles[3] = {0, 3, 99};
  const std::string msg = solid_error(mesh);
  EXPECT_CONTAINS(msg,
                  "1 triangle refers to vertices that do not exist (the mesh has 4 vertices, "
                  "valid indices 0..3), first: triangle 3 (vertices 0, 3, 99)");
  // The unchecked fast path and the shell path refuse it too instead of reading out of bounds.
  EXPECT_THROW((void)integrate_solid_mesh(mesh), MeshError);
  EXPECT_THROW((void)shell_mass_properties(mesh, 0.001, MassSpec::density(1.0)), MeshError);
}

TEST(MeshCheck, NonFiniteVertex) {
  TriangleMesh mesh = tetrahedron();
  mesh.vertices[2].y() = std::nan("");
  const std::string msg = solid_error(mesh);
  EXPECT_CONTAINS(msg, "1 vertex has non-finite coordinates (NaN or infinity), first: vertex 2 (0, nan, 0)");
}

TEST(MeshCheck, ZeroVolumeIsRejected) {
  // Two triangles back to back: closed, manifold, consistently oriented, and flat.
  const TriangleMesh sheet{{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)}, {{0, 1, 2}, {0, 2, 1}}};
  EXPECT_TRUE(check_mesh(sheet).solid());
  EXPECT_CONTAINS(solid_error(sheet), "encloses zero volume");
}

TEST(MeshCheck, EmptyMeshIsRejected) {
  EXPECT_CONTAINS(solid_error(TriangleMesh{}), "no triangles");
  EXPECT_THROW((void)shell_mass_properties(TriangleMesh{}, 0.001, MassSpec::density(1.0)), MeshError);
}

TEST(MeshCheck, ShellAcceptsOpenMeshes) {
  TriangleMesh open = tetrahedron();
  open.triangles.pop_back();
  const MeshMassResult r = shell_mass_properties(open, 0.001, MassSpec::density(1000.0));
  EXPECT_NEAR(r.surface_area, 1.0 + std::sqrt(3.0) / 2, 1e-15);  // two right triangles + slanted face
}

TEST(MeshCheck, AShellAsThickAsTheMeshsFinestEdgeIsWarnedAbout) {
  // The unit tetrahedron's shortest edges are 1 m (its legs); its slanted ones are √2.
  EXPECT_TRUE(shell_mass_properties(tetrahedron(), 0.999, MassSpec::density(1.0)).warnings.empty());
  const MeshMassResult thick = shell_mass_properties(tetrahedron(), 1.0, MassSpec::density(1.0), "tet");
  ASSERT_EQ(thick.warnings.size(), 1u);
  EXPECT_CONTAINS(thick.warnings[0], "tet: shell thickness 1 m is at least the mesh's shortest edge, 1 m");
}

TEST(MeshCheck, SeveralDefectsAreAllReported) {
  TriangleMesh mesh = tetrahedron();
  mesh.triangles.pop_back();
  std::swap(mesh.triangles[0][1], mesh.triangles[0][2]);
  const std::string msg = solid_error(mesh);
  EXPECT_CONTAINS(msg, "boundary edges");
  EXPECT_CONTAINS(msg, "inconsistently oriented");
}

}  // namespace
}  // namespace tumble
