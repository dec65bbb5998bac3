#pragma once
// What a picture of a run needs besides its samples: each body's surface and mass properties, and the
// springs. Written into the trajectory file (HDF5: the group `geometry`; CSV: OUT.run.json) so that
// `tumble report` never reads the scene's meshes again (they may have moved or changed since).
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "tumble/io/scene.hpp"
#include "tumble/mass/triangle_mesh.hpp"

namespace tumble {

struct BodyGeometry {
  /// Its surface, reference frame (m), shared by the bodies of one mesh; null: drawn as the box of the
  /// same principal moments.
  std::shared_ptr<const TriangleMesh> mesh;
  double mass = 0.0;
  Vec3 com = Vec3::Zero();     ///< centre of mass, reference frame
  Mat3 U = Mat3::Identity();   ///< principal axes (columns), reference frame
  Vec3 Lambda = Vec3::Zero();  ///< principal moments, ascending

  /// The surface, empty where there is none.
  const TriangleMesh& surface() const {
    static const TriangleMesh none;
    return mesh ? *mesh : none;
  }
};

struct SpringGeometry {
  long a = -1, b = -1;  ///< rows (bodies, then particles); −1: a world anchor
  Vec3 point_a = Vec3::Zero(), point_b = Vec3::Zero();  ///< reference frame of a body, or world
};

struct SceneGeometry {
  std::vector<BodyGeometry> bodies;  ///< one per rigid body (particles have none)
  std::vector<SpringGeometry> springs;
};

/// The geometry of a scene as read (its display meshes and mass properties, its springs).
SceneGeometry scene_geometry(const Scene& scene);

}  // namespace tumble
