// Mass properties of scene bodies: primitive shapes, meshes, explicit inertia, composites of parts
// (with holes), uniform or polynomial density. Everything is computed in the body's reference frame;
// a part is computed in its own frame and placed with its pose (MassProperties::transformed).
#include <fmt/format.h>

#include <array>
#include <cmath>
#include <string_view>

#include "mesh_cache.hpp"
#include "scene_sanity.hpp"
#include "scene_sections.hpp"
#include "tumble/mass/density.hpp"
#include "tumble/mass/mesh_decimate.hpp"
#include "tumble/mass/mesh_io.hpp"
#include "tumble/mass/mesh_mass.hpp"
#include "tumble/mass/shapes.hpp"
#include "tumble/mass/tessellate.hpp"

namespace tumble::scene {
namespace {

/// ρ(x) = Σ c x^i y^j z^k, x in the body reference frame (kg/m³).
struct Polynomial {
  struct Term {
    double c;
    int i, j, k;
  };
  std::vector<Term> terms;
  int degree = 0;

  double operator()(const Vec3& x) const {
    double rho = 0.0;
    for (const Term& t : terms)
      rho += t.c * std::pow(x.x(), t.i) * std::pow(x.y(), t.j) * std::pow(x.z(), t.k);
    return rho;
  }
};

/// What a body or part is made of.
struct Material {
  enum class Kind { none, density, polynomial, mass } kind = Kind::none;
  double value = 0.0;  // density (kg/m³) or total mass (kg)
  Polynomial polynomial;
  std::string_view key;  // "density" or "mass", for locating messages

