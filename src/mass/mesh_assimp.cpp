// assimp in a child process (mesh_assimp.hpp). The answer on the pipe, all integers little-endian
// (host order: the child is a fork of this process):
//   u32 kMagic, u8 status
//   status 1 (an error tumble words itself): u32 length, the message
//   status 0: u32 parts, then per part (an assimp mesh with triangles, in file order):
//             u32 name length, name, u32 vertices, 3 float32 per vertex (as assimp holds them),
//             u32 triangles, 3 u32 per triangle (indices into the part's vertices)
//           then u32 files, per file the path of another file the loader opened (u32 length, the
//           path; a glTF's buffers), then u32 kEnd.
// The parent trusts nothing in it: a count is used only after the bytes it needs are known to be
// there, indices are checked against their part, coordinates for being finite after scaling.
#include "mesh_assimp.hpp"

#include <algorithm>
#include <array>
#include <assimp/DefaultIOSystem.h>
#include <assimp/Importer.hpp>
#include <assimp/MemoryIOWrapper.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <charconv>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fmt/format.h>
#include <string>
#include <vector>

#include "child_process.hpp"
#include "tumble/error.hpp"
#include "tumble/mass/input_file.hpp"
#include "tumble/mass/mesh_io.hpp"

namespace tumble {

double loader_timeout_seconds(std::uint64_t file_bytes) {
  const char* text = std::getenv(kLoaderTimeoutVariable);
  if (text == nullptr || *text == '\0') {
    return 30.0 + static_cast<double>((file_bytes + (std::uint64_t{1} << 20) - 1) >> 20);
  }
  const std::string_view s(text);
  double value = 0.0;
  const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), value);
  if (ec != std::errc{} || end != s.data() + s.size() || !std::isfinite(value) || !(value > 0.0)) {
    throw InvalidArgument(
        fmt::format("{}='{}' is not a time limit: give a positive number of seconds, e.g. {}=600",
                    kLoaderTimeoutVariable, s.substr(0, 40), kLoaderTimeoutVariable));
  }
  return value;
}

std::uint64_t loader_memory_bytes(std::uint64_t file_bytes) {
  constexpr std::uint64_t kFloor = std::uint64_t{2} << 30;
  const std::uint64_t multiple = file_bytes > (~std::uint64_t{0} >> 5) ? ~std::uint64_t{0} : file_bytes * 32;
  return byte_count_from_environment(kLoaderMemoryVariable, std::max(kFloor, multiple));
}

namespace mesh_assimp {
namespace {

using mesh_text::RawMesh;

constexpr std::uint32_t kMagic = 0x54554d42;  // "BMUT"
constexpr std::uint32_t kEnd = 0x444e4521;    // "!END"
constexpr std::size_t kMaxMessage = 2000;     // bytes of an error message taken from the child

static_assert(sizeof(aiVector3D) == 12, "assimp built with float coordinates (ai_real = float)");

// ---- in the child ----

/// Buffers the small fields (one write, one wake-up of the parent, for a small mesh).
struct Writer {
  explicit Writer(int descriptor) : fd(descriptor) {}
  int fd;
  std::string buffer;
  void bytes(const void* p, std::size_t n) {
    if (buffer.size() + n > kBuffer) flush();
    if (n >= kBuffer) {
      child_process::write_all(fd, p, n);
    } else {
      buffer.append(static_cast<const char*>(p), n);
    }
  }
  void u32(std::uint32_t v) { bytes(&v, 4); }
  void u8(std::uint8_t v) { bytes(&v, 1); }
  void text(std::string_view s) {
    u32(static_cast<std::uint32_t>(s.size()));
    bytes(s.data(), s.size());
  }
  void flush() {
    child_process::write_all(fd, buffer.data(), buffer.size());
    buffer.clear();
  }
  static constexpr std::size_t kBuffer = 1 << 16;
};

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

/// Whether `resolved` (symbolic links and ".." resolved) is `directory` or below it.
bool inside(const std::filesystem::path& directory, const std::filesystem::path& resolved) {
  const auto [d, r] = std::mismatch(directory.begin(), directory.end(), resolved.begin(), resolved.end());
  return d == directory.end();
}

/// Whether `file`, as the child resolved it, is below the directory of `mesh` (resolved the same way).
bool inside_directory_of(const std::filesystem::path& mesh, const std::filesystem::path& file) {
  std::error_code ec;
  const auto directory = std::filesystem::weakly_canonical(std::filesystem::absolute(mesh).parent_path(), ec);
  return !ec && file.is_absolute() && file == file.lexically_normal() && inside(directory, file);
}

/// The files a mesh may make assimp open besides itself: those in its own directory or below it. A
/// received glTF whose buffer is "../secret.txt" or the absolute path of a private key would otherwise
/// have that file read as vertices, and the vertices end up in reports and run files made to be shared
/// (and the same holds for any format with external files: Collada images, a .glb's external buffer
/// read from memory). Paths are compared once symbolic links and ".." are resolved; a refused name is
/// kept for the message, and nothing is ever written, created or deleted.
class ConfinedIOSystem final : public Assimp::DefaultIOSystem {
 public:
  explicit ConfinedIOSystem(const std::filesystem::path& mesh)
      : mesh_(std::filesystem::absolute(mesh)),
        directory_(std::filesystem::weakly_canonical(mesh_.parent_path())) {}

