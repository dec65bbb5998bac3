// Loading mesh files. OBJ, OFF, PLY (ASCII and binary) and ASCII STL are read by tumble's own readers
// (mesh_read_*.cpp: every decimal digit kept, every binary value as stored, every count checked against
// the file's size; binary STL, a fixed record, once its size is checked); every other format goes through assimp
// (every mesh of the scene, node transforms applied, polygons triangulated), in a child process that
// may crash, hang or run out of memory without taking tumble along (mesh_assimp.hpp). Either way the file must
// be a regular file within the input limit (input_file.hpp), parts are counted (and one may be
// picked), and vertices are welded by tumble (mesh_weld.cpp says why not by assimp).
#include "tumble/mass/mesh_io.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <system_error>

#include "mesh_assimp.hpp"
#include "mesh_text.hpp"
#include "tumble/error.hpp"
#include "tumble/mass/input_file.hpp"
#include "tumble/mass/mesh_weld.hpp"

namespace tumble {
namespace {

using mesh_text::RawMesh;

constexpr const char* kTextPrecision = "every digit of the text (each coordinate is the double nearest it)";

std::string lower_extension(const std::filesystem::path& path) {
  std::string ext = path.extension().string();
  for (char& c : ext) c = static_cast<char>(c >= 'A' && c <= 'Z' ? c - 'A' + 'a' : c);
  return ext;
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
  for (std::size_t i = 0; i < shown; ++i) {
    out += fmt::format("{}'{}'", i ? ", " : "", mesh_text::excerpt(names[i]));
  }
  return fmt::format(" ({}{})", out, names.size() > shown ? ", ..." : "");
}

/// "1 mesh", "2 meshes", "3 objects".
std::string counted(std::size_t n, const std::string& word) {
  const bool es = !word.empty() && (word.back() == 'h' || word.back() == 's');
  return fmt::format("{} {}{}", n, word, n == 1 ? "" : es ? "es" : "s");
}

/// Checks the part choice and, when several parts are merged, says so.
void note_parts(const std::filesystem::path& path, const std::vector<std::string>& names,
                const std::string& word, std::size_t part, LoadedMesh& out) {
  out.parts = names.size();
  if (part > names.size()) {
    throw InvalidArgument(fmt::format("{}: part {} does not exist: the file has {}{}; give 1 to {}",
                                      path.string(), part, counted(names.size(), word), listed_names(names),
                                      names.size()));
  }
  if (part == 0 && names.size() > 1) {
    out.warnings.push_back(
        fmt::format("{} holds {}{}; they were merged into one body (to take one "
                    "alone: tumble inertia --part K, K = 1 to {})",
                    path.string(), counted(names.size(), word), listed_names(names), names.size()));
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

/// Whether every vertex of `raw` is a corner of some triangle.
bool every_vertex_used(const RawMesh& raw) {
  if (raw.every_vertex_used) return true;
  std::vector<bool> used(raw.vertices.size(), false);
  std::size_t count = 0;
  for (const auto& t : raw.triangles) {
    for (const std::uint32_t v : t) {
      if (v < used.size() && !used[v]) {
        used[v] = true;
        ++count;
      }
    }
  }
  return count == raw.vertices.size();
}

/// Part selection, dropping unused vertices, welding.
LoadedMesh finish(const std::filesystem::path& path, RawMesh raw, const MeshLoadOptions& options,
                  std::string format, std::string precision) {
  if (raw.triangles.empty()) throw_no_faces(path, raw.vertices.size(), raw.ignored_elements);
  LoadedMesh out;
  out.format = std::move(format);
  out.precision = std::move(precision);
  out.warnings = std::move(raw.warnings);
  out.companions = std::move(raw.companions);
  note_parts(path, raw.part_names, raw.part_word, options.part, out);

  // The triangles of the chosen part(s), with only the vertices they use, in the file's order: the raw
  // mesh itself when that is all of it (a binary STL's corners, every one used), without a copy.
  if (options.part == 0 && every_vertex_used(raw)) {
    TriangleMesh all{std::move(raw.vertices), std::move(raw.triangles)};
    out.mesh = raw.welded ? std::move(all) : weld_identical_vertices(all);
    return out;
  }
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

/// Reads the file through assimp, in a child process (mesh_assimp.hpp): from `memory` (the file's
/// bytes, already checked) when given, else from the path (glTF, whose buffers may be other files).
LoadedMesh load_with_assimp(const std::filesystem::path& path, const MeshLoadOptions& options,
                            std::string format, std::string precision, std::vector<std::string> warnings,
                            std::uint64_t file_bytes, std::string_view memory = {}, const char* hint = "") {
  RawMesh raw = mesh_assimp::read(path, options.scale, memory, hint, file_bytes);
  raw.warnings = std::move(warnings);
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

/// What is wrong with a file that is neither an ASCII STL nor a binary STL of the right size.
std::string binary_stl_size_problem(std::uint64_t size, std::uint64_t declared) {
  if (size == 0) return "the file is empty (0 bytes)";
  if (size < 84) {
    return fmt::format(
        "not an STL file: too short for a binary STL ({} bytes; its header alone is 84) and "
        "not ASCII STL (which starts with 'solid')",
        size);
  }
  const std::uint64_t need = 84 + 50 * declared;  // declared < 2^32: no overflow
  const std::uint64_t allowed = (size - 84) / 50;
  if (size < need) {
    return fmt::format(
        "truncated binary STL: the header says {} triangles (84 + 50 x {} = {} bytes), the "
        "file size ({} bytes) allows {}",
        declared, declared, need, size, allowed);
  }
  return fmt::format(
      "binary STL of the wrong size: the header says {} triangles (84 + 50 x {} = {} bytes) "
      "but the file has {} bytes, {} more (room for {} triangles): the count is wrong or "
      "data was appended",
      declared, declared, need, size, size - need, allowed);
}

LoadedMesh load_stl(const std::filesystem::path& path, std::string bytes, const MeshLoadOptions& options) {
  const std::uint64_t size = bytes.size();
  std::uint64_t declared = 0;  // the triangle count a binary STL's header gives
  if (size >= 84) {
    for (int i = 3; i >= 0; --i) declared = (declared << 8) | static_cast<unsigned char>(bytes[80 + i]);
  }
  // A binary STL is exactly 84 + 50·n bytes; its 80-byte header may well start with "solid".
  if (size == 84 && declared == 0) {
    throw FileError(
        fmt::format("{}: a binary STL of 0 triangles (its 84-byte header only): no surface", path.string()));
  }
  if (size >= 84 && 84 + 50 * declared == size) {
    return finish(path, mesh_text::read_binary_stl(path, bytes, declared, options.scale), options,
                  "binary STL", "float32, the format's own");
  }
  refuse_wide_text(path, bytes);
  if (!starts_with_solid(bytes)) {
    throw FileError(fmt::format("{}: {}", path.string(), binary_stl_size_problem(size, declared)));
  }
  const bool looks_binary = std::string_view(bytes).substr(0, 4096).find('\0') != std::string_view::npos;
  const mesh_text::Text text(path, std::move(bytes), options.scale);
  try {
    return finish(path, mesh_text::read_ascii_stl(text), options, "ASCII STL", kTextPrecision);
  } catch (const FileError& e) {
    if (!looks_binary) throw;
    throw FileError(fmt::format("{}; the file looks binary (a binary STL may start with 'solid' too): {}",
                                e.what(), binary_stl_size_problem(size, declared)));
  }
}

/// What the coordinates of a binary PLY carry, from the types of x, y, z.
std::string binary_ply_precision(const mesh_text::PlyElement& vertex) {
  bool any_float = false, all_double = true;
  for (const auto& p : vertex.properties) {
    if (p.name != "x" && p.name != "y" && p.name != "z") continue;
    const bool is_double = p.type == "double" || p.type == "float64";
    any_float = any_float || p.type == "float" || p.type == "float32";
    all_double = all_double && is_double;
  }
  if (all_double) return "float64, every bit of the file's doubles";
  if (any_float) return "float32, as the file declares";
  return "integers, exact";
}

LoadedMesh load_ply(const std::filesystem::path& path, std::string bytes, const MeshLoadOptions& options) {
  refuse_wide_text(path, bytes);
  const mesh_text::Text text(path, std::move(bytes), options.scale);
  // The header is text even in a binary PLY; its counts are checked against the file's size.
  const mesh_text::PlyHeader header = mesh_text::read_ply_header(text, text.view().size());
  const mesh_text::PlyElement* vertex = header.find("vertex");
  const mesh_text::PlyElement* face = header.find("face");
  if (face == nullptr || face->count == 0) throw_no_faces(path, vertex->count, 0);
  if (header.format == mesh_text::PlyHeader::Format::ascii) {
    return finish(path, mesh_text::read_ascii_ply(text, header), options, "ASCII PLY", kTextPrecision);
  }
  const bool big = header.format == mesh_text::PlyHeader::Format::binary_big_endian;
  return finish(path, mesh_text::read_binary_ply(text, header), options,
                big ? "binary PLY (big-endian)" : "binary PLY (little-endian)",
                binary_ply_precision(*vertex));
}

void check_scale(const std::filesystem::path& path, const MeshLoadOptions& options) {
  if (!std::isfinite(options.scale) || !(options.scale > 0.0)) {
    throw InvalidArgument(
        fmt::format("{}: mesh scale {} is invalid: give a positive factor (e.g. 0.001 for millimetres)",
                    path.string(), options.scale));
  }
}

bool read_by_tumble(const std::string& ext) {
  return ext == ".obj" || ext == ".off" || ext == ".stl" || ext == ".ply";
}

}  // namespace

LoadedMesh load_mesh_bytes(const std::filesystem::path& path, std::string bytes,
                           const MeshLoadOptions& options) {
  check_scale(path, options);
  const std::string ext = lower_extension(path);
  if (ext == ".stl") return load_stl(path, std::move(bytes), options);
  if (ext == ".ply") return load_ply(path, std::move(bytes), options);
  if (ext != ".obj" && ext != ".off") {
    throw InvalidArgument(
        fmt::format("{}: reading from memory takes .obj, .off, .ply or .stl, not '{}'", path.string(), ext));
  }
  refuse_wide_text(path, bytes);
  const mesh_text::Text text(path, std::move(bytes), options.scale);
  return ext == ".obj" ? finish(path, mesh_text::read_obj(text), options, "OBJ (text)", kTextPrecision)
                       : finish(path, mesh_text::read_off(text), options, "OFF (text)", kTextPrecision);
}

LoadedMesh load_mesh(const std::filesystem::path& path, const MeshLoadOptions& options) {
  check_scale(path, options);
  const std::string ext = lower_extension(path);
  if (read_by_tumble(ext)) {
    // Read whole, once: a regular file within the input limit (input_file.hpp).
    return load_mesh_bytes(path, read_input_file(path, "mesh file"), options);
  }
  // assimp parses the bytes tumble read (a regular file within the limit), except glTF's text form,
  // whose buffers may be other files: assimp opens it, and them, itself.
  std::string bytes;
  std::uint64_t size = 0;
  if (ext == ".gltf") {
    size = checked_input_size(path, "mesh file");
  } else {
    bytes = read_input_file(path, "mesh file");
    size = bytes.size();
  }
  if (size == 0) {
    throw FileError(fmt::format(
        "{}: the file is empty (0 bytes); export the surface as triangles or polygons", path.string()));
  }
  const bool float32_format = ext == ".gltf" || ext == ".glb";  // float32 by the format's definition
  std::vector<std::string> warnings;
  if (!float32_format) {
    warnings.push_back(
        fmt::format("{}: read through assimp, which rounds coordinates to float32: if the file "
                    "holds more digits, mass properties may be off by about 1e-7 relative "
                    "(OBJ, OFF, PLY and ASCII STL are read exactly)",
                    path.string()));
  }
  const std::string hint = ext.empty() ? "" : ext.substr(1);
  return load_with_assimp(path, options, ext.empty() ? "mesh" : ext.substr(1),
                          float32_format ? "float32, the format's own" : "float32 (assimp's)",
                          std::move(warnings), size, bytes, hint.c_str());
}

}  // namespace tumble
