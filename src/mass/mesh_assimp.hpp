#pragma once
// Reading a mesh through assimp, in a child process (child_process.hpp): assimp crashes, aborts and
// loops forever on malformed files (docs/ARCHITECTURE.md has the fuzzing counts), so it never runs in
// tumble's own process. The child parses, then sends the meshes back over a pipe; the parent checks
// every count against the bytes received, every index against its mesh, every coordinate for being
// finite, before anything is used.
#include <cstdint>
#include <filesystem>
#include <string_view>

#include "mesh_text.hpp"

namespace tumble::mesh_assimp {

/// The meshes of the file, each with triangles a part (named by assimp, else "mesh K"), coordinates
/// multiplied by `scale`. From `memory` (the file's bytes, already read and checked) with the format
/// `hint` (the extension without its dot) when `memory` is not empty, else from `path` (formats that
/// refer to other files: glTF's buffers). `file_bytes` sets the limits (loader_timeout_seconds,
/// loader_memory_bytes). Throws FileError when assimp fails, crashes, times out or runs out of memory,
/// when a coordinate is not finite, or when no mesh has triangles.
mesh_text::RawMesh read(const std::filesystem::path& path, double scale, std::string_view memory,
                        const char* hint, std::uint64_t file_bytes);

}  // namespace tumble::mesh_assimp
