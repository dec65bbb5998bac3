// MJCF, MuJoCo's XML (https://mujoco.readthedocs.io/en/stable/XMLreference.html): <mujoco> holds a
// <worldbody> whose nested <body> elements are the links; each body is welded to its parent unless it
// has a <joint>. A body's mass is its <inertial>, or, when it has none, what MuJoCo's compiler infers
// from its geoms (each weighed by its mass or density, those in <compiler inertiagrouprange> only).
//
// What this reader follows of MuJoCo's compiler (src/user/user_objects.cc, src/xml/xml_native_reader.cc):
// frame orientations (quat, axisangle, euler with <compiler eulerseq>, xyaxes, zaxis; angles in degrees
// unless <compiler angle="radian">), <default> classes (class, childclass, nested inheritance), <frame>
// elements, geom sizes as half-sizes, fromto, mesh assets (meshdir, assetdir, strippath, scale, refpos,
// refquat). What it leaves to the user is said in model.notes and link.skipped.
#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <map>
#include <numbers>
#include <string>
#include <string_view>
#include <vector>

#include <fmt/format.h>

#include "readers.hpp"

namespace tumble::robot {

namespace {

/// Bodies and frames may nest this deep: far beyond any robot, and a bound on the work a hostile file
/// can ask for (the walk itself keeps its own stack, so depth cannot overflow the call stack).
constexpr int kMaxDepth = 1000;

/// MuJoCo's mjEPS: the smallest axis length its compiler accepts in an orientation.
constexpr double kMinAxis = 1e-14;

/// The <compiler> settings that change what the reader computes, with MuJoCo's defaults.
struct Compiler {
  bool degrees = true;           ///< angle="degree" (MuJoCo's default) or "radian"
  std::string eulerseq = "xyz";  ///< lowercase: rotating axes; uppercase: fixed axes
  std::string meshdir;           ///< from meshdir, else assetdir; relative to the model's directory
  bool strippath = false;
  int group_min = 0, group_max = 5;  ///< inertiagrouprange
};

// ---------------------------------------------------------------------------------------------------
// Small readers of attributes.

Pose compose(const Pose& outer, const Pose& inner) {
  return {outer.R * inner.R, outer.R * inner.p + outer.p};
}

Vec3 vec3(const std::vector<double>& v, std::size_t at = 0) { return Vec3(v[at], v[at + 1], v[at + 2]); }

bool has(const pugi::xml_node& element, const char* attribute) {
  return static_cast<bool>(element.attribute(attribute));
}

/// MuJoCo's booleans are the words "true" and "false".
bool boolean(const XmlSource& xml, const pugi::xml_node& element, const char* attribute, bool fallback) {
  const pugi::xml_attribute a = element.attribute(attribute);
  if (!a) return fallback;
  const std::string_view v = a.value();
  if (v == "true") return true;
  if (v == "false") return false;
  xml.fail(element, fmt::format("{}=\"{}\" must be \"true\" or \"false\"", attribute, v));
}

int integer(const XmlSource& xml, const pugi::xml_node& element, double x, const char* attribute) {
  if (x != std::floor(x) || std::abs(x) > 1e9) {
    xml.fail(element,
             fmt::format("{}=\"{}\" must be an integer", attribute, element.attribute(attribute).value()));
  }
  return static_cast<int>(x);
}

std::string quoted_name(const pugi::xml_node& element) {
  const std::string name = element.attribute("name").value();
  return name.empty() ? std::string() : fmt::format(" '{}'", name);
}

// ---------------------------------------------------------------------------------------------------
// Orientations (MuJoCo's ResolveOrientation, user_objects.cc).

constexpr std::array<const char*, 4> kAlternatives = {"axisangle", "xyaxes", "zaxis", "euler"};

bool has_alternative(const pugi::xml_node& element) {
  for (const char* a : kAlternatives)
    if (has(element, a)) return true;
  return false;
}

bool has_orientation(const pugi::xml_node& element) {
  return has(element, "quat") || has_alternative(element);
}

double radians(const Compiler& compiler, double angle) {
  return compiler.degrees ? angle / 180.0 * std::numbers::pi : angle;  // MuJoCo's order of operations
}

/// The minimal rotation taking (0, 0, 1) to `v` (MuJoCo's mjuu_z2quat): about z × v; about x by π for
/// v along −z.
Mat3 rotation_z_to(const Vec3& v) {
  const Vec3 d = v.normalized();
  Vec3 axis = Vec3::UnitZ().cross(d);
  const double s = axis.norm();
  axis = s < 1e-10 ? Vec3::UnitX() : Vec3(axis / s);
  const double angle = std::atan2(s, d.z());
  const double half = std::sin(angle / 2);
  return Quat(std::cos(angle / 2), half * axis.x(), half * axis.y(), half * axis.z())
      .normalized()
      .toRotationMatrix();
}

/// Euler angles composed as MuJoCo does: for each letter of the sequence, a rotation about that axis,
/// post-multiplied for a lowercase letter (rotating axes), pre-multiplied for an uppercase one (fixed).
Mat3 rotation_euler(const Compiler& compiler, const Vec3& angles) {
  Quat q = Quat::Identity();
  for (int i = 0; i < 3; ++i) {
    const char axis = compiler.eulerseq[static_cast<std::size_t>(i)];
    const double a = radians(compiler, angles[i]);
    Vec3 u = Vec3::Zero();
    u[axis == 'x' || axis == 'X' ? 0 : axis == 'y' || axis == 'Y' ? 1 : 2] = std::sin(a / 2);
    const Quat r(std::cos(a / 2), u.x(), u.y(), u.z());
    q = (axis >= 'a') ? Quat(q * r) : Quat(r * q);
  }
  return q.normalized().toRotationMatrix();
}

/// The rotation an element's own orientation attributes give (identity for none). MuJoCo refuses more
/// than one of quat, axisangle, xyaxes, zaxis and euler on an element.
Mat3 rotation_of(const XmlSource& xml, const Compiler& compiler, const pugi::xml_node& element) {
  std::vector<std::string> given;
  if (has(element, "quat")) given.emplace_back("quat");
  for (const char* a : kAlternatives)
    if (has(element, a)) given.emplace_back(a);
  if (given.size() > 1) {
    xml.fail(element,
             fmt::format("has both {} and {}: MuJoCo takes one orientation (quat, axisangle, xyaxes, "
                         "zaxis or euler)",
                         given[0], given[1]));
  }
  if (given.empty()) return Mat3::Identity();
  const std::string& kind = given[0];
  if (kind == "quat") {
    const std::vector<double> q = xml.numbers(element, "quat", 4);
    if (q[0] == 0 && q[1] == 0 && q[2] == 0 && q[3] == 0) {
      xml.fail(element, "quat=\"0 0 0 0\" is no rotation: give a non-zero quaternion (w x y z)");
    }
    return rotation_wxyz(q[0], q[1], q[2], q[3]);  // normalised, as MuJoCo does
  }
  if (kind == "axisangle") {
    const std::vector<double> v = xml.numbers(element, "axisangle", 4);
    const Vec3 axis = vec3(v);
    if (axis.norm() < kMinAxis)
      xml.fail(element, "axisangle has a zero axis: give \"x y z angle\" with a non-zero axis");
    const double half = radians(compiler, v[3]) / 2;
    const Vec3 u = axis.normalized() * std::sin(half);
    return Quat(std::cos(half), u.x(), u.y(), u.z()).normalized().toRotationMatrix();
  }
  if (kind == "xyaxes") {
    const std::vector<double> v = xml.numbers(element, "xyaxes", 6);
    Vec3 x = vec3(v), y = vec3(v, 3);
    if (x.norm() < kMinAxis) xml.fail(element, "xyaxes has a zero x axis");
    x.normalize();
    y -= x * x.dot(y);  // y made orthogonal to x, as MuJoCo does
    if (y.norm() < kMinAxis) xml.fail(element, "xyaxes has a y axis parallel to its x axis");
    y.normalize();
    Mat3 R;
    R << x, y, x.cross(y).normalized();
    return R;
  }
  if (kind == "zaxis") {
    const Vec3 z = vec3(xml.numbers(element, "zaxis", 3));
    if (z.norm() < kMinAxis) xml.fail(element, "zaxis=\"0 0 0\" is no direction");
    return rotation_z_to(z);
  }
  return rotation_euler(compiler, vec3(xml.numbers(element, "euler", 3)));
}

/// A body's, frame's or inertial's placement: pos and orientation, on the element itself.
Pose pose_of(const XmlSource& xml, const Compiler& compiler, const pugi::xml_node& element) {
  return {rotation_of(xml, compiler, element), vec3(xml.numbers(element, "pos", 3, {0, 0, 0}))};
}

// ---------------------------------------------------------------------------------------------------
// <compiler>.

Compiler read_compiler(const XmlSource& xml, const pugi::xml_node& mujoco, std::vector<std::string>& notes) {
  Compiler c;
  // MuJoCo applies each <compiler> in turn: a later one overrides an earlier one's attributes.
  for (const pugi::xml_node& e : mujoco.children("compiler")) {
    if (const pugi::xml_attribute a = e.attribute("angle")) {
      const std::string_view v = a.value();
      if (v != "degree" && v != "radian")
        xml.fail(e, fmt::format("angle=\"{}\" must be \"degree\" or \"radian\"", v));
      c.degrees = v == "degree";
    }
    if (const pugi::xml_attribute a = e.attribute("eulerseq")) {
      const std::string v = a.value();
      if (v.size() != 3 || v.find_first_not_of("xyzXYZ") != std::string::npos) {
        xml.fail(e, fmt::format("eulerseq=\"{}\" must be three letters of x, y, z (rotating axes) or X, Y, Z "
                                "(fixed axes), e.g. \"xyz\"",
                                v));
      }
      c.eulerseq = v;
    }
    // assetdir sets the mesh directory; meshdir, read after it, overrides it (xml_native_reader.cc).
    if (has(e, "assetdir")) c.meshdir = e.attribute("assetdir").value();
    if (has(e, "meshdir")) c.meshdir = e.attribute("meshdir").value();
    c.strippath = boolean(xml, e, "strippath", c.strippath);
    if (has(e, "inertiagrouprange")) {
      const std::vector<double> r = xml.numbers(e, "inertiagrouprange", 2);
      c.group_min = integer(xml, e, r[0], "inertiagrouprange");
      c.group_max = integer(xml, e, r[1], "inertiagrouprange");
    }
    const std::string where = xml.where(e);
    if (const pugi::xml_attribute a = e.attribute("inertiafromgeom")) {
      const std::string_view v = a.value();
      if (v == "true") {
        notes.push_back(
            fmt::format("{}: <compiler inertiafromgeom=\"true\">: MuJoCo ignores every <inertial> and "
                        "infers each body's mass from its geoms",
                        where));
      } else if (v == "false") {
        notes.push_back(
            fmt::format("{}: <compiler inertiafromgeom=\"false\">: MuJoCo gives a body without "
                        "<inertial> no mass, whatever its geoms",
                        where));
      } else if (v != "auto") {
        xml.fail(e, fmt::format("inertiafromgeom=\"{}\" must be \"true\", \"false\" or \"auto\"", v));
      }
    }
    if (xml.number(e, "settotalmass", -1.0) > 0) {
      notes.push_back(
          fmt::format("{}: <compiler settotalmass=\"{}\">: MuJoCo scales every mass and inertia so that "
                      "they sum to it; the inertials are read as written",
                      where, e.attribute("settotalmass").value()));
    }
    for (const char* bound : {"boundmass", "boundinertia"}) {
      if (xml.number(e, bound, 0.0) > 0) {
        notes.push_back(
            fmt::format("{}: <compiler {}=\"{}\">: MuJoCo raises smaller values to it; the inertials "
                        "are read as written",
                        where, bound, e.attribute(bound).value()));
      }
    }
    if (boolean(xml, e, "balanceinertia", false)) {
      notes.push_back(
          fmt::format("{}: <compiler balanceinertia=\"true\">: MuJoCo alters inertias that violate the "
                      "triangle inequality; the inertials are read as written",
                      where));
    }
    if (boolean(xml, e, "fusestatic", false)) {
      notes.push_back(
          fmt::format("{}: <compiler fusestatic=\"true\">: MuJoCo merges each body without joints into "
                      "its parent; each body is audited as written",
                      where));
    }
  }
  return c;
}

// ---------------------------------------------------------------------------------------------------
// <default> classes. A nested class starts as a copy of its parent (MuJoCo's mjs_addDefault), so an
// attribute comes from the element itself, else from its class, else from that class's parents, up to
// the top-level class "main".

class Defaults {
 public:
  Defaults(const XmlSource& xml, const pugi::xml_node& mujoco) {
    classes_.push_back({"main", -1, {}});
    index_["main"] = 0;
    struct Pending {
      pugi::xml_node element;
      int parent;  ///< -1: a top-level <default>, which is "main" itself
      int depth;
    };
    std::vector<Pending> stack;
    for (pugi::xml_node e = mujoco.last_child(); e; e = e.previous_sibling())
      if (std::string_view(e.name()) == "default") stack.push_back({e, -1, 1});
    while (!stack.empty()) {
      const Pending p = stack.back();
      stack.pop_back();
      if (p.depth > kMaxDepth)
        xml.fail(p.element, fmt::format("default classes nest deeper than {} levels", kMaxDepth));
      const std::string name = p.element.attribute("class").value();
      int index = 0;
      if (p.parent < 0) {
        if (!name.empty() && name != "main") {
          xml.fail(p.element,
                   fmt::format("a top-level <default> is the class \"main\" and cannot be named \"{}\": "
                               "nest <default class=\"{}\"> inside it",
                               name, name));
        }
      } else {
        if (name.empty()) xml.fail(p.element, "a nested <default> needs class=\"...\"");
        if (index_.count(name)) {
          xml.fail(p.element,
                   fmt::format("repeated default class \"{}\": MuJoCo requires unique class names", name));
        }
        index = static_cast<int>(classes_.size());
        classes_.push_back({name, p.parent, {}});
        index_[name] = index;
      }
      std::vector<pugi::xml_node> nested;
      for (const pugi::xml_node& child : p.element.children()) {
        const std::string_view kind = child.name();
        if (kind == "default") {
          nested.push_back(child);
        } else if (kind == "geom" || kind == "joint" || kind == "mesh") {
          // In file order: a later one wins (sources() reads them backwards).
          classes_[static_cast<std::size_t>(index)].elements[std::string(kind)].push_back(child);
        }
      }
      // Nested classes in file order off the stack, so that a repeated name is the later one.
      for (auto n = nested.rbegin(); n != nested.rend(); ++n) stack.push_back({*n, index, p.depth + 1});
    }
  }

