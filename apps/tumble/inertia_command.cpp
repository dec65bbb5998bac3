// `tumble inertia`: mass, volume, centre of mass, inertia tensor and principal axes of a mesh file or
// a primitive shape, for a person or (--json) for a program.
#include <fmt/format.h>

#include <cstdio>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "commands.hpp"
#include "tumble/error.hpp"
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
};

/// What was measured, whatever the source.
struct Report {
  std::string source;  // "t_handle.stl (closed mesh, 12 vertices, 20 triangles)" or "box 0.1 x 0.2 x 0.3 m"
  MassProperties mp;
  std::optional<double> surface_area;
  std::vector<std::string> warnings;
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

MassSpec mass_spec(const InertiaOptions& o) {
  if (o.density) return MassSpec::density(*o.density);
  if (o.mass) return MassSpec::mass(*o.mass);
  throw InvalidArgument("give the material: --density RHO (kg/m^3) or --mass M (kg)");
}

double shell_thickness(const InertiaOptions& o) {
  if (o.thickness) return *o.thickness;
  if (o.density) {
    throw InvalidArgument(
        "--shell with --density needs the wall thickness: add --thickness T (m), or give --mass");
  }
  return 1.0;  // with a total mass the thickness only sets the reported volume; report area instead
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
    const MeshMassResult result = o.shell ? shell_mass_properties(mesh, shell_thickness(o), spec, o.file)
                                          : solid_mass_properties(mesh, spec, o.file);
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
  return r;
}

std::string json_vector(const Vec3& v) { return fmt::format("[{}, {}, {}]", v(0), v(1), v(2)); }
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

void print_json(const Report& r, const PrincipalAxes& pa) {
  // fmt's "{}" prints the shortest representation that reads back to the same double.
  std::vector<std::string> warnings;
  for (const auto& w : r.warnings) warnings.push_back(json_string(w));
  fmt::print(
      "{{\n  \"mass\": {},\n  \"volume\": {},\n  \"surface_area\": {},\n  \"center_of_mass\": {},\n"
      "  \"inertia\": {},\n  \"principal_moments\": {},\n  \"principal_axes\": {},\n"
      "  \"warnings\": [{}]\n}}\n",
      r.mp.mass, r.mp.volume, r.surface_area ? fmt::format("{}", *r.surface_area) : "null",
      json_vector(r.mp.center_of_mass), json_rows(r.mp.inertia), json_vector(pa.Lambda), json_rows(pa.U),
      fmt::join(warnings, ", "));
}

void print_human(const Report& r, const PrincipalAxes& pa) {
  const MassProperties& mp = r.mp;
  fmt::print("{}\n", r.source);
  fmt::print("  mass              {:.10g} kg\n", mp.mass);
  if (mp.volume > 0) fmt::print("  volume            {:.10g} m^3\n", mp.volume);
  if (r.surface_area) fmt::print("  surface area      {:.10g} m^2\n", *r.surface_area);
  const Vec3& c = mp.center_of_mass;
  fmt::print("  centre of mass    ({:.10g}, {:.10g}, {:.10g}) m\n", c(0), c(1), c(2));
  fmt::print("  inertia tensor about the centre of mass, file axes (kg*m^2):\n");
  for (int i = 0; i < 3; ++i) {
    fmt::print("    [{:>17.10g} {:>17.10g} {:>17.10g} ]\n", mp.inertia(i, 0), mp.inertia(i, 1),
               mp.inertia(i, 2));
  }
  fmt::print("  principal moments (ascending) (kg*m^2):\n    {:.10g}  {:.10g}  {:.10g}\n", pa.Lambda(0),
             pa.Lambda(1), pa.Lambda(2));
  fmt::print("  principal axes (columns of U, a proper rotation: I = U diag(moments) U^T):\n");
  for (int i = 0; i < 3; ++i) {
    fmt::print("    [{:>13.10f} {:>13.10f} {:>13.10f} ]\n", pa.U(i, 0), pa.U(i, 1), pa.U(i, 2));
  }
}

}  // namespace

Runner add_inertia_command(CLI::App& app) {
  auto o = std::make_shared<InertiaOptions>();
  CLI::App* cmd = app.add_subcommand(
      "inertia",
      "Mass properties (tutorial section IV) of a closed triangle mesh or a primitive shape: mass, "
      "volume, centre of mass, the inertia tensor about the centre of mass in the file's axes, and "
      "the principal moments (ascending) and axes.\n\nExamples:\n"
      "  tumble inertia part.stl --density 2700 --scale 0.001   (aluminium part drawn in mm)\n"
      "  tumble inertia --shape box --size 0.1,0.2,0.3 --density 1000 --json\n"
      "  tumble inertia --shape sphere --size 0.5 --shell --thickness 0.002 --density 7850");
  cmd->add_option("file", o->file,
                  "mesh file; the mesh must be closed and consistently oriented unless --shell is given. "
                  "Precision: OBJ, OFF, ASCII PLY and ASCII STL are read exactly (every digit written, "
                  "each coordinate the nearest double); binary STL holds float32 by its format; binary "
                  "PLY and the other formats assimp reads (3MF, glTF, DAE, ...) are read as float32");
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
  cmd->add_flag("--json", o->json,
                "print JSON: mass, volume, surface_area, center_of_mass, inertia (3x3 rows), "
                "principal_moments, principal_axes (3x3 rows; columns are the axes), warnings");
  cmd->callback([o, shape] {
    if (o->file.empty() == (shape->count() == 0)) {
      throw CLI::ValidationError("inertia", "give either a mesh FILE or --shape NAME --size ...");
    }
  });

  return [o] {
    const Report r = measure(*o);
    r.mp.validate({}, o->file.empty() ? o->shape : o->file);
    for (const auto& w : r.warnings) fmt::print(stderr, "tumble: warning: {}\n", w);
    const PrincipalAxes pa = r.mp.principal_axes();
    if (o->json) {
      print_json(r, pa);
    } else {
      print_human(r, pa);
    }
    return 0;
  };
}

}  // namespace tumble::cli
