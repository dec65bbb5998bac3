#pragma once
// Reading triangle meshes from files (STL binary/ASCII, OBJ, PLY and the rest assimp reads).
#include <filesystem>

#include "tumble/mass/triangle_mesh.hpp"

namespace tumble {

struct MeshLoadOptions {
  double scale = 1.0;  ///< multiplies every coordinate (0.001 for a CAD file in millimetres)
};

/// Reads every mesh in the file into one triangle mesh with node transforms applied and vertices at
/// identical positions welded (STL stores each triangle's corners separately). Throws FileError with
/// the path and the reason when the file is missing, unreadable, or holds no triangles.
TriangleMesh load_mesh(const std::filesystem::path& path, const MeshLoadOptions& options = {});

/// Writes a binary STL (for tests, benchmarks and examples). Throws FileError on failure.
void write_binary_stl(const TriangleMesh& mesh, const std::filesystem::path& path);

}  // namespace tumble
