// No mesh file can make tumble read forever or allocate more than its size justifies: FIFOs and devices
// are refused before a byte is read, files above the input limit (TUMBLE_MAX_INPUT_BYTES) are refused
// with the limit and how to raise it, header counts that the file cannot hold are refused naming the
// count and the bytes there are, a binary STL of the wrong size says truncated (or too long) with
// the triangle count and what the size allows, and a message quotes at most a short excerpt of a
// huge file.
#include <gtest/gtest.h>

#include <cstdlib>
#include <cstring>
#include <fmt/format.h>
#include <fstream>
#include <sys/stat.h>

#include "mesh_support.hpp"
#include "tumble/error.hpp"
#include "tumble/mass/input_file.hpp"
#include "tumble/mass/mesh_io.hpp"
#include "tumble/mass/shapes.hpp"
#include "tumble/mass/tessellate.hpp"

namespace tumble {
namespace {

using test::TestDir;

using test::load_error;
using test::write_bytes;

#define EXPECT_HAS(text, part) EXPECT_NE((text).find(part), std::string::npos) << "  got: " << (text)

/// Sets TUMBLE_MAX_INPUT_BYTES for the scope.
struct InputLimit {
  explicit InputLimit(const char* value) { ::setenv(kMaxInputBytesVariable, value, 1); }
  ~InputLimit() { ::unsetenv(kMaxInputBytesVariable); }
  InputLimit(const InputLimit&) = delete;
  InputLimit& operator=(const InputLimit&) = delete;
};

TEST(MeshLimits, FifosDevicesAndDirectoriesAreRefusedWithoutReading) {
  TestDir dir;
  // A FIFO with no writer: opening it for reading would wait forever; tumble does not wait.
  for (const char* name : {"pipe.obj", "pipe.stl", "pipe.ply", "pipe.glb"}) {
    ASSERT_EQ(::mkfifo((dir / name).c_str(), 0600), 0);
    const std::string msg = load_error(dir / name);
    EXPECT_HAS(msg, (dir / name).string() +
                        ": a FIFO (named pipe), which may never end, not a regular file; "
                        "give a mesh file");
  }
  // /dev/zero under a mesh's name, and as itself (no extension: the assimp path).
  std::filesystem::create_symlink("/dev/zero", dir / "zero.stl");
  EXPECT_HAS(load_error(dir / "zero.stl"),
             "zero.stl: a character device (such as /dev/zero), which may never "
             "end, not a regular file");
  EXPECT_HAS(load_error("/dev/zero"), "/dev/zero: a character device");
  std::filesystem::create_directory(dir / "folder.obj");
  EXPECT_HAS(load_error(dir / "folder.obj"), "folder.obj: a directory, not a regular file; give a mesh file");
}

TEST(MeshLimits, FilesAboveTheInputLimitAreRefusedNamingItAndHowToRaiseIt) {
  TestDir dir;
  write_binary_stl(tessellate(Sphere{1.0}, 8), dir / "sphere.stl");
  const auto size = std::filesystem::file_size(dir / "sphere.stl");
  {
    const InputLimit limit("1k");
    EXPECT_EQ(max_input_bytes(), 1024U);
    EXPECT_HAS(load_error(dir / "sphere.stl"),
               fmt::format("sphere.stl: the mesh file is {} bytes ({:.3g} KiB), more than tumble reads from "
                           "one input file (1024 bytes (1 KiB)); to read it, raise the limit with the "
                           "environment variable TUMBLE_MAX_INPUT_BYTES, e.g. TUMBLE_MAX_INPUT_BYTES=1G",
                           size, static_cast<double>(size) / 1024.0));
  }
  {
    const InputLimit limit(std::to_string(size).c_str());  // exactly the file: read
    EXPECT_NO_THROW((void)load_mesh(dir / "sphere.stl"));
  }
  for (const char* bad : {"lots", "12Q", "-5", "0", "99999999999T"}) {
    const InputLimit limit(bad);
    try {
      max_input_bytes();
      ADD_FAILURE() << bad;
    } catch (const InvalidArgument& e) {
      EXPECT_HAS(std::string(e.what()), fmt::format("TUMBLE_MAX_INPUT_BYTES='{}' is not a byte count", bad));
    }
  }
  EXPECT_EQ(max_input_bytes(), kDefaultMaxInputBytes);
}

TEST(MeshLimits, HeaderCountsTheFileCannotHoldAreRefusedBeforeAllocating) {
  // A 1 kB file that declares 10^9 vertices: OFF and ASCII PLY refuse it from the header.
  TestDir dir;
  std::string off = "OFF\n1000000000 4 0\n";
  for (int i = 0; i < 40; ++i) off += "0.25 0.5 0.75\n";
  off += "3 0 1 2\n";
  write_bytes(dir / "billion.off", off);
  EXPECT_HAS(
      load_error(dir / "billion.off"),
      "billion.off:2:1: the header declares 1000000000 vertices and 4 faces, which need at least "
      "6000000032 bytes (6 a vertex, 8 a face), but only 568 follow: the counts are wrong or the file is "
      "truncated");
  std::string ply =
      "ply\nformat ascii 1.0\nelement vertex 1000000000\nproperty float x\nproperty float y\nproperty float "
      "z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n";
  for (int i = 0; i < 40; ++i) ply += "0.25 0.5 0.75\n";
  write_bytes(dir / "billion.ply", ply);
  EXPECT_HAS(
      load_error(dir / "billion.ply"),
      "billion.ply:3:1: 'element vertex 1000000000' needs at least 6000000000 bytes (6 per vertex), but "
      "only 560 follow the header: the count is wrong or the file is truncated");
  // OBJ has no counts; a face may name a vertex far past the last one, which is refused at the end.
  write_bytes(dir / "far.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4000000000\n");
  EXPECT_HAS(load_error(dir / "far.obj"),
             "far.obj:4:7: vertex index 4000000000 is past the last vertex: the "
             "file has 3");
}

/// A binary STL of n triangles, then cut or padded to `size` bytes.
std::string binary_stl(std::uint32_t n, std::size_t size) {
  std::string s(80, 'x');
  s.append(reinterpret_cast<const char*>(&n), 4);
  s.resize(size, '\0');
  return s;
}

TEST(MeshLimits, BinaryStlOfTheWrongSizeSaysTruncatedWithTheCounts) {
  TestDir dir;
  write_bytes(dir / "cut.stl", binary_stl(12, 600));
  EXPECT_EQ(load_error(dir / "cut.stl"),
            (dir / "cut.stl").string() +
                ": truncated binary STL: the header says 12 triangles (84 + 50 x 12 = 684 bytes), the file "
                "size (600 bytes) allows 10");
  write_bytes(dir / "huge_count.stl", binary_stl(4000000000U, 1084));
  EXPECT_HAS(
      load_error(dir / "huge_count.stl"),
      "truncated binary STL: the header says 4000000000 triangles (84 + 50 x 4000000000 = 200000000084 "
      "bytes), the file size (1084 bytes) allows 20");
  write_bytes(dir / "long.stl", binary_stl(2, 84 + 50 * 3 + 7));
  EXPECT_HAS(
      load_error(dir / "long.stl"),
      "binary STL of the wrong size: the header says 2 triangles (84 + 50 x 2 = 184 bytes) but the file "
      "has 241 bytes, 57 more (room for 3 triangles): the count is wrong or data was appended");
  // The right size is binary, even when the header starts with "solid"; assimp reads the checked bytes.
  write_binary_stl(tessellate(Sphere{1.0}, 8), dir / "sphere.stl");
  std::string sphere = read_input_file(dir / "sphere.stl", "mesh file");
  sphere.replace(0, 6, "solid ");
  write_bytes(dir / "solid_binary.stl", sphere);
  EXPECT_EQ(load_mesh(dir / "solid_binary.stl").format, "binary STL");
  write_bytes(dir / "empty.stl", "");
  EXPECT_EQ(load_error(dir / "empty.stl"), (dir / "empty.stl").string() + ": the file is empty (0 bytes)");
  write_bytes(dir / "no_triangles.stl", binary_stl(0, 84));
  EXPECT_EQ(load_error(dir / "no_triangles.stl"),
            (dir / "no_triangles.stl").string() +
                ": a binary STL of 0 triangles (its 84-byte header only): no surface");
  write_bytes(dir / "short.stl", "not a mesh\n");
  EXPECT_HAS(load_error(dir / "short.stl"),
             "short.stl: not an STL file: too short for a binary STL (11 bytes; "
             "its header alone is 84) and not ASCII STL (which starts with 'solid')");
  // A binary header that starts with "solid" (common) and a wrong size: the text reader's complaint and
  // the binary explanation.
  std::string solid = binary_stl(12, 600);
  solid.replace(0, 6, "solid ");
  write_bytes(dir / "solid_cut.stl", solid);
  EXPECT_HAS(load_error(dir / "solid_cut.stl"),
             "; the file looks binary (a binary STL may start with 'solid' too): truncated binary STL: the "
             "header says 12 triangles (84 + 50 x 12 = 684 bytes), the file size (600 bytes) allows 10");
}

TEST(MeshLimits, OneBadNumberInAHugeAsciiStlGivesAShortMessage) {
  // 5 MB of facets, one bad coordinate in the middle, written without line breaks after it, and a
  // 1 MB solid name in another file: the message stays short and says the line.
  std::string facet =
      " facet normal 0 0 1\n  outer loop\n   vertex 0 0 0\n   vertex 1 0 0\n   vertex 0 1 0\n"
      "  endloop\n endfacet\n";
  std::string stl = "solid big\n";
  while (stl.size() < 2500000) stl += facet;
  const int bad_line = 1 + static_cast<int>(std::count(stl.begin(), stl.end(), '\n'));
  stl += "facet normal 0 0 1 outer loop vertex 0 0 " + std::string(2500000, '7') + "x";
  stl += " vertex 1 0 0 vertex 0 1 0 endloop endfacet\nendsolid big\n";
  TestDir dir;
  write_bytes(dir / "big.stl", stl);
  const std::string msg = load_error(dir / "big.stl");
  EXPECT_HAS(msg, fmt::format("big.stl:{}:", bad_line));
  EXPECT_HAS(msg, ": z coordinate '7777777777777777777777777777777777777777...' is not a number");
  EXPECT_LT(msg.size(), 200U) << msg.size();

  const std::string name(1000000, 'n');
  write_bytes(dir / "name.stl", "solid " + name + "\n" + facet);  // no endsolid: a warning quotes the name
  const LoadedMesh loaded = load_mesh(dir / "name.stl");
  ASSERT_EQ(loaded.warnings.size(), 1U);
  EXPECT_LT(loaded.warnings[0].size(), 300U);
  EXPECT_HAS(loaded.warnings[0], "the solid 'nnnnnnnnnnnnnnnnnnnnnnnnnnnnnnnnnnnnnnnn...' has no 'endsolid'");
}

}  // namespace
}  // namespace tumble