  /// The class `element` names with class="...", else `inherited` (a childclass, or "main").
  int class_of(const XmlSource& xml, const pugi::xml_node& element, const char* attribute,
               int inherited) const {
    const pugi::xml_attribute a = element.attribute(attribute);
    if (!a) return inherited;
    const auto it = index_.find(a.value());
    if (it == index_.end())
      xml.fail(element, fmt::format("{}=\"{}\" names no <default> class", attribute, a.value()));
    return it->second;
  }

  /// Where a `kind` element of class `index` takes its attributes from, nearest first: the element, its
  /// class's <kind> defaults, then each parent class's.
  std::vector<pugi::xml_node> sources(const pugi::xml_node& element, int index,
                                      const std::string& kind) const {
    std::vector<pugi::xml_node> out{element};
    for (int i = index; i >= 0; i = classes_[static_cast<std::size_t>(i)].parent) {
      const auto& elements = classes_[static_cast<std::size_t>(i)].elements;
      const auto it = elements.find(kind);
      if (it != elements.end()) out.insert(out.end(), it->second.rbegin(), it->second.rend());
    }
    return out;
  }

  const std::string& name(int index) const { return classes_[static_cast<std::size_t>(index)].name; }

 private:
  struct Class {
    std::string name;
    int parent;
    std::map<std::string, std::vector<pugi::xml_node>> elements;  ///< "geom", "joint", "mesh"
  };
  std::vector<Class> classes_;
  std::map<std::string, int, std::less<>> index_;
};

/// The nearest of `sources` that has the attribute; an empty node when none has it.
pugi::xml_node first_with(const std::vector<pugi::xml_node>& sources, const char* attribute) {
  for (const pugi::xml_node& s : sources)
    if (has(s, attribute)) return s;
  return {};
}

// ---------------------------------------------------------------------------------------------------
// <asset><mesh>.

struct MeshAsset {
  std::string file;            ///< as written
  std::filesystem::path path;  ///< resolved
  Vec3 scale = Vec3::Ones();
  Pose reference;                  ///< refpos, refquat: the frame the vertices are given in
  std::string inertia = "legacy";  ///< MuJoCo's mesh inertia mode
  pugi::xml_node element;
};

/// MuJoCo's mjuu_strippath: the file name without its directories (either separator).
std::string strip_path(const std::string& file) {
  const std::size_t slash = file.find_last_of("/\\");
  return slash == std::string::npos ? file : file.substr(slash + 1);
}

/// An unnamed mesh is named by its file: without directories and extension (MuJoCo's mjCMesh::NameSpace).
std::string name_from_file(const std::string& file) {
  const std::string base = strip_path(file);
  const std::size_t dot = base.find_last_of('.');
  return dot == std::string::npos ? base : base.substr(0, dot);
}

std::map<std::string, MeshAsset> read_meshes(const XmlSource& xml, const pugi::xml_node& mujoco,
                                             const Compiler& compiler, const Defaults& defaults) {
  std::map<std::string, MeshAsset> meshes;
  const std::filesystem::path dir = xml.path().parent_path() / compiler.meshdir;
  for (const pugi::xml_node& asset : mujoco.children("asset")) {
    for (const pugi::xml_node& e : asset.children("mesh")) {
      MeshAsset m;
      m.element = e;
      m.file = e.attribute("file").value();
      std::string name = e.attribute("name").value();
      if (name.empty()) name = name_from_file(m.file);
      if (name.empty()) continue;  // vertices given inline and no name: no geom can use it
      if (meshes.count(name)) {
        xml.fail(e, fmt::format("repeated mesh name \"{}\" (also at line {}): MuJoCo requires unique names",
                                name, xml.line_of(meshes.at(name).element)));
      }
      if (!m.file.empty()) {
        // Relative to meshdir, itself relative to the model's directory; an absolute path stays
        // (std::filesystem's / keeps an absolute right-hand side, as MuJoCo's mjuu_combinePaths does).
        m.path = dir / (compiler.strippath ? strip_path(m.file) : m.file);
      }
      const std::vector<pugi::xml_node> sources =
          defaults.sources(e, defaults.class_of(xml, e, "class", 0), "mesh");
      if (const pugi::xml_node s = first_with(sources, "scale")) m.scale = vec3(xml.numbers(s, "scale", 3));
      if (const pugi::xml_node s = first_with(sources, "inertia")) m.inertia = s.attribute("inertia").value();
      m.reference.p = vec3(xml.numbers(e, "refpos", 3, {0, 0, 0}));
      if (has(e, "refquat")) {
        const std::vector<double> q = xml.numbers(e, "refquat", 4);
        if (q[0] == 0 && q[1] == 0 && q[2] == 0 && q[3] == 0)
          xml.fail(e, "refquat=\"0 0 0 0\" is no rotation");
        m.reference.R = rotation_wxyz(q[0], q[1], q[2], q[3]);
      }
      meshes.emplace(name, std::move(m));
    }
  }
  return meshes;
}

// ---------------------------------------------------------------------------------------------------
// Geoms.

/// How many size numbers each primitive reads (MuJoCo's mjGEOMINFO), and with fromto.
int sizes_needed(const std::string& type, bool fromto) {
  if (type == "sphere") return 1;
  if (type == "capsule" || type == "cylinder") return fromto ? 1 : 2;
  if (type == "ellipsoid" || type == "box") return fromto ? 1 : 3;
  return 0;
}

class GeomReader {
 public:
  GeomReader(const XmlSource& xml, const Compiler& compiler, const Defaults& defaults,
             const std::map<std::string, MeshAsset>& meshes, std::vector<std::string>& notes)
      : xml_(xml), compiler_(compiler), defaults_(defaults), meshes_(meshes), notes_(notes) {}

