#pragma once
// The audit of a robot description's inertials (`tumble model check`): each link's mass properties
// computed from its geometry — meshes exactly, primitives in closed form, several geometries summed,
// each posed in the link — and judged against the authored <inertial>, as findings with stable codes
// (docs/robot-models.md lists each with what triggers it and its threshold).
//
// Which geometry carries the mass: URDF and SDF, the link's <collision> geometries, or its <visual>
// ones when it has no collision (AuditOptions::geometry swaps the preference); MJCF, MuJoCo's rule —
// every geom within inertiagrouprange, each weighted by its own mass or density.
//
// The computed mass: at a given density (AuditOptions::density); else, for URDF and SDF, the authored
// mass spread uniformly over the link's geometry (the tensors are then compared at the same mass); for
// MJCF, each geom's own mass or density, as MuJoCo infers it.
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "tumble/mass/mass_properties.hpp"
#include "tumble/robot/robot_model.hpp"

namespace tumble::robot {

enum class GeometryChoice { collision, visual };

struct AuditOptions {
  /// Where package://PKG/... and model://PKG/... resolve: each directory D gives D/PKG, or D itself
  /// when its name is PKG; then ROS_PACKAGE_PATH's directories (the same rule) and AMENT_PREFIX_PATH's
  /// prefixes (P/share/PKG), GAZEBO_MODEL_PATH and GZ_SIM_RESOURCE_PATH (model://).
  std::vector<std::filesystem::path> package_paths;
  GeometryChoice geometry = GeometryChoice::collision;
  std::optional<double> density;  ///< kg/m³: compute every link's mass from it
  bool lump_fixed = false;        ///< also audit the bodies that fixed joints weld together
};

enum class Severity { warning, error };

struct Finding {
  std::string code;  ///< e.g. "not_positive_definite" (docs/robot-models.md)
  Severity severity = Severity::warning;
  std::string message;  ///< what, where (link, file:line) and how to fix it
};

/// What a link's geometry gives.
struct ComputedMass {
  MassProperties properties;  ///< mass, COM, inertia about it (link frame), volume
  std::string geometry;       ///< what it was computed from: "collision 2 meshes, box"
  std::string
      basis;  ///< where its mass comes from: "the authored mass", "1000 kg/m³ (no authored mass)", ...
  bool from_meshes = false;  ///< a mesh is among the geometries (the mesh_scale finding applies)
};

struct LinkAudit {
  std::string name;
  int line = 0;
  std::optional<Inertial> authored;
  std::optional<ComputedMass> computed;  ///< none: no usable geometry (the findings say why)
  std::vector<std::string> parts;        ///< a lumped body's links; empty for a link of the file
  std::vector<std::string> skipped;      ///< geometries that carry no mass, and why (Link::skipped)
  std::vector<Finding> findings;
};

struct ModelAudit {
  RobotModel model;
  std::vector<LinkAudit> links;    ///< in file order; then the lumped bodies when asked
  std::vector<std::string> notes;  ///< the reader's notes and what was assumed
  bool has_errors() const;
};

/// Reads and audits a robot description. Throws as read_robot_model does; everything about a link
/// (a missing mesh, an open one) is a finding, not an exception.
[[nodiscard]] ModelAudit audit_model(const std::filesystem::path& path, const AuditOptions& options = {});

/// The audit as JSON: {"model", "format", "links": [{"name", "authored": {mass, com, inertia},
/// "computed": {volume, mass, com, inertia, geometry}, "findings": [{"code", "severity", "message"}]}]}.
std::string audit_json(const ModelAudit& audit);
/// The audit as a table for a terminal, then every finding.
std::string audit_table(const ModelAudit& audit);

}  // namespace tumble::robot
