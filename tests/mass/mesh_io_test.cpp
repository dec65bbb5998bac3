// Loading meshes (tumble's text readers and assimp): every format gives the same solid, STL corners are
// welded, the scale option scales, and every failure is a FileError that names the file.
// mesh_text_test.cpp tests the precision of the text formats and their error messages.
#include <gtest/gtest.h>

#include <fmt/format.h>
#include <fstream>

#include "mesh_support.hpp"
#include "tumble/error.hpp"
#include "tumble/mass/mesh_check.hpp"
#include "tumble/mass/mesh_io.hpp"
#include "tumble/mass/mesh_mass.hpp"
#include "tumble/mass/shapes.hpp"
#include "tumble/mass/tessellate.hpp"

namespace tumble {
namespace {

using test::TestDir;

/// The T-handle (bar 10 × 2 × 2 along x on top of a 2 × 2 × 6 stem) in centimetres: integer
/// coordinates, which every format and every float parser stores exactly. Built here independently
/// of examples/meshes/make_meshes.py: the outline extruded along y, caps split at the bar/stem joint.
TriangleMesh t_handle_cm() {
  const double outline[8][2] = {{-1, 0}, {1, 0}, {1, 6}, {5, 6}, {5, 8}, {-5, 8}, {-5, 6}, {-1, 6}};
  TriangleMesh m;
  for (double y : {-1.0, 1.0}) {
    for (const auto& p : outline) m.vertices.emplace_back(p[0], y, p[1]);
  }
  const std::uint32_t n = 8;
  const std::uint32_t cap[6][3] = {{0, 1, 2}, {0, 2, 7}, {6, 7, 5}, {7, 4, 5}, {7, 2, 4}, {2, 3, 4}};
  for (const auto& c : cap) {
    m.triangles.push_back({c[0], c[1], c[2]});              // y = −1 face, normal −y
    m.triangles.push_back({n + c[0], n + c[2], n + c[1]});  // y = +1 face, normal +y
  }
  for (std::uint32_t i = 0; i < n; ++i) {
    const std::uint32_t j = (i + 1) % n;
    m.triangles.push_back({i, n + i, n + j});
    m.triangles.push_back({i, n + j, j});
  }
  return m;
}

/// The T-handle as two boxes combined (an independent closed form), in the given length unit.
MassProperties t_handle_closed_form(double unit, double density) {
  const Box bar{unit * Vec3(10, 2, 2)}, stem{unit * Vec3(2, 2, 6)};
  return solid_mass_properties(bar, MassSpec::density(density))
             .transformed(Mat3::Identity(), unit * Vec3(0, 0, 7)) +
         solid_mass_properties(stem, MassSpec::density(density))
             .transformed(Mat3::Identity(), unit * Vec3(0, 0, 3));
}

void write_text(const std::filesystem::path& path, const std::string& text) { std::ofstream(path) << text; }

std::string ascii_stl(const TriangleMesh& m) {
  std::string s = "solid handle\n";
  for (const auto& f : m.triangles) {
    s += " facet normal 0 0 0\n  outer loop\n";
    for (auto i : f) {
      s += fmt::format("   vertex {} {} {}\n", m.vertices[i].x(), m.vertices[i].y(), m.vertices[i].z());
    }
    s += "  endloop\n endfacet\n";
  }
  return s + "endsolid handle\n";
}

std::string obj(const TriangleMesh& m) {
  std::string s = "# T-handle\no handle\n";
  for (const Vec3& v : m.vertices) s += fmt::format("v {} {} {}\n", v.x(), v.y(), v.z());
  for (const auto& f : m.triangles) s += fmt::format("f {} {} {}\n", f[0] + 1, f[1] + 1, f[2] + 1);
  return s;
}

std::string ply(const TriangleMesh& m) {
  std::string s = fmt::format(
      "ply\nformat ascii 1.0\nelement vertex {}\nproperty float x\nproperty float y\n"
      "property float z\nelement face {}\nproperty list uchar int vertex_indices\nend_header\n",
      m.vertices.size(), m.triangles.size());
  for (const Vec3& v : m.vertices) s += fmt::format("{} {} {}\n", v.x(), v.y(), v.z());
  for (const auto& f : m.triangles) s += fmt::format("3 {} {} {}\n", f[0], f[1], f[2]);
  return s;
}

TEST(MeshIo, AllFormatsGiveTheSameSolidAsTheClosedForm) {
  TestDir dir;
  const TriangleMesh mesh = t_handle_cm();
  write_binary_stl(mesh, dir / "binary.stl");
  write_text(dir / "ascii.stl", ascii_stl(mesh));
  write_text(dir / "handle.obj", obj(mesh));
  write_text(dir / "handle.ply", ply(mesh));
  const MassProperties want = t_handle_closed_form(1.0, 1.0);
  for (const char* name : {"binary.stl", "ascii.stl", "handle.obj", "handle.ply"}) {
    const TriangleMesh loaded = load_mesh(dir / name).mesh;
    EXPECT_EQ(loaded.vertices.size(), 16U) << name;  // welded back to the shared corners
    EXPECT_EQ(loaded.triangles.size(), 28U) << name;
    const MeshMassResult r = solid_mass_properties(loaded, MassSpec::density(1.0), name);
    // Integer coordinates are exact in every format: only integration rounding remains.
    test::expect_close(r.properties, want, 1e-14, 10.0, name);
    EXPECT_NEAR(r.properties.volume, 64.0, 1e-12) << name;
  }
}

TEST(MeshIo, PolygonsAreTriangulatedAndAllObjectsMerged) {
  // Two unit cubes as two OBJ objects with quad faces: V = 2, c midway, and each cube's I₃/6 plus
  // the parallel-axis terms of ±1.5 along x.
  TestDir dir;
  std::string s;
  for (int k = 0; k < 2; ++k) {
    s += fmt::format("o cube{}\n", k);
    const double x0 = 3.0 * k;
    for (int i = 0; i < 8; ++i) {
      s += fmt::format("v {} {} {}\n", x0 + (i & 1), (i >> 1) & 1, (i >> 2) & 1);
    }
    const int b = 8 * k + 1;  // OBJ indices are 1-based and global
    // Quads counter-clockwise seen from outside (corner i: x = bit 0, y = bit 1, z = bit 2).
    const int quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                             {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
    for (const auto& q : quads) s += fmt::format("f {} {} {} {}\n", b + q[0], b + q[1], b + q[2], b + q[3]);
  }
  write_text(dir / "cubes.obj", s);
  const LoadedMesh loaded = load_mesh(dir / "cubes.obj");
  EXPECT_EQ(loaded.parts, 2U);
  ASSERT_EQ(loaded.warnings.size(), 1U);
  EXPECT_NE(loaded.warnings[0].find("holds 2 objects ('cube0', 'cube1'); they were merged into one body"),
            std::string::npos)
      << loaded.warnings[0];
  const MeshMassResult r = solid_mass_properties(loaded.mesh, MassSpec::density(1.0));
  const Mat3 I = 2.0 * Mat3::Identity() / 6.0 + 2.0 * parallel_axis_term(1.0, Vec3(1.5, 0, 0));
  test::expect_close(r.properties, MassProperties{2.0, Vec3(2.0, 0.5, 0.5), I, 2.0}, 1e-14, 1.0);
}

TEST(MeshIo, WeldingClosesABinaryStl) {
  // Binary STL stores three corners per triangle; after welding the sphere is closed again, with the
  // original vertex count.
  TestDir dir;
  const TriangleMesh sphere = tessellate(Sphere{0.5}, 24);
  write_binary_stl(sphere, dir / "sphere.stl");
  const TriangleMesh loaded = load_mesh(dir / "sphere.stl").mesh;
  EXPECT_EQ(loaded.vertices.size(), sphere.vertices.size());
  EXPECT_TRUE(check_mesh(loaded).solid()) << describe_solid_defects(check_mesh(loaded));
  // The file holds float32 coordinates: relative rounding 6e-8 per coordinate, a few times that in
  // V and I; 1e-6 bounds it.
  test::expect_close(solid_mass_properties(loaded, MassSpec::density(1.0)).properties,
                     integrate_solid_mesh(sphere), 1e-6, 0.5);
}

TEST(MeshIo, ScaleMultipliesCoordinates) {
  // Mass ∝ s³ and inertia ∝ s⁵ at fixed density; the centre of mass ∝ s.
  TestDir dir;
  write_binary_stl(t_handle_cm(), dir / "handle_cm.stl");
  const MassSpec steel = MassSpec::density(7850.0);
  const MeshMassResult one = solid_mass_properties(load_mesh(dir / "handle_cm.stl").mesh, steel);
  for (double s : {0.01, 2.5}) {
    const MeshMassResult scaled =
        solid_mass_properties(load_mesh(dir / "handle_cm.stl", {.scale = s}).mesh, steel);
    // Scaling rounds each coordinate once (ε relative); 1e-13 leaves room for the integration.
    const MassProperties want{one.properties.mass * s * s * s, s * one.properties.center_of_mass,
                              one.properties.inertia * std::pow(s, 5), one.properties.volume * s * s * s};
    test::expect_close(scaled.properties, want, 1e-13, s * 10.0, fmt::format("scale {}", s));
  }
  EXPECT_THROW((void)load_mesh(dir / "handle_cm.stl", {.scale = 0.0}), InvalidArgument);
  EXPECT_THROW((void)load_mesh(dir / "handle_cm.stl", {.scale = -1.0}), InvalidArgument);
  EXPECT_THROW((void)load_mesh(dir / "handle_cm.stl", {.scale = std::nan("")}), InvalidArgument);
}

std::string file_error(const std::filesystem::path& path) {
  try {
    (void)load_mesh(path);
  } catch (const FileError& e) {
    return e.what();
  }
  ADD_FAILURE() << "no FileError for " << path;
  return "";
}

TEST(MeshIo, MissingFileNamesThePath) {
  TestDir dir;
  const auto path = dir / "no_such_mesh.stl";
  const std::string msg = file_error(path);
  EXPECT_NE(msg.find(path.string()), std::string::npos) << msg;
  EXPECT_NE(msg.find("no such file"), std::string::npos) << msg;
}

TEST(MeshIo, GarbageEmptyAndTriangleFreeFilesNameThePath) {
  TestDir dir;
  write_text(dir / "garbage.stl", "this is not a mesh \x01\x02\x03 at all\n");
  write_text(dir / "empty.obj", "");
  write_text(dir / "points.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\n");
  write_text(dir / "lines.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nl 1 2\nl 2 3\n");
  write_text(dir / "mesh.xyz123", "hello\n");
  for (const char* name : {"garbage.stl", "empty.obj", "points.obj", "lines.obj", "mesh.xyz123"}) {
    const std::string msg = file_error(dir / name);
    EXPECT_NE(msg.find((dir / name).string()), std::string::npos) << msg;
  }
  // Neither ASCII nor binary STL: tumble says why, before assimp sees it (mesh_limits_test.cpp has the
  // binary STLs of the wrong size); assimp's reason comes through for the formats it reads.
  std::string msg = file_error(dir / "garbage.stl");
  EXPECT_NE(msg.find(
                "garbage.stl: not an STL file: too short for a binary STL (30 bytes; its header alone is "
                "84) and not ASCII STL (which starts with 'solid')"),
            std::string::npos)
      << msg;
  msg = file_error(dir / "mesh.xyz123");
  EXPECT_NE(msg.find("cannot read the mesh: "), std::string::npos) << msg;
}

TEST(MeshIo, NonFiniteCoordinateNamesTheVertex) {
  TestDir dir;
  // Text: the line and column of the word.
  write_text(dir / "nan.obj", "v 0 0 0\nv 1 0 0\nv 0 nan 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 2 3 4\nf 1 4 3\n");
  std::string msg = file_error(dir / "nan.obj");
  EXPECT_NE(msg.find("nan.obj:3:5: y coordinate 'nan' is not finite"), std::string::npos) << msg;
  // Binary STL: the first triangle that has the corner, and its bytes. Its second corner is (0, nan, 0).
  // (Written by hand: write_binary_stl refuses non-finite vertices.)
  const float nan = std::nanf("");
  const float corners[4][3][3] = {{{0, 0, 0}, {0, nan, 0}, {1, 0, 0}},
                                  {{0, 0, 0}, {1, 0, 0}, {0, 0, 1}},
                                  {{1, 0, 0}, {0, nan, 0}, {0, 0, 1}},
                                  {{0, 0, 0}, {0, 0, 1}, {0, nan, 0}}};
  std::string stl(80, ' ');
  const std::uint32_t count = 4;  // little-endian on every machine tumble builds for (x86-64, arm64)
  stl.append(reinterpret_cast<const char*>(&count), 4);
  for (const auto& facet : corners) {
    stl.append(12, '\0');  // normal
    stl.append(reinterpret_cast<const char*>(facet), sizeof facet);
    stl.append(2, '\0');  // attribute
  }
  write_text(dir / "nan.stl", stl);
  msg = file_error(dir / "nan.stl");
  EXPECT_NE(msg.find(
                "nan.stl: corner 1 of triangle 0 (bytes 108 to 119) has non-finite coordinates (0, nan, 0)"),
            std::string::npos)
      << msg;
}

TEST(MeshIo, WriteFailureIsAFileError) {
  TestDir dir;
  EXPECT_THROW(write_binary_stl(t_handle_cm(), dir / "no_dir" / "x.stl"), FileError);
}

TEST(MeshIo, ExampleTHandleMatchesTwoBoxes) {
  // examples/meshes/t_handle.stl is the same T in metres (0.10 × 0.02 × 0.02 bar, 0.06 stem) stored
  // as float32: coordinates like 0.01 are rounded to 6e-8 relative, so 1e-6 bounds the difference.
  const auto path = std::filesystem::path(TUMBLE_SOURCE_DIR) / "examples/meshes/t_handle.stl";
  const MeshMassResult r = solid_mass_properties(load_mesh(path).mesh, MassSpec::density(7850.0));
  test::expect_close(r.properties, t_handle_closed_form(0.01, 7850.0), 1e-6, 0.1);
}

TEST(MeshIo, ExampleAsteroidIsAClosedSolid) {
  const auto path = std::filesystem::path(TUMBLE_SOURCE_DIR) / "examples/meshes/asteroid.obj";
  const TriangleMesh mesh = load_mesh(path).mesh;
  EXPECT_EQ(mesh.triangles.size(), 320U);
  const MeshMassResult r = solid_mass_properties(mesh, MassSpec::density(2000.0), "asteroid.obj");
  EXPECT_FALSE(r.flipped);
  EXPECT_NO_THROW(r.properties.validate());
  // Lumpy: three distinct principal moments (more than 1% apart), unlike a sphere.
  const Vec3 L = r.properties.principal_axes().Lambda;
  EXPECT_GT(L(1) / L(0), 1.01);
  EXPECT_GT(L(2) / L(1), 1.01);
}

}  // namespace
}  // namespace tumble
