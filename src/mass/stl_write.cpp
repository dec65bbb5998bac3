// Binary STL writer: an 80-byte header, a little-endian uint32 triangle count, then per triangle the
// unit normal and three corners as little-endian float32 and a zero uint16 attribute (50 bytes).
// Twenty lines do not justify routing through assimp's exporter, which needs a whole aiScene.
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fmt/format.h>
#include <fstream>
#include <limits>
#include <vector>

#include "tumble/error.hpp"
#include "tumble/mass/mesh_check.hpp"
#include "tumble/mass/mesh_io.hpp"

namespace tumble {
namespace {

void put_u32(unsigned char* out, std::uint32_t x) {
  for (int i = 0; i < 4; ++i) out[i] = static_cast<unsigned char>(x >> (8 * i));
}
void put_f32(unsigned char* out, double x) {
  put_u32(out, std::bit_cast<std::uint32_t>(static_cast<float>(x)));
}

}  // namespace

void write_binary_stl(const TriangleMesh& mesh, const std::filesystem::path& path) {
  const MeshReport report = check_mesh_indices(mesh);
  if (!report.usable()) {
    throw MeshError(fmt::format("cannot write {}: {}", path.string(), describe_solid_defects(report)));
  }
  if (mesh.triangles.size() > std::numeric_limits<std::uint32_t>::max()) {
    throw FileError(fmt::format("{}: {} triangles do not fit the 32-bit count of binary STL", path.string(),
                                mesh.triangles.size()));
  }
  // Write next to the target and rename: a failed write never leaves a truncated file behind.
  std::filesystem::path partial = path;
  partial += ".partial";
  {
    std::ofstream out(partial, std::ios::binary | std::ios::trunc);
    if (!out) {
      throw FileError(fmt::format("{}: cannot open for writing: {}", path.string(), std::strerror(errno)));
    }
    std::array<unsigned char, 84> header{};
    const char title[] = "binary STL written by tumble";
    std::memcpy(header.data(), title, sizeof title - 1);
    put_u32(header.data() + 80, static_cast<std::uint32_t>(mesh.triangles.size()));
    out.write(reinterpret_cast<const char*>(header.data()), header.size());

    constexpr std::size_t kChunk = 4096;  // triangles per write
    std::vector<unsigned char> buffer(kChunk * 50);
    for (std::size_t first = 0; first < mesh.triangles.size(); first += kChunk) {
      const std::size_t n = std::min(kChunk, mesh.triangles.size() - first);
      for (std::size_t k = 0; k < n; ++k) {
        const auto& f = mesh.triangles[first + k];
        const Vec3& a = mesh.vertices[f[0]];
        const Vec3& b = mesh.vertices[f[1]];
        const Vec3& c = mesh.vertices[f[2]];
        const Vec3 cross = (b - a).cross(c - a);
        const double len = cross.norm();
        const Vec3 normal = len > 0.0 ? Vec3(cross / len) : Vec3::Zero();
        unsigned char* p = buffer.data() + 50 * k;
        for (int i = 0; i < 3; ++i) put_f32(p + 4 * i, normal(i));
        for (int i = 0; i < 3; ++i) put_f32(p + 12 + 4 * i, a(i));
        for (int i = 0; i < 3; ++i) put_f32(p + 24 + 4 * i, b(i));
        for (int i = 0; i < 3; ++i) put_f32(p + 36 + 4 * i, c(i));
        p[48] = p[49] = 0;
      }
      out.write(reinterpret_cast<const char*>(buffer.data()), static_cast<std::streamsize>(50 * n));
    }
    out.close();
    if (!out) {
      std::error_code ignored;
      std::filesystem::remove(partial, ignored);
      throw FileError(fmt::format("{}: writing failed (disk full?)", path.string()));
    }
  }
  std::error_code ec;
  std::filesystem::rename(partial, path, ec);
  if (ec) {
    std::filesystem::remove(partial, ec);
    throw FileError(
        fmt::format("{}: cannot move the written file into place: {}", path.string(), ec.message()));
  }
}

}  // namespace tumble