  bool Exists(const char* file) const override {
    const std::string p = resolve(file);
    return !p.empty() && DefaultIOSystem::Exists(p.c_str());
  }
  Assimp::IOStream* Open(const char* file, const char* mode) override {
    if (std::string_view(mode).find_first_of("wa+") != std::string_view::npos) return nullptr;
    const std::string p = resolve(file);
    if (p.empty()) return nullptr;
    Assimp::IOStream* stream = DefaultIOSystem::Open(p.c_str(), mode);
    if (stream != nullptr && std::filesystem::path(file) != mesh_ &&
        std::find(opened_.begin(), opened_.end(), p) == opened_.end()) {
      opened_.push_back(p);
    }
    return stream;
  }
  bool CreateDirectory(const std::string&) override { return false; }
  bool ChangeDirectory(const std::string&) override { return false; }
  bool DeleteFile(const std::string&) override { return false; }

  /// The first name refused, empty if none.
  const std::string& refused() const { return refused_; }
  /// The files opened other than the mesh itself, resolved, each once, in the order first opened.
  const std::vector<std::string>& opened() const { return opened_; }
  const std::filesystem::path& directory() const { return directory_; }

 private:
  /// The path to open for `file`, empty if it is outside the directory. A relative name is the mesh's
  /// own (a buffer named in a .glb, read from memory without a directory): beside the mesh.
  std::string resolve(const char* file) const {
    std::filesystem::path p(file);
    if (p == mesh_) return p.string();  // the mesh itself, wherever a symbolic link to it leads
    if (p.is_relative()) p = directory_ / p;
    std::error_code ec;
    const std::filesystem::path resolved = std::filesystem::weakly_canonical(p, ec);
    if (!ec && inside(directory_, resolved)) return resolved.string();  // opened as checked
    if (refused_.empty()) refused_ = file;
    return {};
  }