  std::string describe() const {
    switch (kind) {
      case Kind::density:
        return fmt::format("{:g} kg/m^3", value);
      case Kind::polynomial:
        return fmt::format("polynomial density of degree {}", polynomial.degree);
      case Kind::mass:
        return fmt::format("{:g} kg", value);
      case Kind::none:
        break;
    }
    return "unit density";
  }
};

// The rules are exact for polynomial ρ of degree ≤ d − 2 with d ≤ kMaxDensityDegree (density.hpp).
constexpr int kMaxPolynomialDegree = kMaxDensityDegree - 2;

int exponent(const TableReader& t, const toml::node& n, const ValueName& what) {
  const auto e = n.value_exact<int64_t>();
  if (!e || *e < 0 || *e > kMaxPolynomialDegree) {
    fail(t.file(), n.source(),
         fmt::format("{}: {} must be an integer exponent from 0 to {}, found {}", t.context(), what,
                     kMaxPolynomialDegree, type_name(n)));
  }
  return static_cast<int>(*e);
}

Polynomial read_polynomial(const TableReader& density) {
  Polynomial p;
  const toml::node* n = density.node("polynomial");
  const toml::array* terms = n ? n->as_array() : nullptr;
  if (!terms || terms->empty()) {
    density.fail_at("polynomial", fmt::format("polynomial must be a non-empty array of terms [c, i, j, k] "
                                              "(c x^i y^j z^k, kg/m^3), found {}",
                                              n ? type_name(*n) : "nothing"));
  }
  for (size_t m = 0; m < terms->size(); ++m) {
    const toml::node& term = *terms->get(m);
    const toml::array* a = term.as_array();
    if (!a || a->size() != 4) {
      fail(density.file(), term.source(),
           fmt::format("{}: polynomial term {} must be [c, i, j, k] (coefficient, exponents of x, y, z), "
                       "found {}",
                       density.context(), m, type_name(term)));
    }
    const int row = static_cast<int>(m);
    Polynomial::Term t{number_value(density, *a->get(0), {"polynomial", row, 0}, "kg/m^3 per m^(i+j+k)",
                                    Domain::finite),
                       exponent(density, *a->get(1), {"polynomial", row, 1}),
                       exponent(density, *a->get(2), {"polynomial", row, 2}),
                       exponent(density, *a->get(3), {"polynomial", row, 3})};
    if (t.i + t.j + t.k > kMaxPolynomialDegree) {
      fail(density.file(), term.source(),
           fmt::format("{}: polynomial term {} has degree {}; the quadrature is exact up to degree {}: "
                       "lower it",
                       density.context(), m, t.i + t.j + t.k, kMaxPolynomialDegree));
    }
    p.degree = std::max(p.degree, t.i + t.j + t.k);
    p.terms.push_back(t);
  }
  return p;
}

/// `density` (a number or { polynomial = ... }) or `mass` in table t; Kind::none if neither. A uniform
/// density outside what solids have gets a note in `notes` (scene_sanity.hpp).
Material read_material(const TableReader& t, std::vector<std::string>& notes) {
  t.at_most_one_of({"density", "mass"});
  Material m;
  if (t.has("mass")) {
    m.kind = Material::Kind::mass;
    m.value = *t.number("mass", "kg", Domain::positive);
    m.key = "mass";
  } else if (const toml::node* d = t.node("density")) {
    m.key = "density";
    if (d->is_table()) {
      const TableReader poly(*d->as_table(), t.context().child(" density"), t.file(), {"polynomial"});
      m.kind = Material::Kind::polynomial;
      m.polynomial = read_polynomial(poly);
    } else {
      m.kind = Material::Kind::density;
      m.value = *t.number("density", "kg/m^3", Domain::positive);
      if (auto note = implausible_density(m.value))
        notes.push_back(location(t.file(), t.where("density")) + ": " + *note);
    }
  }
  return m;
}

constexpr std::array<std::string_view, 7> kShapeTypes = {"box",     "sphere", "ellipsoid", "cylinder",
                                                         "capsule", "cone",   "torus"};

Shape read_shape(const TableReader& owner) {
  const toml::node* n = owner.node("shape");
  if (!n->is_table()) {
    owner.fail_at("shape", fmt::format("shape must be a table such as {{ type = \"box\", size = [0.1, 0.2, "
                                       "0.3] }}, found {}",
                                       type_name(*n)));
  }
  const toml::table& table = *n->as_table();
  const toml::node* type_node = table.get("type");
  const Context context = owner.context().child(" shape");
  if (!type_node || !type_node->is_string()) {
    fail(owner.file(), type_node ? type_node->source() : n->source(),
         fmt::format("{}: shape needs type = \"{}\"", context, fmt::join(kShapeTypes, "\" | \"")));
  }
  const std::string_view type = type_node->as_string()->get();
  // The dimensions of this type, then "type".
  auto reader = [&](Keys keys) {
    return TableReader(table, context.child(" (", type, ")"), owner.file(), keys);
  };
  const char* m = "m";
  const Domain pos = Domain::positive;
  Shape shape;
  if (type == "box") {
    const auto t = reader({"size", "type"});
    const auto size = t.vec3("size", m, pos);
    if (!size) t.fail_here("missing 'size': give the edge lengths [x, y, z] (m)");
    shape = Box{*size};
  } else if (type == "sphere") {
    shape = Sphere{reader({"radius", "type"}).required_number("radius", m, pos)};
  } else if (type == "ellipsoid") {
    const auto t = reader({"semi_axes", "type"});
    const auto a = t.vec3("semi_axes", m, pos);
    if (!a) t.fail_here("missing 'semi_axes': give [a, b, c] (m)");
    shape = Ellipsoid{*a};
  } else if (type == "cylinder" || type == "capsule") {
    const auto t = reader({"radius", "length", "type"});
    const double r = t.required_number("radius", m, pos);
    const double l = t.required_number("length", m, pos);
    shape = type == "cylinder" ? Shape(Cylinder{r, l}) : Shape(Capsule{r, l});
  } else if (type == "cone") {
    const auto t = reader({"radius", "height", "type"});
    shape = Cone{t.required_number("radius", m, pos), t.required_number("height", m, pos)};
  } else if (type == "torus") {
    const auto t = reader({"major_radius", "minor_radius", "type"});
    shape = Torus{t.required_number("major_radius", m, pos), t.required_number("minor_radius", m, pos)};
  } else {
    const auto s = closest(std::string(type), {kShapeTypes.begin(), kShapeTypes.end()});
    fail(owner.file(), type_node->source(),
         fmt::format("{}: unknown shape type \"{}\"; {}", context, type,
                     s ? fmt::format("did you mean \"{}\"?", *s)
                       : fmt::format("choose \"{}\"", fmt::join(kShapeTypes, "\", \""))));
  }
  try {
    validate_shape(shape);
  } catch (const InvalidArgument& e) {
    owner.fail_at("shape", e.what());
  }
  return shape;
}

std::string describe_shape(const Shape& s) {
  if (const auto* b = std::get_if<Box>(&s))
    return fmt::format("box {:g} x {:g} x {:g} m", b->size.x(), b->size.y(), b->size.z());
  if (const auto* p = std::get_if<Sphere>(&s)) return fmt::format("sphere r = {:g} m", p->radius);
  if (const auto* e = std::get_if<Ellipsoid>(&s)) {
    return fmt::format("ellipsoid {:g} x {:g} x {:g} m", e->semi_axes.x(), e->semi_axes.y(),
                       e->semi_axes.z());
  }
  if (const auto* c = std::get_if<Cylinder>(&s))
    return fmt::format("cylinder r = {:g} m, length {:g} m", c->radius, c->length);
  if (const auto* c = std::get_if<Capsule>(&s))
    return fmt::format("capsule r = {:g} m, length {:g} m", c->radius, c->length);
  if (const auto* c = std::get_if<Cone>(&s))
    return fmt::format("cone r = {:g} m, height {:g} m", c->radius, c->height);
  const auto& t = std::get<Torus>(s);
  return fmt::format("torus R = {:g} m, r = {:g} m", t.major_radius, t.minor_radius);
}

/// A part's pose in the body reference frame: x_body = R x_part + t.
struct Pose {
  Mat3 R = Mat3::Identity();
  Vec3 t = Vec3::Zero();
};

/// A polynomial density, written in the body frame, as a field over a part placed there by `pose`.
DensityField density_in_part(const Material& mat, const Pose& pose) {
  return [&mat, pose](const Vec3& x) { return mat.polynomial(pose.R * x + pose.t); };
}

/// The solid of `shape` or `mesh` in table t (its own frame), with material `mat`; `pose` places it
/// in the body frame, where a polynomial density is written.
MassProperties solid(const TableReader& t, const Material& mat, const Pose& pose,
                     const std::filesystem::path& directory, std::string& source,
                     std::shared_ptr<const TriangleMesh>& display, Scene& scene) {
  // The rule of degree d is exact for ρ of degree d − 2 (density.hpp).
  const int degree = std::max(kMinDensityDegree, mat.polynomial.degree + 2);
  const MassSpec spec = mat.kind == Material::Kind::mass      ? MassSpec::mass(mat.value)
                        : mat.kind == Material::Kind::density ? MassSpec::density(mat.value)
                                                              : MassSpec::density(1.0);
  // A thickness makes the shape or mesh a thin shell: surface density ρ·t, open meshes allowed.
  const bool is_shell = t.has("thickness");
  const double thickness = is_shell ? t.number("thickness", 0.0, "m", Domain::positive) : 0.0;
  if (is_shell && mat.kind == Material::Kind::polynomial) {
    t.fail_at("thickness",
              "a thin shell takes a uniform density or a mass; a polynomial density applies to "
              "solids only: remove thickness or give density = RHO");
  }
  const std::string shell = is_shell ? fmt::format(", thin shell {:g} m thick", thickness) : "";
  try {
    if (t.has("shape")) {
      t.at_most_one_of({"shape", "mesh"});
      if (t.has("scale"))
        t.fail_at("scale", "scale applies to a mesh only: remove it or give mesh = \"...\"");
      const Shape shape = read_shape(t);
      source = describe_shape(shape) + shell + ", " + mat.describe();
      display = std::make_shared<const TriangleMesh>(tessellate(shape, kDisplaySegments));
      if (is_shell) return shell_mass_properties(shape, thickness, spec);
      if (mat.kind == Material::Kind::polynomial)
        return integrate_density(shape, density_in_part(mat, pose), degree).properties;
      return solid_mass_properties(shape, spec);
    }
    const std::string file(*t.string("mesh"));
    const double scale = t.number("scale", 1.0, "", Domain::positive);
    const std::filesystem::path path = directory / file;
    scene.input_files.push_back(path);
    std::shared_ptr<const CachedMesh> cached;
    try {
      cached = load_mesh_cached(path, MeshLoadOptions{.scale = scale});
      // A glTF's buffers are inputs as much as the mesh: stamped for resume, never overwritten.
      for (const auto& f : cached->loaded().companions) scene.input_files.push_back(f);
      for (const auto& w : cached->loaded().warnings)
        scene.warnings.push_back(location(t.file(), t.where("mesh")) + ": " + w);
    } catch (const Error& e) {
      t.fail_at("mesh", fmt::format("cannot load mesh \"{}\": {}; mesh paths are relative to the scene "
                                    "file's directory",
                                    file, e.what()));
    }
    const TriangleMesh& mesh = cached->mesh();
    if (!t.has("scale")) {
      if (auto note = implausible_mesh_size(cached->diagonal()))
        scene.warnings.push_back(location(t.file(), t.where("mesh")) + ": " + file + ": " + *note);
    }
    source = fmt::format("mesh {} ({} triangles{}){}, {}", file, mesh.triangles.size(),
                         scale != 1.0 ? fmt::format(", scale {:g}", scale) : "", shell, mat.describe());
    display = cached->display();  // shared by every body of this mesh
    if (is_shell) {
      MeshMassResult r = shell_mass_properties(mesh, thickness, spec, file);
      for (auto& w : r.warnings) scene.warnings.push_back(location(t.file(), t.where("mesh")) + ": " + w);
      return r.properties;
    }
    if (mat.kind == Material::Kind::polynomial) {
      DensityResult r = integrate_density(mesh, density_in_part(mat, pose), degree, file);
      for (auto& w : r.warnings) scene.warnings.push_back(location(t.file(), t.where("mesh")) + ": " + w);
      return r.properties;
    }
    MeshMassResult r = cached->unit_solid(file);  // solid_mass_properties(mesh, spec, file), in two
    for (auto& w : r.warnings) scene.warnings.push_back(location(t.file(), t.where("mesh")) + ": " + w);
    return spec.apply(r.properties);
  } catch (const SceneError&) {
    throw;
  } catch (const NotASolidError& e) {
    t.fail_at("mesh", std::string(e.what()) + ": add thickness = T (m) to this body to make it a thin shell");
  } catch (const Error& e) {
    t.fail_at(t.has("mesh") ? "mesh" : (mat.kind == Material::Kind::polynomial ? mat.key : "shape"),
              e.what());
  }
}

/// mass + inertia (+ center_of_mass): a body known from data.
MassProperties explicit_inertia(const TableReader& t, const Material& mat) {
  if (mat.kind != Material::Kind::mass) {
    t.fail_at("inertia", "inertia needs the total mass: give mass = M (kg) (density does not apply)");
  }
  const toml::node& n = *t.node("inertia");
  const toml::array* a = n.as_array();
  Mat3 I = Mat3::Zero();
  if (a && a->size() == 3 && (*a)[0].is_number()) {
    for (int i = 0; i < 3; ++i) {
      I(i, i) = number_value(t, *a->get(static_cast<size_t>(i)), {"inertia", i}, "kg*m^2", Domain::positive);
    }
  } else if (a && a->size() == 3) {
    for (int i = 0; i < 3; ++i) {
      const toml::array* row = (*a)[static_cast<size_t>(i)].as_array();
      if (!row || row->size() != 3) {
        const toml::node& r = (*a)[static_cast<size_t>(i)];
        fail(t.file(), r.source(),
             fmt::format("{}: inertia row {} must be an array of 3 numbers (kg*m^2), found {}", t.context(),
                         i, type_name(r)));
      }
      for (int j = 0; j < 3; ++j) {
        I(i, j) =
            number_value(t, *row->get(static_cast<size_t>(j)), {"inertia", i, j}, "kg*m^2", Domain::finite);
      }
    }
    if (!I.isApprox(I.transpose(), 1e-12)) {  // entries are typed in; a mismatch is a typo
      t.fail_at("inertia",
                "inertia must be symmetric (inertia[i][j] = inertia[j][i]): check the products of inertia");
    }
    I = 0.5 * (I + I.transpose());
  } else {
    t.fail_at("inertia",
              fmt::format("inertia must be [Ixx, Iyy, Izz] or a 3x3 array [[Ixx, Ixy, Ixz], [...], "
                          "[...]] (kg*m^2, about the centre of mass), found {}",
                          type_name(n)));
  }
  const MassProperties mp =
      MassProperties::from_inertia(mat.value, t.vec3("center_of_mass", Vec3::Zero(), "m"), I);
  try {
    mp.validate();
  } catch (const InvalidMassProperties& e) {
    t.fail_at("inertia", e.what());
  }
  return mp;
}

/// Appends `part`, placed in the body frame by `pose`, to `body`.
void append_placed(TriangleMesh& body, const TriangleMesh& part, const Pose& pose) {
  const auto base = static_cast<std::uint32_t>(body.vertices.size());
  for (const Vec3& v : part.vertices) body.vertices.push_back(pose.R * v + pose.t);
  for (const auto& t : part.triangles) body.triangles.push_back({t[0] + base, t[1] + base, t[2] + base});
}

Pose read_pose(const TableReader& t, std::vector<std::string>& notes) {
  Pose p;
  p.t = t.vec3("position", Vec3::Zero(), "m");
  if (const auto q = t.quaternion("orientation", &notes)) p.R = q->toRotationMatrix();
  return p;
}

}  // namespace

BodyMass read_body_mass(const TableReader& body, const std::filesystem::path& directory, Scene& scene) {
  body.require_one_of({"shape", "mesh", "inertia", "parts"});
  const Material material = read_material(body, scene.warnings);
  if (!body.has("inertia") && body.has("center_of_mass")) {
    body.fail_at("center_of_mass", "center_of_mass goes with inertia; for shapes and meshes it is computed");
  }
  if (body.has("inertia")) return {explicit_inertia(body, material), "given mass and inertia", {}};
  if (!body.has("parts")) {
    if (material.kind == Material::Kind::none) {
      body.fail_here("missing the material: give density = RHO (kg/m^3) or mass = M (kg)");
    }
    BodyMass result;
    result.properties = solid(body, material, Pose{}, directory, result.source, result.display, scene);
    return result;
  }

  // A composite: parts placed in the body frame; holes subtract what their volume would have held.
  const auto parts = body.tables("parts");
  if (parts.empty()) body.fail_at("parts", "parts is empty: give at least one [[bodies.parts]]");
  MassProperties total;
  TriangleMesh display;       // the parts that are not holes, placed in the body frame
  std::vector<size_t> holes;  // their indices in `parts`
  for (size_t i = 0; i < parts.size(); ++i) {
    const TableReader part(*parts[i], body.context().child_numbered(" part ", i + 1), body.file(),
                           {"shape", "mesh", "scale", "thickness", "inertia", "center_of_mass", "density",
                            "mass", "position", "orientation", "hole"});
    part.require_one_of({"shape", "mesh", "inertia"});
    Material m = read_material(part, scene.warnings);
    if (m.kind != Material::Kind::none && material.kind == Material::Kind::mass) {
      part.fail_at(m.key,
                   "the body gives its total mass, so its parts cannot have their own density or "
                   "mass: remove one of them");
    }
    if (m.kind == Material::Kind::none && material.kind != Material::Kind::mass) {
      if (material.kind == Material::Kind::none && !part.has("inertia")) {
        part.fail_here("missing the material: give density or mass here, or density at the body");
      }
      m = material;  // the body's density (uniform or polynomial)
    }
    const Pose pose = read_pose(part, scene.warnings);
    std::string source;
    std::shared_ptr<const TriangleMesh> shown;
    const MassProperties mp = part.has("inertia") ? explicit_inertia(part, m)
                                                  : solid(part, m, pose, directory, source, shown, scene);
    const MassProperties placed = mp.transformed(pose.R, pose.t);
    if (shown && !part.boolean("hole").value_or(false))
      append_placed(display, *shown, pose);  // holes are not drawn
    if (part.boolean("hole").value_or(false)) {
      if (!(placed.mass < total.mass)) {
        part.fail_here(
            fmt::format("this hole would remove {:g} kg from the {:g} kg of the parts before it: a "
                        "hole must lie inside the parts it cuts, listed after them",
                        placed.mass, total.mass));
      }
      total -= placed;
      holes.push_back(i);
    } else {
      total += placed;
    }
  }
  if (!(total.mass > 0)) {
    body.fail_here(
        fmt::format("the parts minus the holes leave a mass of {:g} kg: holes must be smaller "
                    "than the parts they cut",
                    total.mass));
  }
  if (material.kind == Material::Kind::mass) {
    // Parts were integrated with unit density; scaling m and I by M/m keeps the centre of mass.
    const double f = material.value / total.mass;
    total.mass *= f;
    total.inertia *= f;
  }
  // Valid parts add up to a valid body; only holes can break it. Checked here, where the holes are
  // known, so that the message points at the hole (RigidBody would name the body a second time).
  try {
    total.validate();
  } catch (const InvalidMassProperties& e) {
    const std::string reason = fmt::format(
        "{}; a hole must lie inside the parts it cuts: check its size and "
        "position",
        e.what());
    if (holes.size() == 1) {
      const TableReader hole = TableReader::any_keys(
          *parts[holes[0]], body.context().child_numbered(" part ", holes[0] + 1), body.file());
      hole.fail_here("this hole leaves the body with mass properties no body can have: " + reason);
    }
    std::vector<size_t> numbers;
    for (size_t h : holes) numbers.push_back(h + 1);
    body.fail_here(
        fmt::format("the parts minus the holes (parts {}) leave mass properties no body can have: {}",
                    fmt::join(numbers, ", "), reason));
  }
  return {total,
          fmt::format("{} parts{}, {}", parts.size(),
                      holes.empty() ? "" : fmt::format(" ({} holes)", holes.size()),
                      material.kind == Material::Kind::none ? "materials per part" : material.describe()),
          std::make_shared<const TriangleMesh>(decimate(display, kDisplayTriangles))};
}

}  // namespace tumble::scene