  /// A <geom> of a body whose enclosing frames are at `frame` in the body, in default class `inherited`:
  /// into the link's geometries when MuJoCo weighs it, into its skipped list when tumble cannot.
  void read(const pugi::xml_node& e, const Pose& frame, int inherited, Link& link) {
    const std::vector<pugi::xml_node> sources =
        defaults_.sources(e, defaults_.class_of(xml_, e, "class", inherited), "geom");
    const auto attribute = [&](const char* name) { return first_with(sources, name); };

    // MuJoCo weighs the geoms whose group is in inertiagrouprange (mjCBody::InertiaFromGeom).
    int group = 0;
    if (const pugi::xml_node s = attribute("group"))
      group = integer(xml_, s, xml_.number(s, "group"), "group");
    if (group < compiler_.group_min || group > compiler_.group_max) return;

    Geometry g;
    g.name = e.attribute("name").value();
    g.element = "geom";
    g.line = xml_.line_of(e);
    const pugi::xml_node type_source = attribute("type");
    const std::string type = type_source ? type_source.attribute("type").value() : "sphere";
    const std::string label = fmt::format("geom{} ({}) at line {}", quoted_name(e), type, g.line);
    const auto skip = [&](const std::string& why) {
      link.skipped.push_back(fmt::format("{}: {}", label, why));
    };

    if (type == "plane") return skip("MuJoCo gives planes no mass");
    if (type == "hfield") {
      return skip(
          "a height field: tumble does not weigh height fields (MuJoCo weighs one as a box of its extent)");
    }
    if (type == "sdf") return skip("a signed distance field from a plugin: tumble cannot weigh it");
    if (sizes_needed(type, false) == 0 && type != "mesh") {
      return skip(
          fmt::format("type=\"{}\" is not a geom type tumble knows (sphere, capsule, cylinder, ellipsoid, "
                      "box, mesh)",
                      type));
    }

    // A given mass wins over the density; zero of either weighs nothing (mjCGeom::Compile).
    if (const pugi::xml_node s = attribute("mass")) {
      g.mass = xml_.number(s, "mass");
      if (*g.mass < 0)
        xml_.fail(s, fmt::format("mass=\"{}\" is negative: a geom's mass is 0 or more",
                                 s.attribute("mass").value()));
      if (*g.mass == 0) return skip("mass=\"0\": MuJoCo gives it no mass");
    }
    g.density = 1000.0;
    if (const pugi::xml_node s = attribute("density")) {
      g.density = xml_.number(s, "density");
      if (*g.density < 0)
        xml_.fail(s, fmt::format("density=\"{}\" is negative: a geom's density is 0 or more",
                                 s.attribute("density").value()));
      if (*g.density == 0 && !g.mass) return skip("density=\"0\": MuJoCo gives it no mass");
    }
    if (const pugi::xml_node s = attribute("shellinertia"); s && boolean(xml_, s, "shellinertia", false)) {
      return skip("shellinertia=\"true\": MuJoCo weighs its surface as a shell; tumble weighs solids");
    }

    const pugi::xml_node mesh_source = attribute("mesh");
    const std::string mesh = mesh_source ? mesh_source.attribute("mesh").value() : "";
    if (type != "mesh" && !mesh.empty()) {
      return skip(
          fmt::format("a {} fitted to mesh '{}': MuJoCo sizes it from the mesh; tumble does not fit "
                      "primitives to meshes",
                      type, mesh));
    }

    const pugi::xml_node fromto = attribute("fromto");
    if (fromto) {
      g.pose = from_to(e, fromto, type, attribute("pos"));
    } else {
      const pugi::xml_node pos = attribute("pos");
      g.pose.p = pos ? vec3(xml_.numbers(pos, "pos", 3)) : Vec3::Zero();
      g.pose.R = rotation_of(xml_, compiler_, orientation_source(e, sources));
    }
    g.pose = compose(frame, g.pose);

    if (type == "mesh") {
      if (!read_mesh(e, mesh, g, skip)) return;
    } else {
      g.shape = shape(e, type, sources, fromto);
    }
    link.collision.push_back(std::move(g));
  }

