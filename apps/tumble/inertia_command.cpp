// `tumble inertia`: mass, volume, centre of mass, inertia tensor and principal axes of a mesh file or
// a primitive shape, for a person or (--json) for a program.
#include <fmt/format.h>

#include <cmath>
#include <cstdio>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "commands.hpp"
#include "tumble/error.hpp"
#include "tumble/io/scene.hpp"
#include "tumble/mass/mesh_io.hpp"
#include "tumble/mass/mesh_mass.hpp"
#include "tumble/mass/shapes.hpp"

namespace tumble::cli {
namespace {

struct InertiaOptions {
  std::string file;
  std::string shape;
  std::vector<double> size;
  std::optional<double> density;
  std::optional<double> mass;
  double scale = 1.0;
  std::size_t part = 0;
  bool shell = false;
  std::optional<double> thickness;
  bool json = false;
  std::vector<double> about;  // a point, file axes (m)
  std::vector<double> axis;   // a direction, file axes
  std::string frame = "reference";
  std::string body;  // for a scene file: one body by name
};

/// What was measured, whatever the source.
struct Report {
  std::string source;  // "t_handle.stl (closed mesh, 12 vertices, 20 triangles)" or "box 0.1 x 0.2 x 0.3 m"
  MassProperties mp;
  std::optional<double> surface_area;
  std::vector<std::string> warnings;
  std::string name;  // the body's, for a scene file
};

Shape make_shape(const std::string& name, const std::vector<double>& s) {
  // Dimensions in the order --help documents; the count is checked against the shape.
  static const std::map<std::string, std::pair<size_t, const char*>> arity = {
      {"box", {3, "x,y,z edge lengths"}},
      {"sphere", {1, "radius"}},
      {"ellipsoid", {3, "semi-axes a,b,c"}},
      {"cylinder", {2, "radius,length"}},
      {"capsule", {2, "radius,length of the cylindrical part"}},
      {"cone", {2, "base radius,height"}},
      {"torus", {2, "major radius,minor radius"}},
  };
  const auto it = arity.find(name);
  if (it == arity.end()) {
    throw InvalidArgument(fmt::format(
        "unknown shape '{}': choose box, sphere, ellipsoid, cylinder, capsule, cone or torus", name));
  }
  if (s.size() != it->second.first) {
    throw InvalidArgument(fmt::format("--shape {} takes --size with {} number(s) ({}), got {}", name,
                                      it->second.first, it->second.second, s.size()));
  }
  if (name == "box") return Box{Vec3(s[0], s[1], s[2])};
  if (name == "sphere") return Sphere{s[0]};
  if (name == "ellipsoid") return Ellipsoid{Vec3(s[0], s[1], s[2])};
  if (name == "cylinder") return Cylinder{s[0], s[1]};
  if (name == "capsule") return Capsule{s[0], s[1]};
  if (name == "cone") return Cone{s[0], s[1]};
  return Torus{s[0], s[1]};
}

/// Without --density or --mass the material is of unit density: the mass is then the volume (the
/// area for a shell) and the tensor the shape's own second moments, which scale with any density.
bool unit_density(const InertiaOptions& o) { return !o.density && !o.mass; }

/// The wall of a shell given without --thickness (with --mass, or with neither mass nor density): its
/// value only sets the volume, which is then reported as unknown. The thinnest wall there is fits
/// inside every shape (the check that a wall fits, and the warning about a wall as thick as a mesh's
/// finest edge, are for walls the user gave); a power of two, so that ρ = 1/t is exact.
constexpr double kUnknownWall = 0x1p-1022;

MassSpec mass_spec(const InertiaOptions& o) {
  if (o.density) return MassSpec::density(*o.density);
  if (o.mass) return MassSpec::mass(*o.mass);
  // Nothing given: unit density for a solid, unit surface density (ρ·t = 1 kg/m²) for a shell.
  return MassSpec::density(o.shell && !o.thickness ? 1.0 / kUnknownWall : 1.0);
}

double shell_thickness(const InertiaOptions& o) {
  if (o.thickness) return *o.thickness;
  if (o.density) {
    throw InvalidArgument(
        "--shell with --density needs the wall thickness: add --thickness T (m), or give --mass");
  }
  return kUnknownWall;
}

/// Every body of a scene file (or the one named by --body), as the scene builds it: its parts, holes,
/// polynomial density, explicit inertia — whatever the file gives.
std::vector<Report> measure_scene(const InertiaOptions& o) {
  const Scene scene = load_scene(o.file);
  std::vector<Report> out;
  for (size_t i = 0; i < scene.model.bodies.size(); ++i) {
    const RigidBody& b = scene.model.bodies[i];
    if (!o.body.empty() && b.name() != o.body) continue;
    Report r;
    r.name = b.name();
    r.source = fmt::format("body '{}' of {}: {}", b.name(), o.file, *scene.body_info[i].source);
    r.mp = b.mass_properties();
    out.push_back(std::move(r));
  }
  if (out.empty()) {
    std::vector<std::string> names;
    for (const RigidBody& b : scene.model.bodies) names.push_back(b.name());
    throw InvalidArgument(
        fmt::format("{} has no body named '{}'; its bodies are: {}", o.file, o.body, fmt::join(names, ", ")));
  }
  return out;
}

Report measure(const InertiaOptions& o) {
  const MassSpec spec = mass_spec(o);
  Report r;
  if (!o.shape.empty()) {
    const Shape shape = make_shape(o.shape, o.size);
    r.source = fmt::format("{} ({}), size {} m", shape_name(shape), o.shell ? "thin shell" : "solid",
                           fmt::join(o.size, " x "));
    r.mp = o.shell ? shell_mass_properties(shape, shell_thickness(o), spec)
                   : solid_mass_properties(shape, spec);
    r.surface_area = surface_area(shape);
  } else {
    LoadedMesh loaded = load_mesh(o.file, MeshLoadOptions{.scale = o.scale, .part = o.part});
    const TriangleMesh& mesh = loaded.mesh;
    const MeshMassResult result = [&] {
      try {
        return o.shell ? shell_mass_properties(mesh, shell_thickness(o), spec, o.file)
                       : solid_mass_properties(mesh, spec, o.file);
      } catch (const NotASolidError& e) {
        throw NotASolidError(std::string(e.what()) +
                             ": add --shell (with --thickness T and --density, or with --mass)");
      }
    }();
    r.source = fmt::format("{} ({}, {} vertices, {} triangles{}{}; {}: {})", o.file,
                           o.shell ? "thin shell" : "closed mesh", mesh.vertices.size(),
                           mesh.triangles.size(),
                           o.part != 0 ? fmt::format(", part {} of {}", o.part, loaded.parts) : "",
                           o.scale != 1.0 ? fmt::format(", scaled by {}", o.scale) : "", loaded.format,
                           loaded.precision);
    r.mp = result.properties;
    r.surface_area = result.surface_area;
    r.warnings = std::move(loaded.warnings);
    r.warnings.insert(r.warnings.end(), result.warnings.begin(), result.warnings.end());
  }
  if (o.shell && !o.thickness) r.mp.volume = 0.0;  // unknown without a thickness
  if (unit_density(o)) {
    r.source += o.shell ? "; unit surface density (1 kg/m^2): the mass is the area"
                        : "; unit density (1 kg/m^3): the mass is the volume";
  }
  return r;
}

bool is_scene_file(const std::string& file) { return std::filesystem::path(file).extension() == ".toml"; }

Vec3 vec3_option(const std::vector<double>& v) { return {v[0], v[1], v[2]}; }

/// The derived quantities the options ask for, in the frame they ask for.
struct Derived {
  Mat3 inertia;                       // about the centre of mass or --about, in --frame axes
  std::optional<Vec3> about;          // the point (file axes)
  std::optional<double> axis_moment;  // about --axis through the point (or the centre of mass)
  std::optional<double> gyration;     // sqrt(axis_moment / m)
  Vec3 axis = Vec3::Zero(), axis_point = Vec3::Zero();
};

Derived derive(const InertiaOptions& o, const Report& r, const PrincipalAxes& pa) {
  Derived d;
  Mat3 I = r.mp.inertia;
  if (!o.about.empty()) {
    d.about = vec3_option(o.about);
    I = r.mp.inertia_about(*d.about);  // I_c + m(|c − p|² E − (c − p)(c − p)ᵀ)
  }
  d.inertia = o.frame == "principal" ? Mat3(pa.U.transpose() * I * pa.U) : I;
  if (!o.axis.empty()) {
    d.axis = vec3_option(o.axis);
    d.axis_point = d.about.value_or(r.mp.center_of_mass);
    d.axis_moment = r.mp.moment_about_axis(d.axis, d.axis_point);
    d.gyration = r.mp.radius_of_gyration(d.axis, d.axis_point);
  }
  return d;
}

// x + 0.0 is x, but −0 becomes +0: a negative zero is rounding's sign, not a fact to print.
std::string json_vector(const Vec3& v) {
  return fmt::format("[{}, {}, {}]", v(0) + 0.0, v(1) + 0.0, v(2) + 0.0);
}
std::string json_rows(const Mat3& M) {
  return fmt::format("[{}, {}, {}]", json_vector(M.row(0)), json_vector(M.row(1)), json_vector(M.row(2)));
}
std::string json_string(const std::string& s) {
  std::string out = "\"";
  for (char c : s) {
    if (c == '"' || c == '\\') out += '\\';
    if (static_cast<unsigned char>(c) < 0x20) {
      out += fmt::format("\\u{:04x}", static_cast<int>(c));
      continue;
    }
    out += c;
  }
  return out + "\"";
}

std::string json_object(const Report& r, const PrincipalAxes& pa, const Derived& d,
                        const std::string& frame) {
  // fmt's "{}" prints the shortest representation that reads back to the same double.
  std::vector<std::string> warnings;
  for (const auto& w : r.warnings) warnings.push_back(json_string(w));
  std::string extra;
  if (!r.name.empty()) extra += fmt::format("  \"name\": {},\n", json_string(r.name));
  if (d.about) extra += fmt::format("  \"about\": {},\n", json_vector(*d.about));
  if (d.axis_moment) {
    extra +=
        fmt::format("  \"axis_moment\": {},\n  \"radius_of_gyration\": {},\n", *d.axis_moment, *d.gyration);
  }
  return fmt::format(
      "{{\n{}  \"mass\": {},\n  \"volume\": {},\n  \"surface_area\": {},\n  \"center_of_mass\": {},\n"
      "  \"frame\": {},\n  \"inertia\": {},\n  \"principal_moments\": {},\n  \"principal_axes\": {},\n"
      "  \"warnings\": [{}]\n}}",
      extra, r.mp.mass, r.mp.volume, r.surface_area ? fmt::format("{}", *r.surface_area) : "null",
      json_vector(r.mp.center_of_mass), json_string(frame), json_rows(d.inertia), json_vector(pa.Lambda),
      json_rows(pa.U), fmt::join(warnings, ", "));
}

void print_human(const Report& r, const PrincipalAxes& pa, const Derived& d, const std::string& frame) {
  const MassProperties& mp = r.mp;
  fmt::print("{}\n", r.source);
  fmt::print("  mass              {:.10g} kg\n", mp.mass);
  if (mp.volume > 0) fmt::print("  volume            {:.10g} m^3\n", mp.volume);
  if (r.surface_area) fmt::print("  surface area      {:.10g} m^2\n", *r.surface_area);
  const Vec3& c = mp.center_of_mass;
  fmt::print("  centre of mass    ({:.10g}, {:.10g}, {:.10g}) m\n", c(0) + 0.0, c(1) + 0.0, c(2) + 0.0);
  fmt::print("  inertia tensor about {}, {} (kg*m^2):\n",
             d.about ? fmt::format("the point ({:.10g}, {:.10g}, {:.10g}) m", (*d.about)(0), (*d.about)(1),
                                   (*d.about)(2))
                     : std::string("the centre of mass"),
             frame == "principal" ? "principal axes (the columns of U below)" : "file axes");
  for (int i = 0; i < 3; ++i) {
    fmt::print("    [{:>17.10g} {:>17.10g} {:>17.10g} ]\n", d.inertia(i, 0) + 0.0, d.inertia(i, 1) + 0.0,
               d.inertia(i, 2) + 0.0);
  }
  if (d.axis_moment) {
    fmt::print(
        "  moment about the axis ({:.10g}, {:.10g}, {:.10g}) through ({:.10g}, {:.10g}, {:.10g}) m: {:.10g} "
        "kg*m^2, radius of gyration {:.10g} m\n",
        d.axis(0), d.axis(1), d.axis(2), d.axis_point(0), d.axis_point(1), d.axis_point(2), *d.axis_moment,
        *d.gyration);
  }
  fmt::print("  principal moments (ascending) (kg*m^2):\n    {:.10g}  {:.10g}  {:.10g}\n", pa.Lambda(0),
             pa.Lambda(1), pa.Lambda(2));
  fmt::print("  principal axes (columns of U, a proper rotation: I = U diag(moments) U^T):\n");
  for (int i = 0; i < 3; ++i) {
    // An entry below the last digit shown is 0, not "-0.0000000000".
    const auto shown = [](double u) { return std::abs(u) < 5e-11 ? 0.0 : u; };
    fmt::print("    [{:>13.10f} {:>13.10f} {:>13.10f} ]\n", shown(pa.U(i, 0)), shown(pa.U(i, 1)),
               shown(pa.U(i, 2)));
  }
}

}  // namespace

Runner add_inertia_command(CLI::App& app) {
  auto o = std::make_shared<InertiaOptions>();
  CLI::App* cmd = app.add_subcommand(
      "inertia",
      "Mass properties (tutorial section IV) of a closed triangle mesh, a primitive shape or the "
      "bodies of a scene file: mass, volume, centre of mass, the inertia tensor about the centre of "
      "mass (or a point) in the file's axes (or the principal ones), the principal moments "
      "(ascending) and axes, and the moment about an axis. Without --density or --mass the density is "
      "1 kg/m^3: the mass is the volume, and the tensor scales with any density.\n\nExamples:\n"
      "  tumble inertia part.stl --density 2700 --scale 0.001   (aluminium part drawn in mm)\n"
      "  tumble inertia --shape box --size 0.1,0.2,0.3 --density 1000 --json\n"
      "  tumble inertia --shape box --size 0.1,0.2,0.3 --mass 6 --about 0.05,0.1,0.15 --axis 1,0,0\n"
      "  tumble inertia examples/asteroid.toml --frame principal   (every body as the scene builds "
      "it: parts, holes, polynomial density)\n"
      "  tumble inertia --shape sphere --size 0.5 --shell --thickness 0.002 --density 7850");
  cmd->add_option("file", o->file,
                  "mesh file, or a scene file (.toml) to report its bodies; a mesh must be closed and "
                  "consistently oriented unless --shell is given. "
                  "Precision: OBJ, OFF, ASCII PLY and ASCII STL are read exactly (every digit written, "
                  "each coordinate the nearest double); binary PLY as stored (double stays double); binary "
                  "STL holds float32 by its format; the other formats assimp reads (3MF, glTF, DAE, ...) "
                  "are read as float32. Only regular files of at most 1 GiB are read (FIFOs and devices "
                  "are refused); raise the limit with the environment variable TUMBLE_MAX_INPUT_BYTES "
                  "(bytes, or with k, M, G: e.g. TUMBLE_MAX_INPUT_BYTES=8G). assimp runs in a child "
                  "process: a crash there is an error, and it is stopped after 30 s + 1 s per MiB "
                  "(TUMBLE_LOADER_TIMEOUT_S=600 raises it) or beyond 32 x the file size of memory, at "
                  "least 2 GiB (TUMBLE_LOADER_MEMORY_BYTES=64G)");
  auto* shape = cmd->add_option("--shape", o->shape,
                                "a primitive instead of a file: box, sphere, ellipsoid, cylinder, "
                                "capsule, cone, torus (axis z, centred; cone base at z=0)");
  cmd->add_option("--size", o->size,
                  "the shape's dimensions in m, comma-separated: box x,y,z | sphere r | ellipsoid "
                  "a,b,c | cylinder r,length | capsule r,length | cone r,height | torus R,r")
      ->delimiter(',')
      ->needs(shape);
  auto* density = cmd->add_option("--density", o->density, "uniform density (kg/m^3)");
  auto* mass = cmd->add_option("--mass", o->mass, "total mass (kg), spread uniformly");
  density->excludes(mass);
  cmd->add_option("--scale", o->scale,
                  "multiply mesh coordinates by S (e.g. 0.001 for a file in millimetres)")
      ->excludes(shape);
  cmd->add_option("--part", o->part,
                  "take only part K (1-based, file order) of a file with several: OBJ objects (or "
                  "groups), STL solids, assimp meshes; by default all parts are merged with a warning")
      ->check(CLI::PositiveNumber)
      ->excludes(shape);
  auto* shell = cmd->add_flag("--shell", o->shell,
                              "thin-walled part: mass on the surface (surface density = density x "
                              "thickness); open meshes are allowed");
  cmd->add_option("--thickness", o->thickness, "wall thickness (m) for --shell with --density")->needs(shell);
  cmd->add_option("--about", o->about,
                  "also the inertia tensor about this point X,Y,Z (m, file axes) instead of the centre "
                  "of mass: I_p = I_c + m (|d|^2 E - d d^T), d = c - p")
      ->delimiter(',')
      ->expected(3);
  cmd->add_option("--axis", o->axis,
                  "the moment of inertia about the line along X,Y,Z (file axes) through the centre of "
                  "mass (or --about), and the radius of gyration sqrt(I/m)")
      ->delimiter(',')
      ->expected(3);
  cmd->add_option("--frame", o->frame,
                  "axes of the printed tensor: reference (the file's, default) or principal (diagonal: "
                  "the principal moments)")
      ->check(CLI::IsMember({"reference", "principal"}));
  cmd->add_option("--body", o->body, "with a scene file: only this body (default: every body)");
  cmd->add_flag(
      "--json", o->json,
      "print JSON: mass, volume, surface_area, center_of_mass, inertia (3x3 rows), "
      "principal_moments, principal_axes (3x3 rows; columns are the axes), warnings; frame, and about, "
      "axis_moment, radius_of_gyration when asked; name and a list of objects for a scene");
  cmd->callback([o, shape] {
    if (o->file.empty() == (shape->count() == 0)) {
      throw CLI::ValidationError("inertia", "give either a mesh FILE or --shape NAME --size ...");
    }
  });

  return [o] {
    const bool scene = !o->file.empty() && is_scene_file(o->file);
    if (!scene && !o->body.empty()) throw InvalidArgument("--body names a body of a scene file (.toml)");
    const std::vector<Report> reports = scene ? measure_scene(*o) : std::vector<Report>{measure(*o)};
    std::vector<std::string> json;
    for (const Report& r : reports) {
      r.mp.validate({}, o->file.empty() ? o->shape : o->file);
      for (const auto& w : r.warnings) fmt::print(stderr, "tumble: warning: {}\n", w);
      const PrincipalAxes pa = r.mp.principal_axes();
      const Derived d = derive(*o, r, pa);
      if (o->json) {
        json.push_back(json_object(r, pa, d, o->frame));
      } else {
        print_human(r, pa, d, o->frame);
      }
    }
    // A scene gives a list (one object per body); a shape or mesh one object.
    if (o->json) {
      const std::string body = fmt::format("{}", fmt::join(json, ",\n"));
      fmt::print("{}\n", scene ? "[" + body + "]" : body);
    }
    return 0;
  };
}

}  // namespace tumble::cli
