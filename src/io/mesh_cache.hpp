#pragma once
// Meshes read once per process: an ensemble reads its scene again for every run (each with its own
// draws), and a Python session may load a scene many times, but a mesh file only needs reading once.
// Keyed by the file's path, size, modification time and the load options, so a file that changed is
// read again. Private to tumble_io.
#include "tumble/mass/mesh_io.hpp"

namespace tumble::scene {

/// load_mesh(path, options), from the cache when the same file (path, size, mtime) was read with the
/// same options before. Thread-safe. Keeps the 16 most recent meshes.
LoadedMesh load_mesh_cached(const std::filesystem::path& path, const MeshLoadOptions& options);

}  // namespace tumble::scene
