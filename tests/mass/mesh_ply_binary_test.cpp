// Binary PLY is read by tumble (mesh_read_ply_binary.cpp), not assimp: both byte orders, coordinates of
// any scalar type kept exactly (a double stays a double), other properties and elements skipped by size.
// Hostile files (truncated, counts larger than the file, indices out of range, list counts of 0,
// huge or negative, the files on which assimp crashed or hung) each get their own message, and a
// mutation loop over a valid file never gets anything but a mesh or a FileError.
#include <gtest/gtest.h>

#include <bit>
#include <cstring>
#include <fmt/format.h>
#include <fstream>
#include <random>

#include "mesh_support.hpp"
#include "tumble/error.hpp"
#include "tumble/mass/mesh_io.hpp"
#include "tumble/mass/mesh_mass.hpp"

namespace tumble {
namespace {

using test::TestDir;

/// A binary PLY written value by value in either byte order.
struct BinaryPly {
  bool big_endian = false;
  std::string header;
  std::string data;

  template <class T>
  BinaryPly& put(T value) {
    char raw[sizeof(T)];
    std::memcpy(raw, &value, sizeof(T));
    if (big_endian != (std::endian::native == std::endian::big)) std::reverse(raw, raw + sizeof(T));
    data.append(raw, sizeof(T));
    return *this;
  }
  std::string bytes() const { return header + data; }
};

/// The unit cube [0, 1]³ as quads (outward), x, y, z of type T; faces as `list uchar int`.
template <class T>
BinaryPly cube(bool big_endian, const std::string& type) {
  BinaryPly p;
  p.big_endian = big_endian;
  p.header = fmt::format(
      "ply\nformat binary_{}_endian 1.0\ncomment made by tumble's tests\nelement vertex 8\n"
      "property {} x\nproperty {} y\nproperty {} z\nelement face 6\nproperty list uchar int "
      "vertex_indices\nend_header\n",
      big_endian ? "big" : "little", type, type, type);
  for (int i = 0; i < 8; ++i) p.put(T(i & 1)).put(T((i >> 1) & 1)).put(T((i >> 2) & 1));
  const int quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                           {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (const auto& q : quads) {
    p.put<std::uint8_t>(4);
    for (int v : q) p.put<std::int32_t>(v);
  }
  return p;
}

using test::load_error;
using test::write_bytes;

void expect_unit_cube(const LoadedMesh& loaded, const std::string& what) {
  EXPECT_EQ(loaded.mesh.vertices.size(), 8U) << what;
  EXPECT_EQ(loaded.mesh.triangles.size(), 12U) << what;
  const MeshMassResult r = solid_mass_properties(loaded.mesh, MassSpec::density(1.0), what);
  test::expect_close(r.properties, MassProperties{1.0, Vec3(0.5, 0.5, 0.5), Mat3::Identity() / 6.0, 1.0},
                     1e-15, 1.0, what);
}

TEST(MeshPlyBinary, EveryByteOrderAndCoordinateTypeGivesTheCube) {
  TestDir dir;
  write_bytes(dir / "le_float.ply", cube<float>(false, "float").bytes());
  write_bytes(dir / "be_float.ply", cube<float>(true, "float32").bytes());
  write_bytes(dir / "le_double.ply", cube<double>(false, "double").bytes());
  write_bytes(dir / "be_double.ply", cube<double>(true, "float64").bytes());
  write_bytes(dir / "le_short.ply", cube<std::int16_t>(false, "short").bytes());
  write_bytes(dir / "be_uchar.ply", cube<std::uint8_t>(true, "uchar").bytes());
  for (const char* name :
       {"le_float.ply", "be_float.ply", "le_double.ply", "be_double.ply", "le_short.ply", "be_uchar.ply"}) {
    expect_unit_cube(load_mesh(dir / name), name);
  }
  EXPECT_EQ(load_mesh(dir / "be_double.ply").format, "binary PLY (big-endian)");
  EXPECT_EQ(load_mesh(dir / "le_float.ply").format, "binary PLY (little-endian)");
  EXPECT_EQ(load_mesh(dir / "le_double.ply").precision, "float64, every bit of the file's doubles");
  EXPECT_EQ(load_mesh(dir / "le_float.ply").precision, "float32, as the file declares");
  EXPECT_EQ(load_mesh(dir / "le_short.ply").precision, "integers, exact");
  EXPECT_TRUE(load_mesh(dir / "le_double.ply").warnings.empty());
}

TEST(MeshPlyBinary, DoublesKeepEveryBitAndOtherPropertiesAreSkipped) {
  // A tetrahedron with coordinates no float32 holds (0.1, 1/3, 1e-9 offsets), surrounded by what real
  // files carry: normals and colours between x, y, z, a face colour after the index list, a list of
  // texture coordinates before it, and an element of edges; indices as `list ushort uint vertex_index`.
  const double v[4][3] = {
      {0.1, 0.2, 0.3}, {1.0 / 3.0, 0.1 + 1e-9, 0.3}, {0.1, 2.0 / 3.0, 0.3 - 1e-12}, {0.1, 0.2, 0.7}};
  BinaryPly p;
  p.big_endian = true;
  p.header =
      "ply\nformat binary_big_endian 1.0\nelement vertex 4\nproperty double x\nproperty float nx\n"
      "property double y\nproperty uchar red\nproperty double z\nproperty int16 flags\n"
      "element face 4\nproperty list uchar float texcoord\nproperty list ushort uint vertex_index\n"
      "property uchar red\nelement edge 2\nproperty int vertex1\nproperty int vertex2\nend_header\n";
  for (const auto& c : v) {
    p.put(c[0]).put(0.5F).put(c[1]).put<std::uint8_t>(200).put(c[2]).put<std::int16_t>(-7);
  }
  const unsigned faces[4][3] = {{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {0, 3, 2}};
  for (const auto& f : faces) {
    p.put<std::uint8_t>(2).put(0.25F).put(0.75F);  // texture coordinates
    p.put<std::uint16_t>(3).put(f[0]).put(f[1]).put(f[2]);
    p.put<std::uint8_t>(9);
  }
  p.put<std::int32_t>(0).put<std::int32_t>(1).put<std::int32_t>(1).put<std::int32_t>(2);
  TestDir dir;
  write_bytes(dir / "tet.ply", p.bytes());
  const LoadedMesh loaded = load_mesh(dir / "tet.ply");
  ASSERT_EQ(loaded.mesh.vertices.size(), 4U);
  ASSERT_EQ(loaded.mesh.triangles.size(), 4U);
  for (int i = 0; i < 4; ++i) {
    for (int k = 0; k < 3; ++k)
      EXPECT_EQ(loaded.mesh.vertices[i][k], v[i][k]) << i << " " << k;  // bit for bit
  }
  // Scaled: each coordinate times the scale, rounded once.
  const LoadedMesh scaled = load_mesh(dir / "tet.ply", {.scale = 0.001});
  EXPECT_EQ(scaled.mesh.vertices[1].x(), 0.001 * (1.0 / 3.0));
}

struct Hostile {
  const char* name;
  std::string bytes;
  std::string message;  // expected in the error, after the path
};

/// Replaces the first `from` in s by `to`.
std::string replaced(std::string s, const std::string& from, const std::string& to) {
  const auto at = s.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  return s.replace(at, from.size(), to);
}

std::vector<Hostile> hostile_files() {
  const BinaryPly good = cube<float>(false, "float");
  const std::string g = good.bytes();
  const std::size_t data = good.header.size();  // 8 vertices × 12 bytes, then 6 faces × 17 bytes
  const std::size_t face0 = data + 96;
  auto face_byte = [&](int face, int offset) { return face0 + 17 * static_cast<std::size_t>(face) + offset; };
  auto with_int = [&](std::size_t at, std::uint32_t value) {
    std::string s = g;
    std::memcpy(s.data() + at, &value, 4);  // little-endian, as the file
    return s;
  };
  auto with_byte = [&](std::size_t at, char value) {
    std::string s = g;
    s[at] = value;
    return s;
  };
  const std::string f = std::to_string(face0);
  std::vector<Hostile> h;
  // What assimp 5.2 did with these: a segfault, an assertion abort, an endless loop.
  h.push_back(
      {"assimp_segfault_truncated.ply", g.substr(0, data + 60),
       ":4:1: 'element vertex 8' needs at least 96 bytes (12 per vertex), but only 60 follow the header: "
       "the count is wrong or the file is truncated"});
  h.push_back({"assimp_abort_no_y.ply", replaced(g, "property float y", "property float\"y"),
               ":6:10: unknown property type 'float\"y'"});
  h.push_back({"assimp_hang_cut_header.ply", "ply\nformat binary_littl\nelement vert",
               ":2:8: unknown PLY format 'binary_littl'"});
  // Truncated in the last face: the header's minimum sizes fit, the data does not.
  h.push_back(
      {"truncated.ply", g.substr(0, g.size() - 5),
       fmt::format(": face 5 (byte {}): list 'vertex_indices' declares 4 values (4 bytes each), but only "
                   "11 bytes are left in the file: the file is corrupt or truncated",
                   face_byte(5, 0))});
  // The same with the faces first, cut in the last vertex.
  const std::string faces_first = replaced(
      replaced(good.header, "element vertex 8\nproperty float x\nproperty float y\nproperty float z\n", ""),
      "end_header", "element vertex 8\nproperty float x\nproperty float y\nproperty float z\nend_header");
  h.push_back(
      {"truncated_in_a_vertex.ply", faces_first + good.data.substr(96) + good.data.substr(0, 91),
       fmt::format(": vertex 7 (byte {}): the file ends inside this vertex (the header declares 8): the "
                   "file is truncated, or the header's counts or types are wrong",
                   faces_first.size() + 102 + 84)});
  // Counts larger than the file can hold: refused from the header, before anything is allocated.
  h.push_back({"billion_vertices.ply", replaced(g, "element vertex 8", "element vertex 1000000000"),
               ":4:1: 'element vertex 1000000000' needs at least 12000000000 bytes (12 per vertex), but only "
               "198 follow the header"});
  h.push_back({"huge_face_count.ply", replaced(g, "element face 6", "element face 4294967295"),
               "'element face 4294967295' needs at least 4294967295 bytes (1 per face), but only 198 follow "
               "the header"});
  h.push_back({"index_out_of_range.ply", with_int(face_byte(2, 1 + 4), 8),
               fmt::format(": face 2 (byte {}): vertex index 8 (corner 1) is out of range: the file has 8 "
                           "vertices, numbered from 0",
                           face_byte(2, 0))});
  h.push_back({"negative_index.ply", with_int(face_byte(0, 1), 0xffffffffu),
               fmt::format(": face 0 (byte {}): vertex index -1 (corner 0) is out of range", f)});
  h.push_back(
      {"list_count_0.ply", with_byte(face_byte(3, 0), 0),
       fmt::format(": face 3 (byte {}): the face has 0 corners; a face needs at least 3", face_byte(3, 0))});
  h.push_back(
      {"list_count_255.ply", with_byte(face_byte(0, 0), char(255)),
       fmt::format(": face 0 (byte {}): list 'vertex_indices' declares 255 values (4 bytes each), but only "
                   "101 bytes are left in the file",
                   f)});
  // The count type changed in the header: the data after it is the same bytes.
  auto with_count_type = [&](const std::string& type, std::string faces) {
    return replaced(good.header, "property list uchar int", "property list " + type + " int") +
           good.data.substr(0, 96) + faces;
  };
  const std::size_t shorter = good.header.size() - 1;  // "char" or "uint" for "uchar"
  h.push_back(
      {"list_count_huge.ply",
       with_count_type("uint", std::string("\xff\xff\xff\xff", 4) + std::string(200, '\0')),
       fmt::format(": face 0 (byte {}): list 'vertex_indices' declares 4294967295 values (4 bytes each), but "
                   "only 200 bytes are left in the file: the file is corrupt or truncated, or the "
                   "header's counts or types are wrong",
                   shorter + 96)});
  h.push_back(
      {"list_count_negative.ply", with_count_type("char", "\xff" + good.data.substr(97)),
       fmt::format(": face 0 (byte {}): list 'vertex_indices' has a negative count (-1)", shorter + 96)});
  h.push_back(
      {"list_count_float.ply", replaced(g, "property list uchar int", "property list float int"),
       ":9:1: list 'vertex_indices' has the count type 'float'; a list count must be an integer type"});
  h.push_back({"float_indices.ply", replaced(g, "property list uchar int", "property list uchar float"),
               ":9:1: the face list 'vertex_indices' holds values of type 'float'; vertex indices must be an "
               "integer type"});
  // One face fewer in the header than in the data: the data left over says the counts are wrong.
  h.push_back({"face_count_short.ply", replaced(g, "element face 6", "element face 5"),
               fmt::format(": 17 bytes follow the elements the header declares (which end at byte {} of {}): "
                           "the header's counts are wrong",
                           face_byte(5, 0), g.size())});
  // One vertex more: the faces are read 12 bytes late, their counts are garbage.
  h.push_back({"vertex_count_long.ply", replaced(g, "element vertex 8", "element vertex 9"),
               "face 0 (byte " + std::to_string(face0 + 12) +
                   "): the face has 0 corners; a face needs at least 3 (or the header's counts or types are "
                   "wrong)"});
  h.push_back(
      {"nan_vertex.ply", with_int(data + 12, 0x7fc00000u),
       fmt::format(": vertex 1 (byte {}): the vertex (nan, 0, 0) has non-finite coordinates; fix the file",
                   data + 12)});
  h.push_back(
      {"no_end_header.ply", replaced(g, "end_header", "end_hexder"), ":10:1: unexpected 'end_hexder'"});
  h.push_back({"binary_garbage_in_header.ply", replaced(g, "comment", "\x01\x02\xff garbage"),
               ":3:1: unexpected '\\x01\\x02\xff' in the PLY header"});
  return h;
}

TEST(MeshPlyBinary, HostileFilesGetTheirOwnMessage) {
  TestDir dir;
  for (const Hostile& h : hostile_files()) {
    write_bytes(dir / h.name, h.bytes);
    const std::string msg = load_error(dir / h.name);
    EXPECT_TRUE(msg.starts_with((dir / h.name).string())) << msg;
    EXPECT_NE(msg.find(h.message), std::string::npos)
        << h.name << "\n  got: " << msg << "\n want: " << h.message;
    EXPECT_LT(msg.size(), 400U) << msg;
  }
}

TEST(MeshPlyBinary, MutatedFilesGiveAMeshOrAFileErrorNeverACrash) {
  // The mutations that made assimp crash or hang in nearly half of the cases (random bytes, flipped
  // bits, 32-bit values planted, cuts, insertions): with tumble's reader each one is a mesh or a
  // FileError (or the MeshError of a mesh that is not a solid). Deterministic: a fixed seed.
  TestDir dir;
  const std::string seed = cube<float>(false, "float").bytes();
  std::mt19937 rng(20261126);
  int loaded = 0, refused = 0;
  for (int round = 0; round < 2000; ++round) {
    std::string s = seed;
    const int edits = 1 + static_cast<int>(rng() % 6);
    for (int e = 0; e < edits; ++e) {
      const std::size_t at = s.empty() ? 0 : rng() % s.size();
      switch (rng() % 5) {
        case 0:
          if (!s.empty()) s[at] = static_cast<char>(rng());
          break;
        case 1:
          if (!s.empty()) s[at] = static_cast<char>(s[at] ^ (1 << (rng() % 8)));
          break;
        case 2:
          s.resize(rng() % (s.size() + 1));
          break;
        case 3:
          if (s.size() >= 4) {
            const std::uint32_t v = rng() % 2 ? rng() % 1000 : rng();
            std::memcpy(s.data() + rng() % (s.size() - 3), &v, 4);
          }
          break;
        default:
          s.insert(at, std::string(1 + rng() % 8, static_cast<char>(rng())));
      }
    }
    write_bytes(dir / "m.ply", s);
    try {
      (void)solid_mass_properties(load_mesh(dir / "m.ply").mesh, MassSpec::density(1.0));
      ++loaded;
    } catch (const Error&) {  // FileError, or a MeshError of a mesh that bounds no solid
      ++refused;
    }
  }
  EXPECT_EQ(loaded + refused, 2000);
  EXPECT_GT(refused, 700);
}

}  // namespace
}  // namespace tumble
