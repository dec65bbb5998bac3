#pragma once
// A robot description (URDF, MJCF or SDF) as far as mass properties go: each link's authored inertial,
// the geometries that carry its mass, the joints between links, and where each came from in the file
// (byte spans and lines), so that an audit can name the element and a fix can rewrite the inertial
// alone. One reader per format fills it (read_urdf.cpp, read_mjcf.cpp, read_sdf.cpp); everything after
// reading — resolving meshes, computing, judging, rewriting — is format-blind but for the rewrite.
//
// Frames: every pose is x_parent = R x + p. A link's geometries and its inertial are posed in the
// link's frame; a joint's origin poses the child link's frame in the parent link's.
#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "tumble/mass/shapes.hpp"
#include "tumble/math/types.hpp"

namespace tumble::robot {

enum class Format { urdf, mjcf, sdf };

/// "urdf", "mjcf", "sdf".
const char* format_name(Format format);

/// A rigid placement: x_parent = R x + p.
struct Pose {
  Mat3 R = Mat3::Identity();
  Vec3 p = Vec3::Zero();
};

/// Where an element is in the file: bytes [begin, end) of the whole element (from its '<' to the end
/// of its closing tag or of its '/>'), and the line (1-based) its start tag is on.
struct SourceSpan {
  std::size_t begin = 0, end = 0;
  int line = 0;
};

/// One geometry of a link, posed in the link's frame. A primitive has its shape (shapes.hpp's placement:
/// centred at its origin, axis along z); a mesh has its file and per-axis scale instead.
struct Geometry {
  std::string name;                 ///< the element's name attribute, if any
  std::string element;              ///< "collision", "visual" (URDF, SDF) or "geom" (MJCF)
  std::optional<Shape> shape;       ///< a primitive; empty for a mesh
  std::string mesh_uri;             ///< the mesh as written: "package://arm/meshes/l1.stl", "l1.stl", ...
  std::filesystem::path mesh_path;  ///< resolved by the reader where it can (relative paths, meshdir);
                                    ///< empty when the URI needs package paths (resolve_meshes)
  Vec3 scale = Vec3::Ones();        ///< per-axis scale of the mesh's coordinates
  Pose pose;                        ///< in the link's frame
  std::optional<double> mass;       ///< MJCF: the geom's own mass (overrides density)
  std::optional<double> density;    ///< MJCF: the geom's density (default 1000 kg/m³)
  int line = 0;
};

/// A link's <inertial> as the file has it.
struct Inertial {
  double mass = 0.0;
  std::string mass_text;                ///< the mass exactly as written ("3.7"), for a fix that keeps it
  Pose frame;                           ///< the inertial frame in the link's frame: its origin is the COM
  Mat3 inertia_written = Mat3::Zero();  ///< the tensor as written, about the COM, in the inertial frame
  /// The tensor about the COM in the link's axes: R I_written Rᵀ (R = frame.R).
  Mat3 inertia_link() const { return frame.R * inertia_written * frame.R.transpose(); }
  bool rotated = false;  ///< the file gives the inertial frame a rotation (rpy, quat, ...)
  SourceSpan span;       ///< the <inertial> element
};

struct Link {
  std::string name;
  int line = 0;
  std::optional<Inertial> inertial;  ///< none: the file gives no inertial (MJCF: MuJoCo infers it)
  /// The geometries that can carry the link's mass. URDF and SDF: its <collision> and its <visual>
  /// elements (ModelOptions::geometry chooses); MJCF: its geoms within the model's inertiagrouprange,
  /// in `collision` (MuJoCo's own rule; `visual` stays empty).
  std::vector<Geometry> collision, visual;
  /// Geometries the reader could not use (an MJCF plane or height field, an SDF heightmap): what and why.
  std::vector<std::string> skipped;
};

struct Joint {
  std::string name;
  std::string type;  ///< "fixed", "revolute", ... as the file names it (MJCF: "fixed" when a body has none)
  std::string parent, child;  ///< link names
  Pose origin;                ///< the child link's frame in the parent's
  int line = 0;
};

struct RobotModel {
  Format format = Format::urdf;
  std::string name;                ///< the robot's or model's name
  std::filesystem::path path;      ///< the file read
  std::string text;                ///< its bytes, for spans and rewriting
  std::vector<Link> links;         ///< in file order
  std::vector<Joint> joints;       ///< in file order
  std::vector<std::string> notes;  ///< what a reader wants the user to know (unsupported elements, ...)
};

/// Reads a robot description, choosing the format by the root element (<robot>: URDF, <mujoco>: MJCF,
/// <sdf>: SDF), not by the extension. Throws FileError for a file that cannot be read (input_file.hpp
/// rules), InvalidArgument with file:line:column for malformed XML, a document type declaration (DTD:
/// entities are refused), an unknown root, xacro elements (with the command that expands them), and
/// for values that are not numbers or poses.
[[nodiscard]] RobotModel read_robot_model(const std::filesystem::path& path);

}  // namespace tumble::robot