 private:
  /// The element whose attributes give the geom's orientation. MuJoCo copies a class's orientation into
  /// the geom and reads the geom's own after it, but an alternative (axisangle, xyaxes, zaxis, euler)
  /// from anywhere in the chain wins over any quat (ResolveOrientation runs unless the alternative is
  /// "quat"): so a class's euler overrides a geom's own quat, which the notes point out.
  pugi::xml_node orientation_source(const pugi::xml_node& e, const std::vector<pugi::xml_node>& sources) {
    pugi::xml_node alternative, quat;
    for (const pugi::xml_node& s : sources) {
      if (!alternative && has_alternative(s)) alternative = s;
      if (!quat && has(s, "quat")) quat = s;
    }
    if (alternative && quat && alternative != e && quat == e) {
      notes_.push_back(
          fmt::format("{}: the geom's quat is overridden by the orientation of its default class at "
                      "line {}, as MuJoCo does: give the geom the same kind of orientation to override "
                      "it",
                      xml_.where(e), xml_.line_of(alternative)));
    }
    return alternative ? alternative : quat;  // an empty node: the identity
  }

  /// fromto="x1 y1 z1 x2 y2 z2" (on the geom `e` or its class `s`): centred between the points, z along
  /// the segment (mjCGeom::Compile).
  Pose from_to(const pugi::xml_node& e, const pugi::xml_node& s, const std::string& type,
               const pugi::xml_node& pos) {
    if (type != "capsule" && type != "cylinder" && type != "box" && type != "ellipsoid") {
      xml_.fail(e, fmt::format("fromto is for capsule, cylinder, box and ellipsoid geoms, not {}", type));
    }
    // MuJoCo refuses a non-zero pos beside fromto, even one from the default class.
    if (pos && !vec3(xml_.numbers(pos, "pos", 3)).isZero(0.0)) {
      xml_.fail(e, fmt::format(
                       "has both pos{} and fromto: fromto places the geom; remove pos",
                       pos == e ? "" : fmt::format(" (from its default class, line {})", xml_.line_of(pos))));
    }
    const std::vector<double> v = xml_.numbers(s, "fromto", 6);
    const Vec3 a = vec3(v), b = vec3(v, 3);
    // MuJoCo turns z towards a − b (not b − a as its documentation says): the same for these symmetric
    // shapes, kept so that the pose is MuJoCo's.
    const Vec3 d = a - b;
    if (d.norm() < kMinAxis) xml_.fail(s, "fromto's two points coincide: the geom has no length");
    return {rotation_z_to(d), (a + b) / 2};
  }