  std::filesystem::path mesh_;       // absolute, as given
  std::filesystem::path directory_;  // the mesh's, symbolic links and ".." resolved
  mutable std::string refused_;
  std::vector<std::string> opened_;
};

/// The child's work: parse, check, send.
void parse_and_send(int fd, const std::filesystem::path& path, double scale, std::string_view memory,
                    const char* hint) {
  Writer out{fd};
  out.u32(kMagic);
  try {
    // Never destroyed: the child ends with _exit, and freeing a scene that a parser left inconsistent
    // could crash after the answer is sent.
    Assimp::Importer& importer = *new Assimp::Importer;
    auto* files = new ConfinedIOSystem(path);  // the importer owns it
    importer.SetIOHandler(files);
    // Points and lines carry no surface: SortByPType splits them off and this drops them.
    importer.SetPropertyInteger(AI_CONFIG_PP_SBP_REMOVE, aiPrimitiveType_POINT | aiPrimitiveType_LINE);
    // Mass properties are in the file's own axes: a Collada file's <up_axis>Z_UP</up_axis> (robot meshes
    // say so) must not turn it into assimp's y-up. Its <unit> still scales it to metres.
    importer.SetPropertyBool(AI_CONFIG_IMPORT_COLLADA_IGNORE_UP_DIRECTION, true);
    const unsigned flags = aiProcess_Triangulate | aiProcess_PreTransformVertices | aiProcess_SortByPType;
    const aiScene* scene =
        memory.empty() ? importer.ReadFile(std::filesystem::absolute(path).string(), flags)  // as mesh_
                       : importer.ReadFileFromMemory(memory.data(), memory.size(), flags, hint);
    if (!files->refused().empty()) {
      throw FileError(fmt::format(
          "{}: the mesh refers to the file {}, outside its directory {}: tumble reads only the files "
          "beside a mesh or below its directory; copy that file there and name it relative to the mesh",
          path.string(), files->refused(), files->directory().string()));
    }
    if (scene == nullptr) {
      // A parser that met a failed allocation may say anything (or "std::bad_alloc").
      if (child_process::near_memory_limit()) child_process::exit_out_of_memory();
      // From memory, assimp calls the file "$$$___magic___$$$.<hint>": say its name.
      std::string error = importer.GetErrorString();
      const std::string magic = fmt::format("{}.{}", AI_MEMORYIO_MAGIC_FILENAME, hint);
      for (std::size_t at; !memory.empty() && (at = error.find(magic)) != std::string::npos;) {
        error.replace(at, magic.size(), path.filename().string());
      }
      throw FileError(fmt::format("{}: cannot read the mesh: {}", path.string(), error));
    }
    // Each assimp mesh with triangles is a part (assimp makes one per object and material).
    struct Part {
      const aiMesh* mesh;
      std::string name;
      std::vector<std::array<std::uint32_t, 3>> triangles;
    };
    std::vector<Part> parts;
    for (unsigned m = 0; m < scene->mNumMeshes; ++m) {
      const aiMesh* mesh = scene->mMeshes[m];
      for (unsigned i = 0; i < mesh->mNumVertices; ++i) {
        const aiVector3D& p = mesh->mVertices[i];
        const Vec3 v = scale *
                       Vec3(static_cast<double>(p.x), static_cast<double>(p.y), static_cast<double>(p.z));
        if (!v.allFinite()) throw_non_finite(path, *mesh, m, i, scale);
      }
      Part part{mesh, mesh->mName.C_Str(), {}};
      for (unsigned f = 0; f < mesh->mNumFaces; ++f) {
        const aiFace& face = mesh->mFaces[f];
        if (face.mNumIndices != 3) continue;  // points and lines left over in a mixed mesh
        part.triangles.push_back({face.mIndices[0], face.mIndices[1], face.mIndices[2]});
      }
      if (part.triangles.empty()) continue;
      if (part.name.empty()) part.name = fmt::format("mesh {}", m);
      parts.push_back(std::move(part));
    }
    if (parts.empty()) {
      throw FileError(fmt::format(
          "{}: the file holds no triangles ({} meshes, only points or lines, or empty); export the "
          "surface as triangles or polygons",
          path.string(), scene->mNumMeshes));
    }
    out.u8(0);
    out.u32(static_cast<std::uint32_t>(parts.size()));
    for (const Part& part : parts) {
      out.text(part.name);
      out.u32(part.mesh->mNumVertices);
      out.bytes(part.mesh->mVertices, std::size_t{12} * part.mesh->mNumVertices);
      out.u32(static_cast<std::uint32_t>(part.triangles.size()));
      out.bytes(part.triangles.data(), std::size_t{12} * part.triangles.size());
    }
    out.u32(static_cast<std::uint32_t>(files->opened().size()));
    for (const std::string& f : files->opened()) out.text(f);
    out.u32(kEnd);
  } catch (const Error& e) {
    out.u8(1);
    out.text(std::string_view(e.what()).substr(0, kMaxMessage));
  }
  out.flush();
}

// ---- in the parent ----

/// Reads the answer, each value only after checking that its bytes are there.
class Reader {
 public:
  explicit Reader(std::string_view bytes) : rest_(bytes) {}

