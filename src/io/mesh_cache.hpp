#pragma once
// Meshes read once per process: an ensemble reads its scene again for every run (each with its own
// draws), and a Python session may load a scene many times, but a mesh file only needs reading once.
// Keyed by the file's identity (device and inode), size, modification time and the load options, so a
// file that changed is read again. Private to tumble_io.
#include <memory>

#include "tumble/mass/mesh_io.hpp"

namespace tumble::scene {

/// load_mesh(path, options), from the cache when the same file (the same size and mtime) was read with
/// the same options before: one stat() per call, no copy. Thread-safe. Keeps the 16 most recent meshes.
std::shared_ptr<const LoadedMesh> load_mesh_cached(const std::filesystem::path& path,
                                                   const MeshLoadOptions& options);

}  // namespace tumble::scene