  /// The geom's size numbers: MuJoCo reads a partial size over its class's (size="0.1" keeps the
  /// class's second and third numbers), so the chain is applied from "main" inwards.
  std::vector<double> sizes(const std::vector<pugi::xml_node>& sources) {
    std::vector<double> size;
    for (auto s = sources.rbegin(); s != sources.rend(); ++s) {
      if (!has(*s, "size")) continue;
      const std::vector<double> given = xml_.all_numbers(*s, "size");
      if (given.size() > 3) {
        xml_.fail(*s, fmt::format("size=\"{}\" has {} numbers; a geom has at most 3",
                                  s->attribute("size").value(), given.size()));
      }
      if (size.size() < given.size()) size.resize(given.size());
      std::copy(given.begin(), given.end(), size.begin());
    }
    return size;
  }

  Shape shape(const pugi::xml_node& e, const std::string& type, const std::vector<pugi::xml_node>& sources,
              const pugi::xml_node& fromto) {
    const std::vector<double> s = sizes(sources);
    const int needed = sizes_needed(type, static_cast<bool>(fromto));
    static const std::map<std::string, std::string, std::less<>> meaning = {
        {"sphere", "radius"},
        {"capsule", "radius, half-length"},
        {"cylinder", "radius, half-length"},
        {"ellipsoid", "three semi-axes"},
        {"box", "three half-sizes"}};
    if (s.size() < static_cast<std::size_t>(needed)) {
      xml_.fail(
          e,
          fmt::format("a {} needs size=\"...\" with {} ({}), from the geom or its default class; it has {}",
                      type, needed, fromto ? "radius; fromto gives the length" : meaning.at(type), s.size()));
    }
    for (int i = 0; i < needed; ++i) {
      if (!(s[static_cast<std::size_t>(i)] > 0)) {
        xml_.fail(e, fmt::format("size number {} of the {} is {}: it must be positive", i + 1, type,
                                 s[static_cast<std::size_t>(i)]));
      }
    }
    if (fromto) {
      // The segment's length is the geom's full length along z; the radius is size[0] across.
      const std::vector<double> v = xml_.numbers(fromto, "fromto", 6);
      const double length = (vec3(v) - vec3(v, 3)).norm();
      if (type == "capsule") return Capsule{s[0], length};
      if (type == "cylinder") return Cylinder{s[0], length};
      if (type == "box") return Box{Vec3(2 * s[0], 2 * s[0], length)};
      return Ellipsoid{Vec3(s[0], s[0], length / 2)};
    }
    // MJCF sizes are half-sizes: a capsule's and a cylinder's second number is half the length of the
    // cylindrical part, a box's numbers are half its edges.
    if (type == "sphere") return Sphere{s[0]};
    if (type == "capsule") return Capsule{s[0], 2 * s[1]};
    if (type == "cylinder") return Cylinder{s[0], 2 * s[1]};
    if (type == "ellipsoid") return Ellipsoid{Vec3(s[0], s[1], s[2])};
    return Box{Vec3(2 * s[0], 2 * s[1], 2 * s[2])};
  }

