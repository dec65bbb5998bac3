#pragma once
// What a link's geometry weighs: each geometry's unit-density mass properties posed in the link
// (primitives in closed form, meshes exactly, each mesh file read once), summed, then scaled to the
// link's mass; and the points of its surface for the COM test. Mesh URIs are resolved here.
#include <array>
#include <filesystem>
#include <functional>
#include <map>
#include <mutex>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "tumble/mass/triangle_mesh.hpp"
#include "tumble/robot/audit.hpp"

namespace tumble::robot {

/// The file a geometry's mesh URI names: a path the reader resolved, file://, a path relative to the
/// model's directory, or package://PKG/... and model://PKG/... through the package paths (audit.hpp).
/// Empty, with the reason in `why`, when none exists.
std::filesystem::path resolve_mesh(const Geometry& geometry, const std::filesystem::path& model_dir,
                                   const std::vector<std::filesystem::path>& package_paths, std::string& why);

/// A mesh file as a solid of unit density, in its own coordinates scaled per axis.
struct MeshSolid {
  TriangleMesh mesh;               ///< scaled
  MassProperties unit;             ///< mass = volume (density 1)
  std::vector<std::string> notes;  ///< the reader's and integrator's warnings
};

/// Calls f(i) for i in [0, n) on `threads` threads (0: one per core), each index once.
void for_each_index(std::size_t n, unsigned threads, const std::function<void(std::size_t)>& f);

/// Each mesh file read and integrated once, whatever number of links use it (keyed by file and scale).
/// get() may be called from several threads.
class MeshLibrary {
 public:
  using Entry = std::pair<std::optional<MeshSolid>, std::string>;
  /// The solid, or the reason it is none (unreadable, open, non-manifold: the mesh's own report).
  const Entry& get(const std::filesystem::path& file, const Vec3& scale);
  /// Reads and integrates these meshes on `threads` threads (0: one per core), so that get() finds them:
  /// a robot's meshes are independent files, and reading them is most of an audit.
  void preload(const std::vector<std::pair<std::filesystem::path, Vec3>>& meshes, unsigned threads = 0);

 private:
  using Key = std::pair<std::string, std::array<double, 3>>;
  static Key key_of(const std::filesystem::path& file, const Vec3& scale);
  static Entry load(const std::filesystem::path& file, const Vec3& scale);
  std::map<Key, Entry> solids_;
  std::mutex lock_;
};

/// A link's geometry as solids in the link's frame: for the test of whether a point is inside it.
struct LinkSolids {
  struct Solid {
    std::optional<Shape> shape;          ///< a primitive ...
    const TriangleMesh* mesh = nullptr;  ///< ... or a mesh (MeshLibrary's, in its own frame)
    Pose pose;
  };
  std::vector<Solid> solids;
  std::vector<Vec3> points;  ///< every vertex in the link's frame (primitives tessellated)
  std::vector<std::string> notes;
  bool from_meshes = false;
  /// Whether x (link frame) is inside any of the solids, or within `tolerance` of a primitive.
  bool contains(const Vec3& x, double tolerance) const;
};

/// Whether x (in the shape's own frame, shapes.hpp) is in the solid shape, or within `tolerance` of it.
bool contains(const Shape& shape, const Vec3& x, double tolerance);
/// The distance from x to the convex hull of `points` (0 inside it).
double distance_to_hull(const std::vector<Vec3>& points, const Vec3& x);

}  // namespace tumble::robot
