#pragma once
// Reading triangle meshes from files. The text formats (OBJ, OFF, ASCII PLY, ASCII STL) are read by
// tumble itself, every coordinate to the double nearest its decimal text, and so is binary PLY, every
// value as the file stores it (a double stays a double), and binary STL, its float32 corners exactly;
// the other formats assimp knows go through assimp, which keeps float32 coordinates. Only regular files
// within the input limit are read (input_file.hpp: TUMBLE_MAX_INPUT_BYTES).
//
// assimp runs in a child process (fuzzing made it segfault, abort and loop forever on mutated DAE, X,
// GLB and 3MF files): its crash, endless loop or runaway allocation becomes a FileError naming the
// file, and tumble goes on. The child gets loader_timeout_seconds() of wall time and
// loader_memory_bytes() of address space; the environment variables below change them.
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "tumble/mass/triangle_mesh.hpp"

namespace tumble {

/// Seconds the assimp child process may take: a decimal number > 0, e.g. TUMBLE_LOADER_TIMEOUT_S=600.
constexpr const char* kLoaderTimeoutVariable = "TUMBLE_LOADER_TIMEOUT_S";
/// Address space the assimp child process may allocate: bytes, optionally followed by k, M, G or T
/// (powers of 1024), e.g. TUMBLE_LOADER_MEMORY_BYTES=64G.
constexpr const char* kLoaderMemoryVariable = "TUMBLE_LOADER_MEMORY_BYTES";

/// The assimp child's time limit for a file of `file_bytes`: TUMBLE_LOADER_TIMEOUT_S if set, else 30 s
/// plus 1 s per MiB (rounded up; assimp parses binary formats at about 250 MiB/s, Collada text at about
/// 20). Throws InvalidArgument when the variable is not a positive number of seconds.
double loader_timeout_seconds(std::uint64_t file_bytes);

/// The assimp child's memory limit for a file of `file_bytes` (address space beyond what it inherits):
/// TUMBLE_LOADER_MEMORY_BYTES if set, else 32 times the file's size, at least 2 GiB. Throws
/// InvalidArgument when the variable is not a byte count.
std::uint64_t loader_memory_bytes(std::uint64_t file_bytes);

struct MeshLoadOptions {
  double scale = 1.0;    ///< multiplies every coordinate (0.001 for a CAD file in millimetres)
  std::size_t part = 0;  ///< 0: every part of the file, merged; k ≥ 1: only the k-th (file order)
};

/// A mesh as read from a file, and what the user should know about the reading.
struct LoadedMesh {
  TriangleMesh mesh;                  ///< welded; only the vertices the triangles use
  std::size_t parts = 1;              ///< parts in the file (OBJ objects or groups, STL solids, meshes)
  std::string format;                 ///< e.g. "OBJ (text)", "binary STL"
  std::string precision;              ///< what the coordinates carry, e.g. "float32 (the format's own)"
  std::vector<std::string> warnings;  ///< one line each, for the user (several parts merged, ...)
  /// Files other than the mesh that its loader read (a glTF's .bin buffers, all beside or below the
  /// mesh): a run stamps them with the mesh, so that resuming after one changed is refused.
  std::vector<std::filesystem::path> companions;
};

/// Reads a mesh file into one triangle mesh, vertices at identical positions welded (STL stores each
/// triangle's corners separately), polygons fanned into triangles. A file of several parts is merged
/// with a warning that counts them, unless options.part picks one. Throws FileError with the path (and
/// line:column in a text file, element and byte offset in binary PLY) and the reason when the file is
/// missing, not a regular file, larger than the input limit, unreadable, malformed, truncated, UTF-16,
/// a point cloud or empty, or when assimp crashed, timed out or ran out of memory on it (one line,
/// with the signal and how to raise a limit); InvalidArgument for a bad scale, a part that does not
/// exist, or a limit variable that is not a number.
[[nodiscard]] LoadedMesh load_mesh(const std::filesystem::path& path, const MeshLoadOptions& options = {});

/// The formats tumble reads itself (OBJ, OFF, ASCII PLY, binary PLY, ASCII and binary STL), from a
/// file's bytes already in memory: what
/// load_mesh does after reading such a file. `name` picks the format by its extension (case-insensitive)
/// and names the file in messages; it is not opened. Throws as load_mesh does, and InvalidArgument for
/// another extension. The fuzz targets (fuzz/) call it.
[[nodiscard]] LoadedMesh load_mesh_bytes(const std::filesystem::path& name, std::string bytes,
                                         const MeshLoadOptions& options = {});

/// Writes a binary STL (for tests, benchmarks and examples). Throws FileError on failure.
void write_binary_stl(const TriangleMesh& mesh, const std::filesystem::path& path);

}  // namespace tumble