  /// A mesh geom's file, scale and pose; false when tumble cannot place it (with a line in skipped).
  template <class Skip>
  bool read_mesh(const pugi::xml_node& e, const std::string& name, Geometry& g, const Skip& skip) {
    if (name.empty()) xml_.fail(e, "a mesh geom needs mesh=\"...\" (the name of an <asset><mesh>)");
    const auto it = meshes_.find(name);
    if (it == meshes_.end()) {
      xml_.fail(e,
                fmt::format("mesh=\"{}\" names no <asset><mesh> (an unnamed mesh is named by its file name "
                            "without extension)",
                            name));
    }
    const MeshAsset& m = it->second;
    if (m.file.empty()) {
      skip(fmt::format("mesh '{}' gives its vertices inline, not in a file: tumble reads mesh files", name));
      return false;
    }
    if (m.inertia == "shell") {
      skip(fmt::format("mesh '{}' has inertia=\"shell\": MuJoCo weighs its surface; tumble weighs solids",
                       name));
      return false;
    }
    if (m.inertia == "convex") {
      notes_.push_back(
          fmt::format("{}: mesh '{}' has inertia=\"convex\": MuJoCo weighs its convex hull; tumble "
                      "weighs the mesh itself",
                      xml_.where(e), name));
    }
    // MuJoCo moves the vertices into the mesh's reference frame, then scales them: v' = S Rᵀ (v − p)
    // (mjCMesh::ApplyTransformations). As a pose before the scale that needs R = I or a uniform scale.
    const Pose& ref = m.reference;
    const bool uniform = m.scale.x() == m.scale.y() && m.scale.y() == m.scale.z();
    if (!ref.R.isIdentity(0.0) && !uniform) {
      skip(fmt::format("mesh '{}' has refquat and a non-uniform scale: tumble cannot place it", name));
      return false;
    }
    if (!ref.R.isIdentity(0.0) || !ref.p.isZero(0.0)) {
      const Mat3 Rt = ref.R.transpose();
      g.pose = compose(g.pose, Pose{Rt, -(Rt * m.scale.cwiseProduct(ref.p))});
    }
    g.mesh_uri = m.file;
    g.mesh_path = m.path;
    g.scale = m.scale;
    return true;
  }

