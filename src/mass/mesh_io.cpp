// Loading mesh files. OBJ, OFF, ASCII PLY and ASCII STL are read by tumble's own readers
// (mesh_read_*.cpp: every decimal digit kept); binary STL, binary PLY and every other format go
// through assimp (every mesh of the scene, node transforms applied, polygons triangulated). Either
// way parts are counted (and one may be picked), and vertices are welded by tumble (mesh_weld.cpp
// says why not by assimp).
#include "tumble/mass/mesh_io.hpp"

#include <algorithm>
#include <assimp/Importer.hpp>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <cmath>
#include <fmt/format.h>
#include <fstream>
#include <system_error>

#include "mesh_text.hpp"
#include "tumble/error.hpp"
#include "tumble/mass/mesh_weld.hpp"

namespace tumble {
namespace {

using mesh_text::RawMesh;

constexpr const char* kTextPrecision = "every digit of the text (each coordinate is the double nearest it)";

void require_readable_file(const std::filesystem::path& path) {
  std::error_code ec;
  const auto status = std::filesystem::status(path, ec);
  if (!std::filesystem::exists(status)) {
    throw FileError(fmt::format("{}: no such file; check the path and the working directory", path.string()));
  }
  if (!std::filesystem::is_regular_file(status)) {
    throw FileError(fmt::format("{}: not a regular file (a directory?); give a mesh file", path.string()));
  }
}

std::string lower_extension(const std::filesystem::path& path) {
  std::string ext = path.extension().string();
  for (char& c : ext) c = static_cast<char>(c >= 'A' && c <= 'Z' ? c - 'A' + 'a' : c);
  return ext;
}

/// The first `limit` bytes of the file (all of it by default).
std::string read_bytes(const std::filesystem::path& path, std::uint64_t size,
                       std::uint64_t limit = ~std::uint64_t{0}) {
  std::ifstream in(path, std::ios::binary);
  std::string bytes(static_cast<std::size_t>(std::min(size, limit)), '\0');
  if (!in || !in.read(bytes.data(), static_cast<std::streamsize>(bytes.size()))) {
    throw FileError(fmt::format("{}: cannot read the file (permissions?)", path.string()));
  }
  return bytes;
}

/// Refuses UTF-16 and UTF-32 text (with or without a byte-order mark): tumble reads ASCII or UTF-8.
void refuse_wide_text(const std::filesystem::path& path, std::string_view head) {
  auto byte = [&](std::size_t i) { return i < head.size() ? static_cast<unsigned char>(head[i]) : 256u; };
  auto text_char = [](unsigned c) { return c == '\t' || c == '\n' || c == '\r' || (c >= 0x20 && c < 0x7f); };
  std::string encoding, how;
  if (byte(0) == 0xFF && byte(1) == 0xFE && byte(2) == 0 && byte(3) == 0) {
    encoding = "UTF-32", how = "byte-order mark FF FE 00 00";
  } else if (byte(0) == 0 && byte(1) == 0 && byte(2) == 0xFE && byte(3) == 0xFF) {
    encoding = "UTF-32", how = "byte-order mark 00 00 FE FF";
  } else if (byte(0) == 0xFF && byte(1) == 0xFE) {
    encoding = "UTF-16", how = "byte-order mark FF FE, little-endian";
  } else if (byte(0) == 0xFE && byte(1) == 0xFF) {
    encoding = "UTF-16", how = "byte-order mark FE FF, big-endian";
  } else if (head.size() >= 4 && text_char(byte(0)) && byte(1) == 0 && text_char(byte(2)) && byte(3) == 0) {
    encoding = "UTF-16", how = "no byte-order mark, little-endian: every other byte is zero";
  } else if (head.size() >= 4 && byte(0) == 0 && text_char(byte(1)) && byte(2) == 0 && text_char(byte(3))) {
    encoding = "UTF-16", how = "no byte-order mark, big-endian: every other byte is zero";
  }
  if (encoding.empty()) return;
  const std::string p = path.string();
  throw FileError(fmt::format(
      "{}: the file is {} text ({}); tumble reads mesh text as ASCII or UTF-8: "
      "convert it, e.g. iconv -f {} -t UTF-8 '{}' > '{}'",
      p, encoding, how, encoding, p,
      (path.parent_path() / (path.stem().string() + "-utf8" + path.extension().string())).string()));
}

/// " ('a', 'b', ...)" for the first few names, or nothing when the format has no names (OFF, PLY).
std::string listed_names(const std::vector<std::string>& names) {
  if (std::all_of(names.begin(), names.end(), [](const std::string& n) { return n.empty(); })) return "";
  std::string out;
  const std::size_t shown = std::min<std::size_t>(names.size(), 5);
  for (std::size_t i = 0; i < shown; ++i) out += fmt::format("{}'{}'", i ? ", " : "", names[i]);
  return fmt::format(" ({}{})", out, names.size() > shown ? ", ..." : "");
}

/// Checks the part choice and, when several parts are merged, says so.
void note_parts(const std::filesystem::path& path, const std::vector<std::string>& names,
                const std::string& word, std::size_t part, LoadedMesh& out) {
  out.parts = names.size();
  if (part > names.size()) {
    throw InvalidArgument(fmt::format("{}: part {} does not exist: the file has {} {}{}{}; give 1 to {}",
                                      path.string(), part, names.size(), word, names.size() == 1 ? "" : "s",
                                      listed_names(names), names.size()));
  }
  if (part == 0 && names.size() > 1) {
    out.warnings.push_back(
        fmt::format("{} holds {} {}s{}; they were merged into one body (to take one "
                    "alone: tumble inertia --part K, K = 1 to {})",
                    path.string(), names.size(), word, listed_names(names), names.size()));
  }
}

[[noreturn]] void throw_no_faces(const std::filesystem::path& path, std::size_t vertices,
                                 std::size_t ignored) {
  if (vertices == 0) {
    throw FileError(
        fmt::format("{}: the file holds no vertices and no faces (empty?); export the surface "
                    "as triangles or polygons",
                    path.string()));
  }
  throw FileError(
      fmt::format("{}: the file has {} vertices but no faces: a point cloud has no volume{}; "
                  "tumble needs the closed surface as triangles or polygons (reconstruct a "
                  "surface from the points first, then export it)",
                  path.string(), vertices,
                  ignored ? fmt::format(" (nor have its {} line or point elements)", ignored) : ""));
}

/// Part selection, dropping unused vertices, welding.
LoadedMesh finish(const std::filesystem::path& path, RawMesh raw, const MeshLoadOptions& options,
                  std::string format, std::string precision) {
  if (raw.triangles.empty()) throw_no_faces(path, raw.vertices.size(), raw.ignored_elements);
  LoadedMesh out;
  out.format = std::move(format);
  out.precision = std::move(precision);
  out.warnings = std::move(raw.warnings);
  note_parts(path, raw.part_names, raw.part_word, options.part, out);

  // The triangles of the chosen part(s), with only the vertices they use, in the file's order.
  TriangleMesh m;
  constexpr std::uint32_t kUnused = 0xffffffffu;
  std::vector<std::uint32_t> renumber(raw.vertices.size(), kUnused);
  for (std::size_t t = 0; t < raw.triangles.size(); ++t) {
    if (options.part != 0 && raw.part_of[t] != options.part - 1) continue;
    for (std::uint32_t v : raw.triangles[t]) renumber[v] = 0;
  }
  for (std::size_t v = 0; v < raw.vertices.size(); ++v) {
    if (renumber[v] == kUnused) continue;
    renumber[v] = static_cast<std::uint32_t>(m.vertices.size());
    m.vertices.push_back(raw.vertices[v]);
  }
  for (std::size_t t = 0; t < raw.triangles.size(); ++t) {
    if (options.part != 0 && raw.part_of[t] != options.part - 1) continue;
    const auto& f = raw.triangles[t];
    m.triangles.push_back({renumber[f[0]], renumber[f[1]], renumber[f[2]]});
  }
  out.mesh = weld_identical_vertices(m);
  return out;
}

/// Names the bad vertex by the first face that uses it: assimp renumbers vertices (OBJ corners are
/// split per face), but faces keep the file's order, so "face 12 of mesh 0" is findable in the file.
[[noreturn]] void throw_non_finite(const std::filesystem::path& path, const aiMesh& part, unsigned mesh_index,
                                   unsigned vertex, double scale) {
  const aiVector3D& p = part.mVertices[vertex];
  std::string where = fmt::format("vertex {} of mesh {}", vertex, mesh_index);
  for (unsigned f = 0; f < part.mNumFaces; ++f) {
    const aiFace& face = part.mFaces[f];
    for (unsigned k = 0; k < face.mNumIndices; ++k) {
      if (face.mIndices[k] == vertex) {
        where = fmt::format("corner {} of face {} of mesh {}", k, f, mesh_index);
        f = part.mNumFaces - 1;  // stop at the first face that uses it
        break;
      }
    }
  }
  throw FileError(fmt::format("{}: {} has non-finite coordinates ({}, {}, {}){}; fix the file", path.string(),
                              where, p.x, p.y, p.z,
                              scale == 1.0 ? "" : fmt::format(" after scaling by {}", scale)));
}

LoadedMesh load_with_assimp(const std::filesystem::path& path, const MeshLoadOptions& options,
                            std::string format, std::string precision, std::vector<std::string> warnings) {
  Assimp::Importer importer;
  // Points and lines carry no surface: SortByPType splits them off and this drops them.
  importer.SetPropertyInteger(AI_CONFIG_PP_SBP_REMOVE, aiPrimitiveType_POINT | aiPrimitiveType_LINE);
  const aiScene* scene = importer.ReadFile(
      path.string(), aiProcess_Triangulate | aiProcess_PreTransformVertices | aiProcess_SortByPType);
  if (scene == nullptr) {
    throw FileError(fmt::format("{}: cannot read the mesh: {}", path.string(), importer.GetErrorString()));
  }

  // Each assimp mesh with triangles is a part (assimp makes one per object and material).
  RawMesh raw;
  raw.part_word = "mesh";
  raw.warnings = std::move(warnings);
  for (unsigned m = 0; m < scene->mNumMeshes; ++m) {
    const aiMesh* part = scene->mMeshes[m];
    const auto base = static_cast<std::uint32_t>(raw.vertices.size());
    const auto part_index = static_cast<std::uint32_t>(raw.part_names.size());
    for (unsigned i = 0; i < part->mNumVertices; ++i) {
      const aiVector3D& p = part->mVertices[i];
      const Vec3 v = options.scale *
                     Vec3(static_cast<double>(p.x), static_cast<double>(p.y), static_cast<double>(p.z));
      if (!v.allFinite()) throw_non_finite(path, *part, m, i, options.scale);
      raw.vertices.push_back(v);
    }
    bool any = false;
    for (unsigned f = 0; f < part->mNumFaces; ++f) {
      const aiFace& face = part->mFaces[f];
      if (face.mNumIndices != 3) continue;  // points and lines left over in a mixed mesh
      raw.triangles.push_back({base + face.mIndices[0], base + face.mIndices[1], base + face.mIndices[2]});
      raw.part_of.push_back(part_index);
      any = true;
    }
    if (any) {
      const std::string name = part->mName.C_Str();
      raw.part_names.push_back(name.empty() ? fmt::format("mesh {}", m) : name);
    }
  }
  if (raw.triangles.empty()) {
    throw FileError(
        fmt::format("{}: the file holds no triangles ({} meshes, only points or lines, or empty); export the "
                    "surface as triangles or polygons",
                    path.string(), scene->mNumMeshes));
  }
  return finish(path, std::move(raw), options, std::move(format), std::move(precision));
}

bool starts_with_solid(std::string_view head) {
  if (head.starts_with("\xEF\xBB\xBF")) head.remove_prefix(3);
  while (!head.empty() && (head[0] == ' ' || head[0] == '\t' || head[0] == '\r' || head[0] == '\n')) {
    head.remove_prefix(1);
  }
  if (head.size() < 5) return false;
  std::string word(head.substr(0, 5));
  for (char& c : word) c = static_cast<char>(c >= 'A' && c <= 'Z' ? c - 'A' + 'a' : c);
  return word == "solid";
}

LoadedMesh load_stl(const std::filesystem::path& path, std::uint64_t size, const MeshLoadOptions& options) {
  const std::string head = read_bytes(path, size, 512);
  std::uint64_t declared = 0;  // the triangle count a binary STL's header gives
  if (size >= 84) {
    for (int i = 3; i >= 0; --i) declared = (declared << 8) | static_cast<unsigned char>(head[80 + i]);
  }
  // A binary STL is exactly 84 + 50·n bytes; its 80-byte header may well start with "solid".
  if (size >= 84 && 84 + 50 * declared == size) {
    return load_with_assimp(path, options, "binary STL", "float32, the format's own", {});
  }
  refuse_wide_text(path, head);
  if (!starts_with_solid(head)) {
    // Neither: assimp says why it cannot read it.
    return load_with_assimp(path, options, "STL", "float32", {});
  }
  const mesh_text::Text text(path, read_bytes(path, size), options.scale);
  try {
    return finish(path, mesh_text::read_ascii_stl(text), options, "ASCII STL", kTextPrecision);
  } catch (const FileError& e) {
    if (text.view().substr(0, 4096).find('\0') == std::string_view::npos || size < 84) throw;
    throw FileError(
        fmt::format("{} (the file looks binary: a binary STL whose header declares {} triangles "
                    "is {} bytes long, this one is {}: truncated or padded?)",
                    e.what(), declared, 84 + 50 * declared, size));
  }
}

LoadedMesh load_ply(const std::filesystem::path& path, std::uint64_t size, const MeshLoadOptions& options) {
  // The header is text even in a binary PLY: read it (at most 1 MiB), then the rest only if ASCII.
  std::string head = read_bytes(path, size, std::uint64_t{1} << 20);
  refuse_wide_text(path, head);
  mesh_text::Text header_text(path, std::move(head), options.scale);
  const mesh_text::PlyHeader header = mesh_text::read_ply_header(header_text, size);
  const mesh_text::PlyElement* vertex = header.find("vertex");
  const mesh_text::PlyElement* face = header.find("face");
  if (face == nullptr || face->count == 0) throw_no_faces(path, vertex->count, 0);
  if (header.format == mesh_text::PlyHeader::Format::ascii) {
    const mesh_text::Text text(path, read_bytes(path, size), options.scale);
    return finish(path, mesh_text::read_ascii_ply(text, header), options, "ASCII PLY", kTextPrecision);
  }
  bool doubles = false;
  for (const auto& p : vertex->properties) {
    doubles = doubles || ((p.name == "x" || p.name == "y" || p.name == "z") &&
                          (p.type == "double" || p.type == "float64"));
  }
  std::vector<std::string> warnings;
  if (doubles) {
    warnings.push_back(
        fmt::format("{}: binary PLY with double coordinates is read through assimp, which "
                    "rounds them to float32 (6e-8 relative; mass properties to about 1e-7); "
                    "for full precision write the file as ASCII PLY",
                    path.string()));
  }
  return load_with_assimp(path, options, "binary PLY",
                          doubles ? "float32 (assimp rounds the file's doubles)"
                                  : "float32, as the file declares",
                          std::move(warnings));
}

}  // namespace

LoadedMesh load_mesh(const std::filesystem::path& path, const MeshLoadOptions& options) {
  if (!std::isfinite(options.scale) || !(options.scale > 0.0)) {
    throw InvalidArgument(
        fmt::format("{}: mesh scale {} is invalid: give a positive factor (e.g. 0.001 for millimetres)",
                    path.string(), options.scale));
  }
  require_readable_file(path);
  std::error_code ec;
  const std::uint64_t size = std::filesystem::file_size(path, ec);
  if (ec) throw FileError(fmt::format("{}: cannot read the file size: {}", path.string(), ec.message()));

  const std::string ext = lower_extension(path);
  if (ext == ".obj" || ext == ".off") {
    std::string bytes = read_bytes(path, size);
    refuse_wide_text(path, bytes);
    const mesh_text::Text text(path, std::move(bytes), options.scale);
    return ext == ".obj" ? finish(path, mesh_text::read_obj(text), options, "OBJ (text)", kTextPrecision)
                         : finish(path, mesh_text::read_off(text), options, "OFF (text)", kTextPrecision);
  }
  if (ext == ".stl") return load_stl(path, size, options);
  if (ext == ".ply") return load_ply(path, size, options);
  const bool float32_format = ext == ".gltf" || ext == ".glb";  // float32 by the format's definition
  std::vector<std::string> warnings;
  if (!float32_format) {
    warnings.push_back(
        fmt::format("{}: read through assimp, which rounds coordinates to float32: if the file "
                    "holds more digits, mass properties may be off by about 1e-7 relative "
                    "(OBJ, OFF, PLY and STL text are read exactly)",
                    path.string()));
  }
  return load_with_assimp(path, options, ext.empty() ? "mesh" : ext.substr(1),
                          float32_format ? "float32, the format's own" : "float32 (assimp's)",
                          std::move(warnings));
}

}  // namespace tumble
