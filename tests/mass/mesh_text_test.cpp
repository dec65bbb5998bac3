// The text mesh formats (OBJ, OFF, ASCII PLY, ASCII STL) are read by tumble at full precision: closed
// meshes with short decimal coordinates give the mass properties that exact rational arithmetic gives
// for the decimal text, to 1e-13. Several parts are counted and can be picked, point clouds and UTF-16
// get tumble's own messages, malformed lines are named by file:line:column, and header counts that
// cannot fit in the file are refused before anything is allocated.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstdlib>
#include <fmt/format.h>
#include <fstream>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "mesh_support.hpp"
#include "tumble/error.hpp"
#include "tumble/mass/mesh_io.hpp"
#include "tumble/mass/mesh_mass.hpp"

namespace tumble {
namespace {

using test::TestDir;

/// A closed polyhedron as decimal text: vertices as the strings written to the files, faces as
/// polygons (0-based, counter-clockwise seen from outside).
struct DecimalMesh {
  std::vector<std::array<std::string, 3>> vertices;
  std::vector<std::vector<int>> faces;
};

/// An L-shaped prism, sheared so that every product of inertia is non-zero: the outline (0.1, 0.2),
/// (2.05, 0.2), (2.05, 0.7), (0.6, 0.7), (0.6, 1.5), (0.1, 1.5) at z = 0.3 + 0.25 x + 0.1 y (bottom) and
/// one higher (top). Its caps are non-convex hexagons: fanned from their first corner, some triangles
/// stick out of the L and are cancelled by others of opposite sign (exact for planar polygons).
DecimalMesh l_prism() {
  return {{{"0.1", "0.2", "0.345"},
           {"2.05", "0.2", "0.8325"},
           {"2.05", "0.7", "0.8825"},
           {"0.6", "0.7", "0.52"},
           {"0.6", "1.5", "0.6"},
           {"0.1", "1.5", "0.475"},
           {"0.1", "0.2", "1.345"},
           {"2.05", "0.2", "1.8325"},
           {"2.05", "0.7", "1.8825"},
           {"0.6", "0.7", "1.52"},
           {"0.6", "1.5", "1.6"},
           {"0.1", "1.5", "1.475"}},
          {{5, 4, 3, 2, 1, 0},
           {6, 7, 8, 9, 10, 11},
           {0, 1, 7, 6},
           {1, 2, 8, 7},
           {2, 3, 9, 8},
           {3, 4, 10, 9},
           {4, 5, 11, 10},
           {5, 0, 6, 11}}};
}

DecimalMesh tetrahedron() {
  return {{{"0.1", "0.2", "0.3"}, {"2.05", "0.15", "0.35"}, {"0.45", "1.7", "0.25"}, {"0.3", "0.55", "1.9"}},
          {{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {0, 3, 2}}};
}

// Exact mass properties (unit density) of the solids bounded by the decimal text, computed with
// Python's fractions.Fraction: each coordinate as the exact rational its digits say, the divergence
// theorem over the fanned triangles (signed tetrahedra from the origin: V = Σ det/6, first moments
// Σ det/24 (a+b+c), second moments Σ det/120 (Σ aᵢaⱼ + sᵢsⱼ)), then c = M₁/V, C = M₂ − V c cᵀ,
// I = tr(C) I₃ − C. The doubles are those fractions rounded once (float(Fraction)).
MassProperties l_prism_exact() {
  MassProperties mp;
  mp.volume = mp.mass = 1.375;                            // 11/8
  mp.center_of_mass = Vec3(0.8640909090909091,            // 1901/2200
                           0.639090909090909,             // 703/1100
                           1.0799318181818183);           // 47517/44000
  mp.inertia << 0.3001454718276515, 0.13366363636363637,  // 1267814473/4224000000, 14703/110000
      -0.10322684185606061,                               // -21801509/211200000
      0.13366363636363637, 0.6050360968276515,            // 14703/110000, 2555672473/4224000000
      0.017267689393939394,                               // 455867/26400000
      -0.10322684185606061, 0.017267689393939394,         // -21801509/211200000, 455867/26400000
      0.627855018939394;                                  // 6630149/10560000
  return mp;
}

MassProperties tetrahedron_exact() {
  MassProperties mp;
  mp.volume = mp.mass = 0.7889583333333333;                 // 3787/4800
  mp.center_of_mass = Vec3(0.725, 0.65, 0.7);               // 29/40, 13/20, 7/10
  mp.inertia << 0.13767322916666666, 0.024753567708333334,  // 1321663/9600000, 950537/38400000
      0.02366875,                                           // 3787/160000
      0.024753567708333334, 0.170710859375,                 // 950537/38400000, 2185099/12800000
      0.009368880208333333,                                 // 71953/7680000
      0.02366875, 0.009368880208333333,                     // 3787/160000, 71953/7680000
      0.156509609375;                                       // 2003323/12800000
  return mp;
}

// Coordinates read exactly (each within ½ ulp of its decimal) leave only the rounding of the
// integration, a few ulps times the moderate cancellation about the centre of mass (≈1e-15); 1e-13
// leaves room for that and is five orders of magnitude below what float32 coordinates cost (≈1e-8,
// checked in FloatCoordinatesWouldFailTheTolerance).
constexpr double kTol = 1e-13;

void write_text(const std::filesystem::path& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
}

std::string obj(const DecimalMesh& m) {
  std::string s = "# decimal test solid\n";
  for (const auto& v : m.vertices) s += fmt::format("v {} {} {}\n", v[0], v[1], v[2]);
  for (const auto& f : m.faces) {
    s += "f";
    for (int i : f) s += fmt::format(" {}", i + 1);
    s += "\n";
  }
  return s;
}

std::string off(const DecimalMesh& m) {
  std::string s = fmt::format("OFF\n{} {} 0\n", m.vertices.size(), m.faces.size());
  for (const auto& v : m.vertices) s += fmt::format("{} {} {}\n", v[0], v[1], v[2]);
  for (const auto& f : m.faces) s += fmt::format("{} {}\n", f.size(), fmt::join(f, " "));
  return s;
}

std::string ply(const DecimalMesh& m, const std::string& type) {
  std::string s = fmt::format(
      "ply\nformat ascii 1.0\ncomment decimal test solid\nelement vertex {}\nproperty {} x\n"
      "property {} y\nproperty {} z\nelement face {}\nproperty list uchar int vertex_indices\nend_header\n",
      m.vertices.size(), type, type, type, m.faces.size());
  for (const auto& v : m.vertices) s += fmt::format("{} {} {}\n", v[0], v[1], v[2]);
  for (const auto& f : m.faces) s += fmt::format("{} {}\n", f.size(), fmt::join(f, " "));
  return s;
}

std::string stl(const DecimalMesh& m, const std::string& name = "decimal") {
  std::string s = fmt::format("solid {}\n", name);
  for (const auto& f : m.faces) {
    for (std::size_t k = 1; k + 1 < f.size(); ++k) {
      s += "  facet normal 0 0 0\n    outer loop\n";
      for (int i : {f[0], f[k], f[k + 1]}) {
        const auto& v = m.vertices[static_cast<std::size_t>(i)];
        s += fmt::format("      vertex {} {} {}\n", v[0], v[1], v[2]);
      }
      s += "    endloop\n  endfacet\n";
    }
  }
  return s + fmt::format("endsolid {}\n", name);
}

/// Every format's text of a mesh, by file name.
std::vector<std::pair<std::string, std::string>> every_text_format(const DecimalMesh& m) {
  return {{"m.obj", obj(m)},
          {"m.off", off(m)},
          {"double.ply", ply(m, "double")},
          {"float.ply", ply(m, "float")},
          {"m.stl", stl(m)}};
}

Vec3 strtod_vertex(const std::array<std::string, 3>& v) {
  return {std::strtod(v[0].c_str(), nullptr), std::strtod(v[1].c_str(), nullptr),
          std::strtod(v[2].c_str(), nullptr)};
}

void expect_exact(const std::filesystem::path& path, const DecimalMesh& m, const MassProperties& want,
                  const MeshLoadOptions& options = {}) {
  const LoadedMesh loaded = load_mesh(path, options);
  const std::string name = path.filename().string();
  EXPECT_TRUE(loaded.warnings.empty()) << name << ": " << loaded.warnings.front();
  EXPECT_NE(loaded.precision.find("every digit"), std::string::npos) << name << ": " << loaded.precision;
  // Welded back to the polyhedron's own vertices, each the double strtod (correctly rounded) gives.
  ASSERT_EQ(loaded.mesh.vertices.size(), m.vertices.size()) << name;
  for (const auto& v : m.vertices) {
    const Vec3 want_v = options.scale * strtod_vertex(v);
    const bool found = std::find(loaded.mesh.vertices.begin(), loaded.mesh.vertices.end(), want_v) !=
                       loaded.mesh.vertices.end();
    EXPECT_TRUE(found) << name << ": no vertex is exactly (" << v[0] << ", " << v[1] << ", " << v[2] << ")";
  }
  const MeshMassResult r = solid_mass_properties(loaded.mesh, MassSpec::density(1.0), name);
  EXPECT_FALSE(r.flipped) << name;
  test::expect_close(r.properties, want, kTol, 1.0, name);
}

TEST(MeshText, EveryTextFormatGivesTheExactMassPropertiesOfItsDecimals) {
  TestDir dir;
  for (const auto& [shape, mesh, want] : {std::tuple{"l_prism", l_prism(), l_prism_exact()},
                                          std::tuple{"tetrahedron", tetrahedron(), tetrahedron_exact()}}) {
    for (const auto& [name, text] : every_text_format(mesh)) {
      const auto path = dir / (std::string(shape) + "_" + name);
      write_text(path, text);
      expect_exact(path, mesh, want);
    }
  }
  // The volume alone: 11/8 to a few ulps (the integration's rounding), where float32 coordinates
  // would be off in the 8th digit.
  write_text(dir / "l.obj", obj(l_prism()));
  EXPECT_NEAR(solid_mass_properties(load_mesh(dir / "l.obj").mesh, MassSpec::density(1.0)).properties.volume,
              1.375, 4 * std::numeric_limits<double>::epsilon());
}

TEST(MeshText, FloatCoordinatesWouldFailTheTolerance) {
  // The same L-prism with every coordinate rounded to float32 first (what assimp hands over): its
  // mass properties are off by far more than kTol, so the test above tells exact reading from float.
  TriangleMesh m;
  for (const auto& v : l_prism().vertices)
    m.vertices.push_back(strtod_vertex(v).cast<float>().cast<double>());
  for (const auto& f : l_prism().faces) {
    for (std::size_t k = 1; k + 1 < f.size(); ++k) {
      m.triangles.push_back({static_cast<std::uint32_t>(f[0]), static_cast<std::uint32_t>(f[k]),
                             static_cast<std::uint32_t>(f[k + 1])});
    }
  }
  const MassProperties got = integrate_solid_mesh(m);
  EXPECT_GT(std::abs(got.volume - 1.375) / 1.375, 1e3 * kTol) << got.volume;
}

TEST(MeshText, ScaleIsAppliedToTheExactCoordinates) {
  // Millimetres to metres: mass ∝ s³, c ∝ s, I ∝ s⁵ at unit density; one more rounding per
  // coordinate (the product with 0.001) stays within kTol.
  TestDir dir;
  write_text(dir / "t.off", off(tetrahedron()));
  const double s = 0.001;
  MassProperties want = tetrahedron_exact();
  want.mass *= s * s * s;
  want.volume *= s * s * s;
  want.center_of_mass *= s;
  want.inertia *= std::pow(s, 5);
  const MeshMassResult r =
      solid_mass_properties(load_mesh(dir / "t.off", {.scale = s}).mesh, MassSpec::density(1.0));
  test::expect_close(r.properties, want, kTol, s);
}

TEST(MeshText, ObjForms) {
  // v/vt/vn corner forms, negative (relative) indices, comments, CRLF line ends, a continued line, a
  // UTF-8 byte-order mark, colours after the coordinates, and statements tumble does not need.
  TestDir dir;
  const std::string text =
      "\xEF\xBB\xBF# exported by hand\r\n"
      "mtllib none.mtl\r\n"
      "v 0.1 0.2 0.3 1 0 0\r\n"
      "v +2.05 0.15 0.35\r\n"
      "v 0.45 1.7 \\\r\n  0.25   # continued\r\n"
      "v 0.3\t0.55 1.9\r\n"
      "vt 0 0\r\nvn 0 0 1\r\nusemtl stone\r\ns off\r\n"
      "f 1/1/1 3/1/1 2/1/1\r\n"
      "f -4//1 -3//1 -1//1\r\n"
      "f 2/1 3/1 4/1\r\n"
      "f -4 -1 -2\r\n";
  write_text(dir / "forms.obj", text);
  expect_exact(dir / "forms.obj", tetrahedron(), tetrahedron_exact());
}

TEST(MeshText, OffAndPlyVariants) {
  TestDir dir;
  // OFF: counts on the keyword line, comments, blank lines, per-vertex colours (COFF), face colours.
  write_text(dir / "c.off",
             "COFF 4 4 6 # counts here\n# vertices\n0.1 0.2 0.3 255 0 0 255\n2.05 0.15 0.35 0 255 0 255\n\n"
             "0.45 1.7 0.25 0 0 255 255\n0.3 0.55 1.9 9 9 9 255\n3 0 2 1 1 0 0\n3 0 1 3\n3 1 2 3\n3 0 3 2\n");
  expect_exact(dir / "c.off", tetrahedron(), tetrahedron_exact());
  // PLY: extra vertex properties (normals, colours), an extra element, a uint list count and
  // "vertex_index", values spread over lines as the format allows.
  write_text(dir / "extra.ply",
             "ply\r\nformat ascii 1.0\r\nobj_info by hand\r\nelement vertex 4\r\nproperty float32 x\r\n"
             "property float32 y\r\nproperty float32 z\r\nproperty float nx\r\nproperty uchar red\r\n"
             "element material 1\r\nproperty list uchar float rgb\r\n"
             "element face 4\r\nproperty list uint int32 vertex_index\r\nend_header\r\n"
             "0.1 0.2 0.3 nan 1\r\n2.05 0.15 0.35 0 2\r\n0.45 1.7 0.25 0 3\r\n0.3 0.55 1.9 0 4\r\n"
             "3 0.5 0.5 0.5\r\n3 0 2 1\r\n3 0 1\r\n3\r\n3 1 2 3 3 0 3 2\r\n");
  expect_exact(dir / "extra.ply", tetrahedron(), tetrahedron_exact());
}

std::string error_of(const std::filesystem::path& path, const MeshLoadOptions& options = {}) {
  try {
    (void)load_mesh(path, options);
  } catch (const Error& e) {
    return e.what();
  }
  ADD_FAILURE() << "no error for " << path;
  return "";
}

/// Two tetrahedra as OBJ with the given part statements ("o" or "g"), the second moved by +50 in x
/// ("5" written before each x: 0.1 becomes 50.1).
std::string two_tetrahedra_obj(const std::string& statement) {
  std::string s;
  for (int k = 0; k < 2; ++k) {
    s += fmt::format("{} piece{}\n", statement, k + 1);
    for (const auto& v : tetrahedron().vertices)
      s += fmt::format("v {}{} {} {}\n", k ? "5" : "", v[0], v[1], v[2]);
    for (const auto& f : tetrahedron().faces) s += fmt::format("f {} {} {}\n", f[0] - 4, f[1] - 4, f[2] - 4);
  }
  return s;
}

TEST(MeshText, SeveralPartsAreCountedAndOneCanBePicked) {
  // The exact values of the first tetrahedron apply to part 1.
  TestDir dir;
  write_text(dir / "objects.obj", two_tetrahedra_obj("o"));
  write_text(dir / "groups.obj", two_tetrahedra_obj("g"));
  write_text(dir / "solids.stl", stl(tetrahedron(), "first") + stl(l_prism(), "second"));
  for (const auto& [name, word] : {std::pair{"objects.obj", "objects"}, std::pair{"groups.obj", "groups"},
                                   std::pair{"solids.stl", "solids"}}) {
    const LoadedMesh all = load_mesh(dir / name);
    EXPECT_EQ(all.parts, 2U) << name;
    ASSERT_EQ(all.warnings.size(), 1U) << name;
    const std::string& w = all.warnings[0];
    EXPECT_NE(w.find(fmt::format("holds 2 {}", word)), std::string::npos) << w;
    EXPECT_NE(w.find("merged into one body"), std::string::npos) << w;
    EXPECT_NE(w.find("--part K"), std::string::npos) << w;
    EXPECT_EQ(all.mesh.vertices.size(), name == std::string("solids.stl") ? 16U : 8U) << name;

    const LoadedMesh first = load_mesh(dir / name, {.part = 1});
    EXPECT_TRUE(first.warnings.empty()) << name;
    EXPECT_EQ(first.mesh.vertices.size(), 4U) << name;  // only the vertices its triangles use
    test::expect_close(solid_mass_properties(first.mesh, MassSpec::density(1.0)).properties,
                       tetrahedron_exact(), kTol, 1.0, name);
    if (name == std::string("solids.stl")) {
      test::expect_close(
          solid_mass_properties(load_mesh(dir / name, {.part = 2}).mesh, MassSpec::density(1.0)).properties,
          l_prism_exact(), kTol, 1.0, name);
    }
    const std::string msg = error_of(dir / name, {.part = 3});
    EXPECT_NE(msg.find(fmt::format("part 3 does not exist: the file has 2 {}", word)), std::string::npos)
        << msg;
  }
  // Names are quoted in the notice.
  EXPECT_NE(load_mesh(dir / "solids.stl").warnings.at(0).find("'first', 'second'"), std::string::npos);
}

TEST(MeshText, PointCloudsGetTumblesOwnMessage) {
  TestDir dir;
  const std::string xyz = "0 0 0\n1 0 0\n0 1 0\n0 0 1\n";
  write_text(dir / "cloud.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\np 1 2 3 4\n");
  write_text(dir / "cloud.off", "OFF\n4 0 0\n" + xyz);
  write_text(dir / "cloud.ply",
             "ply\nformat ascii 1.0\nelement vertex 4\nproperty double x\nproperty double y\n"
             "property double z\nend_header\n" +
                 xyz);
  // A binary PLY point cloud: tumble reads its header and answers before assimp is asked.
  std::string binary =
      "ply\nformat binary_little_endian 1.0\nelement vertex 4\nproperty float x\nproperty float y\n"
      "property float z\nelement face 0\nproperty list uchar int vertex_indices\nend_header\n";
  binary += std::string(4 * 12, '\0');
  write_text(dir / "binary_cloud.ply", binary);
  write_text(dir / "cloud.stl", "solid empty\nendsolid empty\n");
  for (const char* name : {"cloud.obj", "cloud.off", "cloud.ply", "binary_cloud.ply"}) {
    const std::string msg = error_of(dir / name);
    EXPECT_NE(msg.find((dir / name).string() + ": the file has 4 vertices but no faces: a point cloud has no "
                                               "volume"),
              std::string::npos)
        << msg;
  }
  EXPECT_NE(error_of(dir / "cloud.obj").find("its 1 line or point elements"), std::string::npos);
  EXPECT_NE(error_of(dir / "cloud.stl").find("no vertices and no faces"), std::string::npos);
}

std::string utf16(const std::string& ascii, bool little_endian, bool bom) {
  std::string out = bom ? (little_endian ? "\xFF\xFE" : "\xFE\xFF") : "";
  for (char c : ascii) out += little_endian ? std::string{c, '\0'} : std::string{'\0', c};
  return out;
}

TEST(MeshText, Utf16IsRefusedWithHowToConvert) {
  TestDir dir;
  const std::vector<std::pair<std::string, std::string>> files = {{"a.obj", obj(tetrahedron())},
                                                                  {"a.off", off(tetrahedron())},
                                                                  {"a.ply", ply(tetrahedron(), "double")},
                                                                  {"a.stl", stl(tetrahedron())}};
  for (const auto& [name, text] : files) {
    for (bool le : {true, false}) {
      for (bool bom : {true, false}) {
        const auto path = dir / fmt::format("{}_{}_{}", le ? "le" : "be", bom ? "bom" : "nobom", name);
        write_text(path, utf16(text, le, bom));
        const std::string msg = error_of(path);
        EXPECT_NE(msg.find(path.string() + ": the file is UTF-16 text"), std::string::npos) << msg;
        EXPECT_NE(msg.find("iconv -f UTF-16 -t UTF-8"), std::string::npos) << msg;
      }
    }
  }
  // UTF-8 with a byte-order mark is read.
  for (const auto& [name, text] : files) {
    write_text(dir / ("utf8_" + name), "\xEF\xBB\xBF" + text);
    expect_exact(dir / ("utf8_" + name), tetrahedron(), tetrahedron_exact());
  }
}

TEST(MeshText, MalformedLinesAreNamedByFileLineAndColumn) {
  TestDir dir;
  const std::string tet_v = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\n";
  const std::string ply_head =
      "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
      "element face 1\nproperty list uchar int vertex_indices\nend_header\n";
  const std::vector<std::tuple<std::string, std::string, std::string>> cases = {
      {"short_v.obj", "v 0 0 0\nv 1 2\n", ":2:6: the line ends where the z coordinate should be"},
      {"comma.obj", "v 0,1 0 0\n", ":1:3: x coordinate '0,1' is not a number; write the decimal separator"},
      {"word.obj", tet_v + "f 1 2 x\n", ":5:7: vertex index 'x' is not a whole number"},
      {"zero.obj", tet_v + "f 0 1 2\n", ":5:3: vertex index 0: OBJ counts vertices from 1"},
      {"past.obj", tet_v + "f 1 2 3\nf 1 2 9\n",
       ":6:7: vertex index 9 is past the last vertex: the file has 4"},
      {"back.obj", tet_v + "f -1 -2 -5\n", ":5:9: vertex index -5 reaches back before the first vertex"},
      {"line.obj", tet_v + "f 1 2\n", ":5:1: a face needs at least 3 corners, this one has 2"},
      {"nan.obj", "v 0 0 0\nv 1 0 0\nv 0 nan 0\n", ":3:5: y coordinate 'nan' is not finite"},
      {"huge.obj", "v 1e999 0 0\n", ":1:3: x coordinate '1e999' is out of the range of a double"},
      {"keyword.off", "OFFF\n3 1 0\n", ":1:1: 'OFFF' is not an OFF header"},
      {"binary.off", "OFF BINARY\n", ":1:5: binary OFF is not supported"},
      {"4d.off", "4OFF\n", ":1:1: '4OFF' is a 4-dimensional or n-dimensional OFF file"},
      {"index.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n", ":6:7: vertex index 3 is out of range"},
      {"short_face.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n4 0 1 2\n", ":6:8: face 0 declares 4 corners"},
      {"extra.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n3 0 1 2\n", ":7:1: unexpected text after"},
      {"ends.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n", ":2:1: the header declares 3 vertices and 1 faces"},
      {"type.ply", "ply\nformat ascii 1.0\nelement vertex 3\nproperty real x\n",
       ":4:10: unknown property type 'real'"},
      {"noz.ply", "ply\nformat ascii 1.0\nelement vertex 0\nproperty float x\nproperty float y\nend_header\n",
       ":3:1: the vertex element has no scalar property 'z'"},
      {"noend.ply", "ply\nformat ascii 1.0\nelement vertex 0\n",
       ":4:1: the PLY header has no 'end_header' line"},
      {"index.ply", ply_head + "0 0 0\n1 0 0\n0 1 0\n3 0 1 7\n", ":13:7: vertex index 7 is out of range"},
      {"value.ply", ply_head + "0 0 0\n1 zero 0\n0 1 0\n3 0 1 2\n",
       ":11:3: y coordinate 'zero' is not a number"},
      {"trail.ply", ply_head + "0 0 0\n1 0 0\n0 1 0\n3 0 1 2 5\n",
       ":13:9: unexpected text after the elements"},
      // Counts that disagree with the data say so (not "repair the non-manifold edges").
      {"fewer.ply",
       "ply\nformat ascii 1.0\nelement vertex 2\n" + ply_head.substr(38) + "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n",
       ":12:1: face 0 has 0 corners; a face needs at least 3 (or the header's counts are wrong)"},
      {"more.ply", ply_head + "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n3 0 2 1\n",
       ":14:1: unexpected text after the elements the header declares: the counts are wrong"},
      {"facet.stl", "solid s\n facet normal 0 0 1\n  outer loop\n   vertex 0 0 0\n   vertex 1 0\n  endloop\n",
       ":6:3: z coordinate 'endloop' is not a number"},
      {"keyword.stl", "solid s\n facet normal 0 0 1\n  outer lop\n", ":3:9: expected 'loop' after 'outer'"},
      {"two.stl", "solid s\n facet normal 0 0 1\n  outer loop\n   vertex 0 0 0\n   vertex 1 0 0\n  endloop\n",
       ":2:2: this facet has 2 vertices; a facet needs 3"},
      {"junk.stl", "solid s\nendsolid s\nmore\n", ":3:1: expected 'solid' to start a solid, found 'more'"},
  };
  for (const auto& [name, text, expected] : cases) {
    write_text(dir / name, text);
    const std::string msg = error_of(dir / name);
    EXPECT_NE(msg.find((dir / name).string() + expected), std::string::npos)
        << name << "\n got: " << msg << "\nwant: " << expected;
  }
}

TEST(MeshText, CountsThatCannotFitAreRefusedBeforeAllocating) {
  // Each claims billions of items in a file of a few bytes: refused at once with the header's line,
  // without reserving memory for them (an allocation of 10⁹ vertices would take 24 GB).
  TestDir dir;
  const std::string xyz = "property float x\nproperty float y\nproperty float z\n";
  const std::vector<std::tuple<std::string, std::string, std::string>> cases = {
      {"v.off", "OFF\n4000000000 1 0\n0 0 0\n", ":2:1: the header declares 4000000000 vertices and 1 faces"},
      {"f.off", "OFF\n3 999999999999 0\n0 0 0\n1 0 0\n0 1 0\n", ":2:1: the header declares 3 vertices"},
      {"v.ply", "ply\nformat ascii 1.0\nelement vertex 1000000000\n" + xyz + "end_header\n0 0 0\n",
       ":3:1: 'element vertex 1000000000' needs at least 6000000000 bytes"},
      {"f.ply",
       "ply\nformat binary_little_endian 1.0\nelement vertex 0\n" + xyz +
           "element face 4294967295\nproperty list uchar int vertex_indices\nend_header\n",
       ":7:1: 'element face 4294967295' needs at least 4294967295 bytes"},
      {"list.ply",
       "ply\nformat ascii 1.0\nelement vertex 3\n" + xyz +
           "element face 1\nproperty list uint int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n"
           "4000000000 0 1 2",
       ":13:17: the file ends inside list 'vertex_indices' of face 0 (3 of 4000000000 values)"},
  };
  for (const auto& [name, text, expected] : cases) {
    write_text(dir / name, text);
    const std::string msg = error_of(dir / name);
    EXPECT_NE(msg.find((dir / name).string() + expected), std::string::npos)
        << name << "\n got: " << msg << "\nwant: " << expected;
  }
}

TEST(MeshText, DamagedFilesGiveErrorsNeverCrashes) {
  // Every prefix of each format's file, and random byte changes, load or throw tumble::Error (nothing
  // else, no crash, no hang): truncation and corruption are the usual ways a text mesh goes bad.
  TestDir dir;
  std::mt19937 rng(20240611);
  std::size_t loaded = 0, refused = 0;
  for (const auto& [name, text] : every_text_format(tetrahedron())) {
    const auto path = dir / name;
    auto attempt = [&](const std::string& bytes) {
      write_text(path, bytes);
      try {
        (void)load_mesh(path);
        ++loaded;
      } catch (const Error&) {
        ++refused;
      }
    };
    for (std::size_t n = 0; n < text.size(); ++n) attempt(text.substr(0, n));
    const std::string alphabet("0123456789 -+.e\n/#vfOFFsolidfacet\0\xFF", 35);
    for (int trial = 0; trial < 300; ++trial) {
      std::string bytes = text;
      for (int k = 0; k < 1 + trial % 3; ++k) {
        bytes[rng() % bytes.size()] = alphabet[rng() % alphabet.size()];
      }
      attempt(bytes);
    }
  }
  EXPECT_GT(loaded, 0U);  // some damage is harmless (a changed digit)
  EXPECT_GT(refused, 0U);
}

}  // namespace
}  // namespace tumble