  const XmlSource& xml_;
  const Compiler& compiler_;
  const Defaults& defaults_;
  const std::map<std::string, MeshAsset>& meshes_;
  std::vector<std::string>& notes_;
};

// ---------------------------------------------------------------------------------------------------
// Inertials.

/// <inertial pos mass diaginertia|fullinertia [orientation]> (MuJoCo requires pos and mass).
Inertial read_inertial(const XmlSource& xml, const Compiler& compiler, const pugi::xml_node& e,
                       std::vector<std::string>& notes) {
  Inertial in;
  in.span = xml.span_of(e);
  if (!has(e, "pos"))
    xml.fail(e, "needs pos=\"x y z\" (the centre of mass in the body's frame; MuJoCo requires it)");
  if (!has(e, "mass")) xml.fail(e, "needs mass=\"...\" (MuJoCo requires it)");
  in.mass = xml.number(e, "mass");
  in.mass_text = e.attribute("mass").value();
  const bool diagonal = has(e, "diaginertia"), full = has(e, "fullinertia");
  if (diagonal == full) {
    xml.fail(e, diagonal ? "has both diaginertia and fullinertia: give one"
                         : "needs diaginertia=\"ixx iyy izz\" or fullinertia=\"ixx iyy izz ixy ixz iyz\"");
  }
  in.frame.p = vec3(xml.numbers(e, "pos", 3));
  if (full) {
    // MuJoCo diagonalises fullinertia itself, in the body's axes: it refuses an alternative orientation
    // and overwrites a quat (mjCBody::Compile).
    if (has_alternative(e)) {
      xml.fail(e,
               "has fullinertia and an orientation: fullinertia is in the body's axes (MuJoCo refuses both)");
    }
    if (has(e, "quat")) {
      notes.push_back(
          fmt::format("{}: <inertial> has fullinertia and quat: MuJoCo ignores the quat (fullinertia is "
                      "in the body's axes)",
                      xml.where(e)));
    }
    const std::vector<double> I = xml.numbers(e, "fullinertia", 6);
    in.inertia_written << I[0], I[3], I[4],  //
        I[3], I[1], I[5],                    //
        I[4], I[5], I[2];
    return in;
  }
  in.frame.R = rotation_of(xml, compiler, e);
  in.rotated = has_orientation(e) && !in.frame.R.isIdentity(0.0);
  const std::vector<double> d = xml.numbers(e, "diaginertia", 3);
  in.inertia_written = Vec3(d[0], d[1], d[2]).asDiagonal();
  return in;
}

// ---------------------------------------------------------------------------------------------------
// The body tree.

/// Elements whose expansion this reader does not do: what they would add is not read.
bool unexpanded(std::string_view kind) {
  return kind == "replicate" || kind == "attach" || kind == "composite" || kind == "flexcomp";
}

class BodyWalker {
 public:
  BodyWalker(const XmlSource& xml, const Compiler& compiler, const Defaults& defaults, GeomReader& geoms,
             RobotModel& model)
      : xml_(xml), compiler_(compiler), defaults_(defaults), geoms_(geoms), model_(model) {}

  /// Each element in file order, depth first, on an explicit stack: a body makes its link and joint
  /// before its children are read, so links come parent first, in file order.
  void walk(const pugi::xml_node& worldbody) {
    push_children(worldbody, -1, Pose{}, 0, 1);
    while (!stack_.empty()) {
      const Item item = stack_.back();
      stack_.pop_back();
      const std::string_view kind = item.element.name();
      if (kind == "body") {
        body(item);
      } else if (kind == "frame") {
        if (item.depth > kMaxDepth)
          xml_.fail(item.element, fmt::format("bodies and frames nest deeper than {} levels", kMaxDepth));
        const Pose pose = compose(item.frame, pose_of(xml_, compiler_, item.element));
        push_children(item.element, item.link, pose,
                      defaults_.class_of(xml_, item.element, "childclass", item.cls), item.depth + 1);
      } else if (kind == "geom") {
        // Geoms of the world body are static scenery: no link's mass.
        if (item.link >= 0) geoms_.read(item.element, item.frame, item.cls, link(item.link));
      } else if (kind == "joint" || kind == "freejoint") {
        joint(item);
      } else if (kind == "inertial") {
        inertial(item);
      } else if (unexpanded(kind)) {
        model_.notes.push_back(
            fmt::format("{}: <{}> is not expanded: the bodies and geoms it would add are not read",
                        xml_.where(item.element), kind));
      }
    }
  }

 private:
  struct Item {
    pugi::xml_node element;
    int link;    ///< index in model.links of the body it belongs to; -1: the world body
    Pose frame;  ///< the enclosing <frame>s' pose in that body's frame
    int cls;     ///< the default class in effect (the nearest childclass, or "main")
    int depth;
  };

  void push_children(const pugi::xml_node& parent, int link, const Pose& frame, int cls, int depth) {
    for (pugi::xml_node e = parent.last_child(); e; e = e.previous_sibling())
      if (e.type() == pugi::node_element) stack_.push_back({e, link, frame, cls, depth});
  }

  Link& link(int index) { return model_.links[static_cast<std::size_t>(index)]; }

