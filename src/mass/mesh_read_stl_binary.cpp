// Binary STL: an 80-byte header, a little-endian uint32 count n, then n records of 50 bytes: a normal
// and three corners as float32 (x, y, z each), and a 2-byte attribute. The size is checked against n
// before this is called (mesh_io.cpp). Read here rather than by assimp's child process: the format is a
// fixed record that needs no parser to guard against, and the child's start and the copy of the bytes
// to it cost 0.2 s for a 5 MB file — most of reading a robot's hundred meshes. The corners are the
// float32 values exactly (a double holds every float); the normal is not used (the winding says which
// side is out).
#include <array>
#include <bit>
#include <cmath>

#include <fmt/format.h>

#include "mesh_text.hpp"
#include "tumble/error.hpp"
#include "tumble/mass/mesh_weld.hpp"

namespace tumble::mesh_text {

namespace {

float float_at(std::string_view bytes, std::size_t at) {
  std::uint32_t bits = 0;
  for (int i = 3; i >= 0; --i)
    bits = (bits << 8) | static_cast<unsigned char>(bytes[at + static_cast<std::size_t>(i)]);
  return std::bit_cast<float>(bits);
}

}  // namespace

RawMesh read_binary_stl(const std::filesystem::path& path, std::string_view bytes, std::uint64_t triangles,
                        double scale) {
  RawMesh mesh;
  mesh.every_vertex_used = true;  // every vertex is a corner
  mesh.welded = true;             // welded here, corner by corner, not from a soup of 3 n corners
  mesh.part_word = "solid";
  mesh.part_names.push_back("(binary STL)");
  mesh.triangles.reserve(triangles);
  mesh.part_of.assign(triangles, 0);
  VertexWelder welder(triangles / 2);  // a closed surface has about n/2 vertices for n triangles
  for (std::uint64_t t = 0; t < triangles; ++t) {
    const std::size_t record = 84 + 50 * t;
    std::array<std::uint32_t, 3> corners{};
    for (std::size_t corner = 0; corner < 3; ++corner) {
      const std::size_t at = record + 12 + 12 * corner;
      const float x = float_at(bytes, at), y = float_at(bytes, at + 4), z = float_at(bytes, at + 8);
      if (!(std::isfinite(x) && std::isfinite(y) && std::isfinite(z))) {
        throw FileError(
            fmt::format("{}: corner {} of triangle {} (bytes {} to {}) has non-finite coordinates ({}, "
                        "{}, {}); fix the file",
                        path.string(), corner, t, at, at + 11, x, y, z));
      }
      corners[corner] = welder.add(Vec3(scale * static_cast<double>(x), scale * static_cast<double>(y),
                                        scale * static_cast<double>(z)));
    }
    mesh.triangles.push_back(corners);
  }
  mesh.vertices = welder.take_vertices();
  return mesh;
}

}  // namespace tumble::mesh_text