  std::uint32_t u32(const char* what) {
    std::uint32_t v;
    std::memcpy(&v, take(4, what).data(), 4);
    return v;
  }
  std::uint8_t u8(const char* what) { return static_cast<std::uint8_t>(take(1, what)[0]); }
  std::string_view take(std::uint64_t n, const char* what) {
    if (n > rest_.size()) {
      throw Inconsistent(fmt::format("{} needs {} bytes, {} are left", what, n, rest_.size()));
    }
    const std::string_view out = rest_.substr(0, n);
    rest_.remove_prefix(n);
    return out;
  }
  std::size_t left() const { return rest_.size(); }

  struct Inconsistent : std::runtime_error {
    using std::runtime_error::runtime_error;
  };

 private:
  std::string_view rest_;
};

[[noreturn]] void throw_bad_answer(const std::filesystem::path& path, const std::string& why) {
  throw FileError(fmt::format(
      "{}: the mesh loader (assimp) gave no usable answer ({}): the file is malformed or unsupported; "
      "convert it to OBJ, PLY or STL",
      path.string(), why));
}

/// The meshes in the child's answer, all checked.
RawMesh parse_answer(const std::filesystem::path& path, std::string_view answer, double scale) {
  RawMesh raw;
  raw.part_word = "mesh";
  try {
    Reader in(answer);
    if (in.u32("the header") != kMagic) throw Reader::Inconsistent("it does not start with tumble's mark");
    const std::uint8_t status = in.u8("the status");
    if (status == 1) {
      const std::uint32_t length = in.u32("the message length");
      const std::string_view message = in.take(std::min<std::uint64_t>(length, kMaxMessage), "the message");
      throw FileError(std::string(message));
    }
    if (status != 0) throw Reader::Inconsistent(fmt::format("status {}", status));
    const std::uint32_t parts = in.u32("the part count");
    for (std::uint32_t p = 0; p < parts; ++p) {
      const std::string_view name = in.take(in.u32("a part name's length"), "a part name");
      const std::uint32_t vertices = in.u32("a vertex count");
      const std::string_view coordinates = in.take(std::uint64_t{12} * vertices, "the vertices");
      const std::uint32_t triangles = in.u32("a triangle count");
      const std::string_view indices = in.take(std::uint64_t{12} * triangles, "the triangles");
      const std::uint64_t base = raw.vertices.size();
      if (base + vertices > std::uint64_t{0xffffffffu}) {
        throw FileError(
            fmt::format("{}: the file has more than {} vertices: more than tumble reads from one file",
                        path.string(), 0xffffffffu));
      }
      raw.vertices.reserve(base + vertices);
      for (std::uint32_t i = 0; i < vertices; ++i) {
        float xyz[3];
        std::memcpy(xyz, coordinates.data() + std::size_t{12} * i, 12);
        const Vec3 v = scale * Vec3(static_cast<double>(xyz[0]), static_cast<double>(xyz[1]),
                                    static_cast<double>(xyz[2]));
        if (!v.allFinite())
          throw Reader::Inconsistent(fmt::format("vertex {} of part {} is not finite", i, p));
        raw.vertices.push_back(v);
      }
      const auto part_index = static_cast<std::uint32_t>(raw.part_names.size());
      for (std::uint32_t t = 0; t < triangles; ++t) {
        std::array<std::uint32_t, 3> f;
        std::memcpy(f.data(), indices.data() + std::size_t{12} * t, 12);
        for (std::uint32_t& k : f) {
          if (k >= vertices) {
            throw Reader::Inconsistent(
                fmt::format("triangle {} of part {} uses vertex {} of {}", t, p, k, vertices));
          }
          k += static_cast<std::uint32_t>(base);
        }
        raw.triangles.push_back(f);
        raw.part_of.push_back(part_index);
      }
      if (triangles == 0) throw Reader::Inconsistent(fmt::format("part {} has no triangles", p));
      raw.part_names.emplace_back(name);
    }
    if (parts == 0) throw Reader::Inconsistent("no parts");
    // The other files it read: stamped by a run, so each must be one the child was allowed to open.
    const std::uint32_t files = in.u32("the file count");
    for (std::uint32_t f = 0; f < files; ++f) {
      const std::filesystem::path file(in.take(in.u32("a file name's length"), "a file name"));
      if (!inside_directory_of(path, file))
        throw Reader::Inconsistent(fmt::format("file {} is outside the mesh's directory", f));
      raw.companions.push_back(file);
    }
    if (in.u32("the end mark") != kEnd) throw Reader::Inconsistent("the end mark is wrong");
    if (in.left() != 0) throw Reader::Inconsistent(fmt::format("{} bytes after the end mark", in.left()));
  } catch (const Reader::Inconsistent& e) {
    throw_bad_answer(path, e.what());
  }
  return raw;
}

/// "2 GiB", "512 MiB", "4 KiB", "100 bytes".
std::string readable(std::uint64_t bytes) {
  const char* units[] = {"bytes", "KiB", "MiB", "GiB", "TiB", "PiB", "EiB"};
  double v = static_cast<double>(bytes);
  int u = 0;
  while (v >= 1024.0 && u < 6) v /= 1024.0, ++u;
  return fmt::format("{:.4g} {}", v, units[u]);
}

constexpr const char* kConvert = "convert it to OBJ, PLY or STL";

}  // namespace

RawMesh read(const std::filesystem::path& path, double scale, std::string_view memory, const char* hint,
             std::uint64_t file_bytes) {
  child_process::Limits limits;
  limits.timeout_seconds = loader_timeout_seconds(file_bytes);
  limits.memory_bytes = loader_memory_bytes(file_bytes);
  const child_process::Outcome outcome =
      child_process::run([&](int fd) { parse_and_send(fd, path, scale, memory, hint); }, limits);
  const std::string p = path.string();
  const std::string said = child_process::telling_line(outcome.diagnostics);
  const std::string quote = said.empty() ? "" : fmt::format(": {}", said);
  switch (outcome.end) {
    case child_process::End::finished:
    case child_process::End::unknown:
      return parse_answer(path, outcome.answer, scale);
    case child_process::End::crashed:
      throw FileError(
          fmt::format("{}: the mesh loader (assimp) crashed on this file ({}{}): the file is malformed or "
                      "unsupported; {}",
                      p,
                      outcome.signal != 0 ? fmt::format("signal {}, {}", outcome.signal,
                                                        child_process::signal_name(outcome.signal))
                                          : fmt::format("exit status {}", outcome.exit_status),
                      quote, kConvert));
    case child_process::End::interrupted:
      throw FileError(
          fmt::format("{}: the mesh loader (assimp) was stopped by signal {} ({}) before it finished", p,
                      outcome.signal, child_process::signal_name(outcome.signal)));
    case child_process::End::timed_out:
      throw FileError(fmt::format(
          "{}: the mesh loader (assimp) did not finish within {:g} s ({} raises the limit): the file is "
          "malformed (assimp loops forever on some) or very large; {}",
          p, limits.timeout_seconds, kLoaderTimeoutVariable, kConvert));
    case child_process::End::out_of_memory:
      throw FileError(fmt::format(
          "{}: the mesh loader (assimp) ran out of memory on this file (limit {}; {} raises it): the file is "
          "malformed or too large for assimp; {}",
          p, readable(limits.memory_bytes), kLoaderMemoryVariable, kConvert));
  }
  throw_bad_answer(path, "it ended in an unknown way");
}

}  // namespace mesh_assimp
}  // namespace tumble