  void body(const Item& item) {
    const pugi::xml_node& e = item.element;
    if (item.depth > kMaxDepth)
      xml_.fail(e, fmt::format("bodies and frames nest deeper than {} levels", kMaxDepth));
    const int index = static_cast<int>(model_.links.size());
    Link l;
    l.name = e.attribute("name").value();
    l.line = xml_.line_of(e);
    // An unnamed body is named by its MuJoCo body id: its place in file order, the world being body 0.
    const bool generated = l.name.empty();
    if (generated) l.name = fmt::format("body#{}", index + 1);
    check_unique(e, l.name, generated);
    Joint j;
    j.type = "fixed";  // MuJoCo welds a body without joints to its parent
    j.parent = item.link < 0 ? std::string("world") : link(item.link).name;
    j.child = l.name;
    j.origin = compose(item.frame, pose_of(xml_, compiler_, e));
    j.line = l.line;
    model_.links.push_back(std::move(l));
    model_.joints.push_back(std::move(j));
    has_joint_.push_back(false);
    push_children(e, index, Pose{}, defaults_.class_of(xml_, e, "childclass", item.cls), item.depth + 1);
  }

  void check_unique(const pugi::xml_node& e, const std::string& name, bool generated) {
    if (name == "world") xml_.fail(e, "a body cannot be named \"world\": that is MuJoCo's world body");
    const auto [it, inserted] = names_.emplace(name, std::make_pair(xml_.line_of(e), generated));
    if (inserted) return;
    const auto& [line, earlier_generated] = it->second;
    if (!generated && !earlier_generated) {
      xml_.fail(e, fmt::format("repeated body name \"{}\" (also at line {}): MuJoCo requires unique names",
                               name, line));
    }
    xml_.fail(
        e, fmt::format("the name \"{}\" is both a body's name and the one tumble gives the unnamed body at "
                       "line {}: name the unnamed body",
                       name, generated ? xml_.line_of(e) : line));
  }

  /// The body's joint takes the type and name of its first <joint> (MuJoCo's default type "hinge",
  /// through the default classes) or <freejoint>.
  void joint(const Item& item) {
    if (item.link < 0) xml_.fail(item.element, "the world body cannot have joints: put it in a <body>");
    if (has_joint_[static_cast<std::size_t>(item.link)]) return;
    has_joint_[static_cast<std::size_t>(item.link)] = true;
    Joint& j = model_.joints[static_cast<std::size_t>(item.link)];
    j.name = item.element.attribute("name").value();
    if (std::string_view(item.element.name()) == "freejoint") {
      j.type = "free";  // a freejoint takes no defaults
      return;
    }
    const std::vector<pugi::xml_node> sources =
        defaults_.sources(item.element, defaults_.class_of(xml_, item.element, "class", item.cls), "joint");
    const pugi::xml_node s = first_with(sources, "type");
    j.type = s ? s.attribute("type").value() : "hinge";
    if (j.type != "hinge" && j.type != "slide" && j.type != "ball" && j.type != "free") {
      xml_.fail(s, fmt::format("type=\"{}\" is not a MuJoCo joint type (hinge, slide, ball, free)", j.type));
    }
  }

  void inertial(const Item& item) {
    if (item.link < 0) xml_.fail(item.element, "the world body cannot have an <inertial>");
    Link& l = link(item.link);
    if (l.inertial) {
      xml_.fail(item.element,
                fmt::format("body '{}' has a second <inertial> (the first at line {}): give one", l.name,
                            l.inertial->span.line));
    }
    if (std::string_view(item.element.parent().name()) == "frame") {
      model_.notes.push_back(
          fmt::format("{}: an <inertial> inside a <frame>: MuJoCo places it in the body's frame, "
                      "not the <frame>'s; so does tumble",
                      xml_.where(item.element)));
    }
    l.inertial = read_inertial(xml_, compiler_, item.element, model_.notes);
  }

  const XmlSource& xml_;
  const Compiler& compiler_;
  const Defaults& defaults_;
  GeomReader& geoms_;
  RobotModel& model_;
  std::vector<Item> stack_;
  std::vector<bool> has_joint_;                        ///< per link: its first joint has been read
  std::map<std::string, std::pair<int, bool>> names_;  ///< body name → line, whether tumble made it
};

/// <include file="..."> anywhere: MuJoCo splices the file in; this reader does not.
void note_includes(const XmlSource& xml, const pugi::xml_node& mujoco, std::vector<std::string>& notes) {
  std::vector<pugi::xml_node> stack{mujoco};
  while (!stack.empty()) {
    const pugi::xml_node n = stack.back();
    stack.pop_back();
    for (pugi::xml_node c = n.last_child(); c; c = c.previous_sibling()) {
      if (c.type() != pugi::node_element) continue;
      if (std::string_view(c.name()) == "include") {
        notes.push_back(
            fmt::format("{}: <include file=\"{}\"> is not followed: the included file is not read",
                        xml.where(c), c.attribute("file").value()));
      } else {
        stack.push_back(c);
      }
    }
  }
}

}  // namespace

void read_mjcf(const XmlSource& xml, const pugi::xml_node& mujoco, RobotModel& model) {
  model.name = mujoco.attribute("model").value();
  note_includes(xml, mujoco, model.notes);
  const Compiler compiler = read_compiler(xml, mujoco, model.notes);
  const Defaults defaults(xml, mujoco);
  const std::map<std::string, MeshAsset> meshes = read_meshes(xml, mujoco, compiler, defaults);
  GeomReader geoms(xml, compiler, defaults, meshes, model.notes);
  BodyWalker walker(xml, compiler, defaults, geoms, model);
  for (const pugi::xml_node& worldbody : mujoco.children("worldbody")) walker.walk(worldbody);
}

}  // namespace tumble::robot
