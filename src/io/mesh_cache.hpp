#pragma once
// Meshes read once per process: an ensemble reads its scene again for every run (each with its own
// draws), and a Python session may load a scene many times, but a mesh file only needs reading once —
// and its checks, unit-density integrals and display mesh computing once. Keyed by the file's identity
// (device and inode), size, modification time and the load options, so a file that changed is read
// again. Private to tumble_io.
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <utility>

#include "tumble/mass/mesh_io.hpp"
#include "tumble/mass/mesh_mass.hpp"

namespace tumble::scene {

/// A mesh file as read, and what is computed from the mesh alone, on first use. Thread-safe.
class CachedMesh {
 public:
  explicit CachedMesh(LoadedMesh loaded) : loaded_(std::move(loaded)) {
    Eigen::AlignedBox3d box;
    for (const Vec3& v : loaded_.mesh.vertices) box.extend(v);
    diagonal_ = loaded_.mesh.vertices.empty() ? 0.0 : box.diagonal().norm();
  }
  const LoadedMesh& loaded() const { return loaded_; }
  const TriangleMesh& mesh() const { return loaded_.mesh; }
  /// The diagonal of the mesh's bounding box (m).
  double diagonal() const { return diagonal_; }
  /// solid_unit_properties(mesh(), name): its checks and integrals once (per name, which its messages
  /// carry); throws as it does.
  MeshMassResult unit_solid(const std::string& name) const;
  /// decimate(mesh(), kDisplayTriangles), once; every body of this mesh shares it.
  std::shared_ptr<const TriangleMesh> display() const;

 private:
  LoadedMesh loaded_;
  double diagonal_ = 0.0;
  mutable std::mutex lock_;
  mutable std::optional<std::pair<std::string, MeshMassResult>> unit_;
  mutable std::once_flag display_once_;
  mutable std::shared_ptr<const TriangleMesh> display_;
};

/// load_mesh(path, options), from the cache when the same file (the same size and mtime) was read with
/// the same options before: one stat() per call, no copy. Thread-safe. Keeps the 16 most recent meshes.
std::shared_ptr<const CachedMesh> load_mesh_cached(const std::filesystem::path& path,
                                                   const MeshLoadOptions& options);

}  // namespace tumble::scene
