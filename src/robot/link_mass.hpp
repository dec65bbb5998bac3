#pragma once
// What a link's geometry weighs: each geometry's unit-density mass properties posed in the link
// (primitives in closed form, meshes exactly, each mesh file read once), summed, then scaled to the
// link's mass; and the points of its surface for the COM test. Mesh URIs are resolved here.
#include <array>
#include <filesystem>
#include <map>
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

/// Each mesh file read and integrated once, whatever number of links use it (keyed by file and scale).
class MeshLibrary {
 public:
  /// The solid, or the reason it is none (unreadable, open, non-manifold: the mesh's own report).
  const std::pair<std::optional<MeshSolid>, std::string>& get(const std::filesystem::path& file,
                                                              const Vec3& scale);

 private:
  std::map<std::pair<std::string, std::array<double, 3>>, std::pair<std::optional<MeshSolid>, std::string>>
      solids_;
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
/// The generalised winding number of a closed, outward-oriented mesh at x: 1 inside, 0 outside.
double winding_number(const TriangleMesh& mesh, const Vec3& x);
/// The distance from x to the convex hull of `points` (0 inside it).
double distance_to_hull(const std::vector<Vec3>& points, const Vec3& x);

}  // namespace tumble::robot
