#pragma once
// Scene files: what to simulate, written in TOML (docs/scene-format.md lists every key, its unit,
// frame and default). load_scene() turns a file into a Model, its initial state and the run settings;
// anything wrong in the file is a SceneError whose message begins with file:line:column and says
// what was expected, what was found and how to fix it.
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "tumble/error.hpp"
#include "tumble/forces/model.hpp"
#include "tumble/mass/triangle_mesh.hpp"
#include "tumble/sim/drift_monitor.hpp"
#include "tumble/sim/event_specs.hpp"
#include "tumble/sim/simulate.hpp"

namespace tumble {

/// A scene file that cannot be used. The message is one line: "file:line:column: what; how to fix".
class SceneError : public Error {
 public:
  using Error::Error;
};

/// What a scene says about one body besides its dynamics (for `tumble check`, summaries and pictures).
/// Both are shared: the rows of a body table share one source, the bodies of one mesh one display mesh,
/// so a scene of 10^5 bodies holds two pointers per body here (its mass properties are the RigidBody's).
struct SceneBodyInfo {
  /// Where the mass came from, e.g. "mesh t_handle.stl, 2700 kg/m^3".
  std::shared_ptr<const std::string> source;
  /// The body's surface for pictures (reports), reference frame: its shape tessellated, its mesh (at most
  /// kDisplayTriangles, decimated beyond), its parts but the holes; null where only mass and inertia are
  /// known (a report then draws the box of the same principal moments).
  std::shared_ptr<const TriangleMesh> display;
};

struct Scene {
  std::filesystem::path path;  ///< the scene file (as given)
  std::string text;            ///< its contents, stored with the outputs
  /// Every file the scene was read from: the scene file first, then each mesh file as a body or part
  /// names it and each [[body_tables]] file (paths as opened; a mesh used twice appears twice). An
  /// output must be none of them.
  std::vector<std::filesystem::path> input_files;
  RunSettings settings;                  ///< [simulation]
  Model model;                           ///< bodies, particles and force models, in file order
  SystemState initial;                   ///< the state at t = 0
  std::vector<SceneBodyInfo> body_info;  ///< parallel to model.bodies
  /// Which invariants the scene's forces conserve (decided from the force models present).
  Conservation conserved;
  /// Per-body output fields ([output] fields; sim/output_fields.hpp); empty: the defaults.
  std::vector<std::string> output_fields;
  /// [output] unwrap_angles: Euler-angle fields continuous from sample to sample (AngleUnwrapper).
  bool unwrap_angles = false;
  /// [[events]]: conditions watched during a run (make_events() turns them into RunHooks::events).
  std::vector<EventSpec> events;
  /// Things the user should know that are not errors (e.g. a mesh was inside-out and was flipped).
  std::vector<std::string> warnings;
};

/// Reads and validates a scene file. Mesh paths in it are relative to the file's directory.
/// Throws SceneError (file:line:column) for anything wrong in the file, FileError if it cannot be read.
Scene load_scene(const std::filesystem::path& path);

/// The same for scene text already in memory; `path` names it in messages and anchors mesh paths.
Scene parse_scene(const std::string& text, const std::filesystem::path& path);

/// Events for a scene given apart from its file: TOML text holding [[events]] tables (the keys of a
/// scene file's, docs/scene-format.md), checked against the scene's bodies and particles. SceneError
/// (`path`:line:column) for anything wrong.
std::vector<EventSpec> parse_events(const Scene& scene, const std::string& text,
                                    const std::filesystem::path& path);

}  // namespace tumble
