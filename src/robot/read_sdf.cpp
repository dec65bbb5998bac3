// SDFormat (http://sdformat.org/spec, versions 1.4 to 1.11): <sdf> holds a <model> or a <world> of
// models; a model holds <link>s (each with an optional <inertial> and any number of <collision> and
// <visual> geometries), <joint>s, <frame>s and nested <model>s. Values are element text
// (<radius>0.1</radius>), poses are "x y z roll pitch yaw" (R = Rz Ry Rx, radians unless degrees="true")
// or "x y z qx qy qz qw" (rotation_format="quat_xyzw").
//
// Frames (http://sdformat.org/tutorials?tut=pose_frame_semantics): every link, joint, frame and nested
// model of a model is a frame named in the model's scope, posed relative to another frame of that scope
// — its pose's relative_to, else by default the model frame (links, nested models), the frame it is
// attached_to (frames) or its child link (joints). A name "inner::x" reaches into nested model `inner`.
// The reader resolves these lazily, once each, walking each chain iteratively (a converted URDF chains
// every link to its parent joint and every joint to its parent link), so that only the hops between
// scopes recurse, and those are bounded.
//
// Names: a link or joint of a nested model is named as its enclosing top-level model scopes it
// ("inner::link"), which is also how that model's joints name it. A file of several top-level models
// (a world) prefixes every name with its model's ("arm::link") so that names stay unique.
#include <cmath>
#include <map>
#include <memory>
#include <numbers>
#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <fmt/format.h>

#include "readers.hpp"

namespace tumble::robot {

namespace {

namespace fs = std::filesystem;

/// Nested <model>s deeper than this are refused: no real robot needs it, and it bounds the recursion.
constexpr int max_model_depth = 32;
/// Resolving a frame may step into a nested model's scope (a "::" name, a placement frame, a canonical
/// link); a chain of more such steps than this is refused rather than followed down the stack.
constexpr int max_scope_steps = 64;

Pose compose(const Pose& a, const Pose& b) { return {a.R * b.R, a.R * b.p + a.p}; }
Pose inverse(const Pose& a) { return {a.R.transpose(), -(a.R.transpose() * a.p)}; }

std::string trimmed(std::string_view s) {
  const auto space = [](char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r'; };
  while (!s.empty() && space(s.front())) s.remove_prefix(1);
  while (!s.empty() && space(s.back())) s.remove_suffix(1);
  return std::string(s);
}

/// An element's text, trimmed ("" when the element is absent).
std::string text_of(const pugi::xml_node& element) { return trimmed(element.child_value()); }

/// An SDFormat bool: "true" or "1", "false" or "0", in any case (libsdformat's reading); none otherwise.
std::optional<bool> parse_bool(std::string v) {
  for (char& c : v) c = (c >= 'A' && c <= 'Z') ? static_cast<char>(c - 'A' + 'a') : c;
  if (v == "true" || v == "1") return true;
  if (v == "false" || v == "0") return false;
  return std::nullopt;
}

bool bool_attribute(const XmlSource& xml, const pugi::xml_node& element, const char* name, bool fallback) {
  const pugi::xml_attribute a = element.attribute(name);
  if (!a) return fallback;
  if (const std::optional<bool> b = parse_bool(trimmed(a.value()))) return *b;
  xml.fail(element, fmt::format("{}=\"{}\" is not a bool: write true or false", name, a.value()));
}

/// One number from a required child element's text (<radius>0.1</radius>).
double child_number(const XmlSource& xml, const pugi::xml_node& parent, const char* child) {
  const pugi::xml_node c = parent.child(child);
  if (!c) xml.fail(parent, fmt::format("needs <{0}>...</{0}> (a number)", child));
  return xml.text_numbers(c, 1)[0];
}

/// A 3-vector from a child element's text; `fallback` when the element is absent, required if none.
Vec3 child_vector(const XmlSource& xml, const pugi::xml_node& parent, const char* child,
                  const std::optional<Vec3>& fallback = std::nullopt) {
  const pugi::xml_node c = parent.child(child);
  if (!c) {
    if (fallback) return *fallback;
    xml.fail(parent, fmt::format("needs <{0}>x y z</{0}> (3 numbers)", child));
  }
  const std::vector<double> v = xml.text_numbers(c, 3);
  return {v[0], v[1], v[2]};
}

/// The frame an element's <pose> is written relative to: relative_to (SDFormat 1.7+), else frame
/// (1.5 and 1.6, which libsdformat converts to relative_to); "" when neither is given.
std::string relative_to_of(const pugi::xml_node& pose) {
  if (const pugi::xml_attribute a = pose.attribute("relative_to")) return trimmed(a.value());
  return trimmed(pose.attribute("frame").value());
}

/// An element's own <pose> as written (the identity when it has none), without its relative_to.
Pose pose_of(const XmlSource& xml, const pugi::xml_node& parent) {
  const pugi::xml_node e = parent.child("pose");
  if (!e) return {};
  const std::string format = e.attribute("rotation_format") ? trimmed(e.attribute("rotation_format").value())
                                                            : "euler_rpy";
  const bool quaternion = format == "quat_xyzw";
  if (!quaternion && format != "euler_rpy") {
    xml.fail(e,
             fmt::format("rotation_format=\"{}\" is not one SDFormat has: write euler_rpy (x y z roll pitch "
                         "yaw) or quat_xyzw (x y z qx qy qz qw)",
                         format));
  }
  const bool degrees = bool_attribute(xml, e, "degrees", false);
  if (quaternion && degrees) xml.fail(e, "degrees=\"true\" does not apply to rotation_format=\"quat_xyzw\"");
  // An empty <pose/> is the identity (libsdformat reads it so).
  if (text_of(e).empty()) return {};
  const std::vector<double> v = xml.text_numbers(e, quaternion ? 7 : 6);
  Pose pose;
  pose.p = Vec3(v[0], v[1], v[2]);
  if (quaternion) {
    // Normalised (rotation_wxyz), as the file's quaternion may be rounded; scaled by its largest
    // component first, so that neither tiny nor huge components under- or overflow on the way.
    const double largest = Eigen::Vector4d(v[3], v[4], v[5], v[6]).cwiseAbs().maxCoeff();
    if (largest == 0.0)
      xml.fail(e, "the quaternion qx qy qz qw is 0 0 0 0: it is no rotation (the identity is 0 0 0 1)");
    pose.R = rotation_wxyz(v[6] / largest, v[3] / largest, v[4] / largest, v[5] / largest);
  } else {
    const double unit = degrees ? std::numbers::pi / 180.0 : 1.0;
    pose.R = rotation_rpy(Vec3(v[3], v[4], v[5]) * unit);
  }
  return pose;
}

/// A mesh URI resolved to a file where that needs nothing but this file's place: a plain path
/// (relative ones against the SDF file's directory, as Gazebo resolves them) or file://. Empty for
/// model://, package:// and other schemes, which need the package paths (resolve_mesh).
fs::path mesh_file(const XmlSource& xml, const std::string& uri) {
  std::string path = uri;
  if (uri.rfind("file://", 0) == 0) {
    path = uri.substr(7);
  } else if (uri.find("://") != std::string::npos) {
    return {};
  }
  if (path.empty()) return {};
  const fs::path p(path);
  return p.is_relative() ? xml.path().parent_path() / p : p;
}

enum class Kind { link, joint, frame, model, include };

const char* kind_name(Kind kind) {
  switch (kind) {
    case Kind::link:
      return "link";
    case Kind::joint:
      return "joint";
    case Kind::frame:
      return "frame";
    case Kind::model:
      return "model";
    case Kind::include:
      return "include";
  }
  return "?";
}

/// A named element of a scope: a frame that poses can be written relative to.
struct Entry {
  Kind kind;
  pugi::xml_node node;
};

/// A model's (or a world's) names and the poses of its frames in its own frame (the model frame,
/// "__model__"; a world's: "world"), resolved on demand.
struct Scope {
  pugi::xml_node element;   ///< <model>, <world>
  Scope* parent = nullptr;  ///< the enclosing model or world, when its pose there matters
  std::string name;         ///< the model's name ("" for a world)
  std::string path;         ///< its scoped name, for messages: "outer::inner"
  std::string root;         ///< "__model__" or "world"
  std::string prefix;       ///< of the names this scope's links and joints get in the RobotModel
  std::map<std::string, std::vector<Entry>> entries;
  std::map<std::string, std::unique_ptr<Scope>> models;  ///< nested models, by name
  std::map<pugi::xml_node, Pose> poses;                  ///< resolved frames, in this scope's frame
  std::set<pugi::xml_node> resolving;                    ///< frames on a chain being resolved
  bool includes = false;                                 ///< it has <include>s, unread

  std::string label() const { return root == "world" ? "the world" : fmt::format("model '{}'", path); }
  /// Where a name reaches into a nested model ("inner::x"), or npos: a name without "::", or one that
  /// names an element of this scope as it stands (SDFormat 1.7 flattened nested models into names
  /// such as "inner::x", and `gz sdf -p` still writes them so).
  std::size_t scoped_at(const std::string& frame) const {
    return entries.count(frame) ? std::string::npos : frame.find("::");
  }
  bool is_root(const std::string& frame) const {
    // The model's own name is taken as its frame only when nothing in it has that name.
    return frame.empty() || frame == root || (root != "world" && frame == name && !entries.count(frame));
  }
};

/// A reference to a frame by name: the name, the element that wrote it (for messages) and how.
struct Ref {
  std::string name;
  pugi::xml_node at;
  std::string how;  ///< "relative_to=\"x\"", "<child>x</child>", ...
};

/// Where a link went in the RobotModel.
struct LinkRecord {
  Scope* scope;
  std::string name;  ///< as in the RobotModel (prefixed)
};

class SdfReader {
 public:
  SdfReader(const XmlSource& xml, RobotModel& model) : xml_(xml), model_(model) {}

  void read(const pugi::xml_node& sdf) {
    std::vector<pugi::xml_node> top;  // the top-level models, under <sdf> or a <world>
    bool includes = false;
    for (const pugi::xml_node& e : sdf.children()) {
      const std::string_view n = e.name();
      if (n == "model") top.push_back(e);
      if (n == "world") {
        for (const pugi::xml_node& m : e.children("model")) top.push_back(m);
        includes = includes || e.child("include");
      }
    }
    if (top.empty()) {
      xml_.fail(sdf, includes
                         ? "holds no <model> but <include>s, which tumble does not read (it reads one file): "
                           "expand them first (`gz sdf -p FILE` prints the file with its includes expanded)"
                         : "holds no <model> (nor a <world> with models): there is no robot to read");
    }
    model_.name = trimmed(top.front().attribute("name").value());
    // Several models: each name is prefixed with its model's, so that two models' "base_link" stay apart.
    const bool prefixed = top.size() > 1;
    // Every scope and every link's name first: a joint may name a link that comes after it.
    for (const pugi::xml_node& e : sdf.children()) {
      const std::string_view n = e.name();
      // A model directly under <sdf> is placed by whoever includes it: its pose is not part of the robot.
      if (n == "model") roots_.push_back(build(e, nullptr, 0, prefixed));
      if (n == "world") roots_.push_back(build_world(e, prefixed));
    }
    for (const auto& s : roots_) register_links(*s);
    for (const auto& s : roots_) read_scope(*s);
  }

 private:
  const XmlSource& xml_;
  RobotModel& model_;
  std::vector<std::unique_ptr<Scope>> roots_;
  std::map<pugi::xml_node, LinkRecord> links_;
  std::map<std::string, pugi::xml_node> link_names_;
  std::map<pugi::xml_node, pugi::xml_node> attached_;  ///< frames and joints: the link each is attached to

  std::string required_name(const pugi::xml_node& e) const {
    std::string name = trimmed(e.attribute("name").value());
    if (name.empty()) xml_.fail(e, "needs name=\"...\"");
    return name;
  }

  // ---- Scopes -------------------------------------------------------------------------------------

  /// The scope of a <model> and, recursively, of its nested models.
  std::unique_ptr<Scope> build(const pugi::xml_node& element, Scope* parent, int depth, bool prefixed) {
    if (depth > max_model_depth) {
      xml_.fail(element,
                fmt::format("models are nested more than {} deep here: tumble refuses deeper nesting "
                            "(no robot needs it)",
                            max_model_depth));
    }
    auto s = std::make_unique<Scope>();
    s->element = element;
    s->parent = parent;
    s->name = required_name(element);
    s->root = "__model__";
    s->path = parent && parent->root == "__model__" ? parent->path + "::" + s->name : s->name;
    if (parent && parent->root == "__model__") {
      s->prefix = parent->prefix + s->name + "::";
    } else if (prefixed) {
      s->prefix = s->name + "::";
    }
    add_children(*s, depth, prefixed);
    return s;
  }

  /// A scope's named children; nested models get scopes of their own.
  void add_children(Scope& s, int depth, bool prefixed) {
    for (const pugi::xml_node& e : s.element.children()) {
      const std::string_view n = e.name();
      if (n == "link" && s.root == "__model__") add(s, Kind::link, e);
      if (n == "joint") add(s, Kind::joint, e);
      if (n == "frame") add(s, Kind::frame, e);
      if (n == "include") add_include(s, e);
      if (n == "model") {
        add(s, Kind::model, e);
        std::unique_ptr<Scope> inner = build(e, &s, depth + 1, prefixed);
        const std::string name = inner->name;
        s.models.emplace(name, std::move(inner));  // unique: add() checked
      }
    }
  }

  /// The scope of a <world>: its models (and theirs), frames and joints.
  std::unique_ptr<Scope> build_world(const pugi::xml_node& world, bool prefixed) {
    auto s = std::make_unique<Scope>();
    s->element = world;
    s->root = "world";
    add_children(*s, -1, prefixed);  // its models are top-level: depth 0
    return s;
  }

  void add(Scope& s, Kind kind, const pugi::xml_node& e) { add(s, kind, e, required_name(e)); }

  void add(Scope& s, Kind kind, const pugi::xml_node& e, const std::string& name) {
    std::vector<Entry>& same = s.entries[name];
    for (const Entry& other : same) {
      // Elements of different kinds may share a name in SDFormat 1.6 and earlier (a converted URDF's link
      // and joint, a world's model and frame): such a name is refused only where something refers to it.
      if (other.kind == kind) {
        xml_.fail(e,
                  fmt::format("{} already has a {} named '{}' (line {}): names are unique within a model (or "
                              "world)",
                              s.label(), kind_name(kind), name, xml_.line_of(other.node)));
      }
    }
    same.push_back({kind, e});
  }

  void add_include(Scope& s, const pugi::xml_node& e) {
    const std::string uri = text_of(e.child("uri"));
    model_.notes.push_back(
        fmt::format("{}: <include> of \"{}\" at line {} is not read: tumble reads one file "
                    "(`gz sdf -p FILE` prints it with its includes expanded)",
                    s.label(), uri, xml_.line_of(e)));
    // Its name, when written, is a frame of the scope that cannot be resolved: say so when it is used.
    if (const std::string name = text_of(e.child("name")); !name.empty()) add(s, Kind::include, e, name);
    s.includes = true;
  }

  /// The entry `ref` names in `s`; fails for none, an include, or a name two kinds share. A link and a
  /// joint may share a name in SDFormat 1.6 and earlier (converted URDFs do): the link is meant.
  const Entry& lookup(const Scope& s, const Ref& ref) const {
    const auto it = s.entries.find(ref.name);
    if (it == s.entries.end()) {
      xml_.fail(ref.at, fmt::format("{}: {} has no link, joint, frame or nested model named '{}' (a frame of "
                                    "a nested model is named nested::frame){}",
                                    ref.how, s.label(), ref.name, include_hint(s)));
    }
    const std::vector<Entry>& all = it->second;
    for (const Entry& e : all)
      if (e.kind == Kind::link) return e;
    if (all.size() > 1) {
      xml_.fail(ref.at, fmt::format("{}: {} has a {} (line {}) and a {} (line {}) named '{}': rename one",
                                    ref.how, s.label(), kind_name(all[0].kind), xml_.line_of(all[0].node),
                                    kind_name(all[1].kind), xml_.line_of(all[1].node), ref.name));
    }
    if (all[0].kind == Kind::include) {
      xml_.fail(ref.at, fmt::format("{}: '{}' is an <include>d model (line {}), which tumble does not read: "
                                    "expand the includes first (`gz sdf -p FILE`)",
                                    ref.how, ref.name, xml_.line_of(all[0].node)));
    }
    return all[0];
  }

  /// "outer::rest" split at its first "::"; fails for an empty part.
  std::pair<std::string, std::string> split_scoped(const Ref& ref, std::size_t sep) const {
    std::pair<std::string, std::string> parts{ref.name.substr(0, sep), ref.name.substr(sep + 2)};
    if (parts.first.empty() || parts.second.empty()) {
      xml_.fail(ref.at, fmt::format("{}: '{}' is not a frame's name (nested::frame)", ref.how, ref.name));
    }
    return parts;
  }

  static std::string include_hint(const Scope& s) {
    return s.includes
               ? "; it may come from one of its <include>s, which tumble does not read: expand them first "
                 "(`gz sdf -p FILE`)"
               : "";
  }

  Scope& nested(Scope& s, const std::string& name, const Ref& ref) {
    const auto it = s.models.find(name);
    if (it == s.models.end()) {
      xml_.fail(ref.at, fmt::format("{}: {} has no nested model named '{}'{}", ref.how, s.label(), name,
                                    include_hint(s)));
    }
    return *it->second;
  }

  void check_steps(int steps, const Ref& ref) const {
    if (steps > max_scope_steps) {
      xml_.fail(ref.at, fmt::format("{}: resolving it steps between models more than {} times: the frames "
                                    "refer to one another in a loop, or far too deep",
                                    ref.how, max_scope_steps));
    }
  }

  // ---- Poses ----------------------------------------------------------------------------------------

  /// The frame an entry's pose is relative to, by SDFormat's defaults.
  Ref target_of(const Entry& e) const {
    const pugi::xml_node pose = e.node.child("pose");
    if (std::string rt = relative_to_of(pose); !rt.empty()) {
      return {rt, pose, fmt::format("relative_to=\"{}\"", rt)};
    }
    if (e.kind == Kind::frame) {
      if (std::string to = trimmed(e.node.attribute("attached_to").value()); !to.empty()) {
        return {to, e.node, fmt::format("attached_to=\"{}\"", to)};
      }
    }
    if (e.kind == Kind::joint) return child_of(e.node);  // a joint's pose is in its child's frame
    return {};
  }

  /// A joint's <child>, required, and not the world.
  Ref child_of(const pugi::xml_node& joint) const {
    const pugi::xml_node child = joint.child("child");
    const std::string name = text_of(child);
    if (name.empty()) xml_.fail(joint, "needs <child>...</child> (the child link)");
    if (name == "world") xml_.fail(child, "the world cannot be a joint's child: swap parent and child");
    return {name, child, fmt::format("<child>{}</child>", name)};
  }

  /// The pose an entry writes, from its target frame to its own.
  Pose local_pose(Scope& s, const Entry& e, int steps) {
    Pose pose = pose_of(xml_, e.node);
    if (e.kind == Kind::model) {
      // placement_frame (1.8+): the pose places that frame of the nested model, not the model frame.
      const std::string placement = trimmed(e.node.attribute("placement_frame").value());
      if (!placement.empty()) {
        Scope& inner = *s.models.at(trimmed(e.node.attribute("name").value()));
        const Ref ref{placement, e.node, fmt::format("placement_frame=\"{}\"", placement)};
        pose = compose(pose, inverse(resolve(inner, ref, steps + 1)));
      }
    }
    return pose;
  }

  /// The pose of the frame `ref` names, in the frame of scope `s`.
  Pose resolve(Scope& s, const Ref& ref, int steps) {
    check_steps(steps, ref);
    if (s.is_root(ref.name)) return {};
    if (const std::size_t sep = s.scoped_at(ref.name); sep != std::string::npos) {
      const auto [outer, rest] = split_scoped(ref, sep);
      Scope& inner = nested(s, outer, ref);
      return compose(resolve(s, {outer, ref.at, ref.how}, steps + 1),
                     resolve(inner, {rest, ref.at, ref.how}, steps + 1));
    }
    return resolve(s, lookup(s, ref), ref, steps);
  }

  /// The pose of an entry of scope `s`, in its frame; `via` refers to it (for messages).
  Pose resolve(Scope& s, const Entry& entry, const Ref& via, int steps) {
    // The chain of frames each relative to the next, up to one already known; then composed back down.
    std::vector<const Entry*> chain;
    const Entry* at = &entry;
    Ref ref = via;
    Pose base;
    while (true) {
      if (const auto known = s.poses.find(at->node); known != s.poses.end()) {
        base = known->second;
        break;
      }
      if (!s.resolving.insert(at->node).second) {
        xml_.fail(ref.at, fmt::format("{}: the poses of {} refer to one another in a loop through '{}'",
                                      ref.how, s.label(), ref.name));
      }
      chain.push_back(at);
      ref = target_of(*at);
      if (s.is_root(ref.name)) break;
      if (s.scoped_at(ref.name) != std::string::npos) {
        base = resolve(s, ref, steps + 1);
        break;
      }
      at = &lookup(s, ref);
    }
    for (auto it = chain.rbegin(); it != chain.rend(); ++it) {
      base = compose(base, local_pose(s, **it, steps));
      s.poses[(*it)->node] = base;
      s.resolving.erase((*it)->node);
    }
    return base;
  }

  /// The scope's frame in the file's root frame: the world's, or the top-level model's.
  Pose placement(Scope& s) {
    if (!s.parent) return {};
    return compose(placement(*s.parent), resolve(*s.parent, Entry{Kind::model, s.element},
                                                 {s.name, s.element, "the model's pose"}, 0));
  }

  /// A link's frame in its model's frame.
  Pose link_in_scope(Scope& s, const pugi::xml_node& link) {
    return resolve(s, Entry{Kind::link, link},
                   {trimmed(link.attribute("name").value()), link, "the link's pose"}, 0);
  }

  /// A link's frame in the file's root frame.
  Pose link_pose(const pugi::xml_node& link) {
    const LinkRecord& r = links_.at(link);
    return compose(placement(*r.scope), link_in_scope(*r.scope, link));
  }

  // ---- Links joints hang from ---------------------------------------------------------------------

  /// The link a frame is attached to, following attached_to, joints' children and models' canonical
  /// links; an empty node for the world frame (in a world's scope).
  pugi::xml_node attached_link(Scope& s, const Ref& ref, int steps) {
    Scope* scope = &s;
    Ref at = ref;
    std::set<pugi::xml_node> seen;
    std::vector<pugi::xml_node> passed;  // the frames and joints on the way, each attached to the result
    const auto found = [&](const pugi::xml_node& link) {
      for (const pugi::xml_node& n : passed) attached_[n] = link;
      return link;
    };
    while (true) {
      check_steps(steps, at);
      if (const std::size_t sep = scope->scoped_at(at.name); sep != std::string::npos) {
        auto [outer, rest] = split_scoped(at, sep);
        scope = &nested(*scope, outer, at);
        at.name = std::move(rest);
        ++steps;
        continue;
      }
      if (scope->is_root(at.name)) {
        if (scope->root == "world") return found({});
        return found(canonical_link(*scope, at, steps + 1));
      }
      const Entry& e = lookup(*scope, at);
      if (const auto known = attached_.find(e.node); known != attached_.end()) return found(known->second);
      if (!seen.insert(e.node).second) {
        xml_.fail(at.at,
                  fmt::format("{}: the frames of {} are attached to one another in a loop through '{}'",
                              at.how, scope->label(), at.name));
      }
      passed.push_back(e.node);
      switch (e.kind) {
        case Kind::link:
          return found(e.node);
        case Kind::model:
          scope = &nested(*scope, at.name, at);
          at.name.clear();
          ++steps;
          break;
        case Kind::frame: {
          const std::string to = trimmed(e.node.attribute("attached_to").value());
          at = {to, e.node, fmt::format("attached_to=\"{}\"", to)};
          break;
        }
        case Kind::joint:  // a joint is attached to its child link
          at = child_of(e.node);
          break;
        case Kind::include:
          xml_.fail(at.at, fmt::format("{}: '{}' is an <include>d model", at.how, at.name));
      }
    }
  }

  /// A model's canonical link: canonical_link="..." (a link of it or of a nested model), else its first
  /// link, else its first nested model's canonical link.
  pugi::xml_node canonical_link(Scope& s, const Ref& ref, int steps) {
    check_steps(steps, ref);
    if (std::string c = trimmed(s.element.attribute("canonical_link").value()); !c.empty()) {
      Scope* scope = &s;
      Ref named{c, s.element, fmt::format("canonical_link=\"{}\"", c)};
      for (std::size_t sep; (sep = scope->scoped_at(named.name)) != std::string::npos;) {
        auto [outer, rest] = split_scoped(named, sep);
        scope = &nested(*scope, outer, named);
        named.name = std::move(rest);
      }
      const Entry& e = lookup(*scope, named);
      if (e.kind != Kind::link)
        xml_.fail(s.element, fmt::format("{}: '{}' is a {}, not a link", named.how, c, kind_name(e.kind)));
      return e.node;
    }
    if (const pugi::xml_node link = s.element.child("link")) return link;
    if (const pugi::xml_node inner = s.element.child("model")) {
      return canonical_link(nested(s, trimmed(inner.attribute("name").value()), ref), ref, steps + 1);
    }
    xml_.fail(ref.at, fmt::format("{}: {} has no link to attach it to", ref.how, s.label()));
  }

  // ---- Reading ----------------------------------------------------------------------------------------

  /// A model's (or world's) links, joints and nested models, in file order.
  void read_scope(Scope& s) {
    const bool model = s.root == "__model__";
    if (model && parse_bool(text_of(s.element.child("static"))).value_or(false)) {
      model_.notes.push_back(
          fmt::format("{} is static: simulators ignore the inertials of its links", s.label()));
    }
    for (const pugi::xml_node& e : s.element.children()) {
      const std::string_view n = e.name();
      if (n == "link" && model) check_pose(s, e, Kind::link);
      if (n == "joint") check_pose(s, e, Kind::joint);
      if (n == "frame") check_pose(s, e, Kind::frame);
      if (n == "model") check_pose(s, e, Kind::model);
      if (n == "link" && model) read_link(s, e);
      if (n == "joint") read_joint(s, e);
      if (n == "model") read_scope(*s.models.at(trimmed(e.attribute("name").value())));
    }
  }

  /// Resolves an element's pose, though nothing may need it, so that a bad one is an error wherever it is.
  void check_pose(Scope& s, const pugi::xml_node& e, Kind kind) {
    const std::string name = trimmed(e.attribute("name").value());
    (void)resolve(s, Entry{kind, e}, {name, e, fmt::format("the pose of <{} name=\"{}\">", e.name(), name)},
                  0);
  }

  /// The RobotModel names of the links of a scope and of its nested scopes, checked unique.
  void register_links(Scope& s) {
    for (const pugi::xml_node& e : s.element.children()) {
      const std::string_view n = e.name();
      if (n == "model") register_links(*s.models.at(trimmed(e.attribute("name").value())));
      if (n != "link" || s.root != "__model__") continue;
      const std::string name = s.prefix + trimmed(e.attribute("name").value());
      if (const auto [it, fresh] = link_names_.emplace(name, e); !fresh) {
        xml_.fail(e, fmt::format("a link named '{}' is already at line {}: link names must be unique", name,
                                 xml_.line_of(it->second)));
      }
      links_.emplace(e, LinkRecord{&s, name});
    }
  }

  void read_link(Scope& s, const pugi::xml_node& element) {
    Link& link = model_.links.emplace_back();
    link.name = links_.at(element).name;
    link.line = xml_.line_of(element);
    const std::string own = trimmed(element.attribute("name").value());
    if (const pugi::xml_node inertial = element.child("inertial")) read_inertial(link, own, inertial);
    for (const pugi::xml_node& g : element.children()) {
      const std::string_view n = g.name();
      if (n != "collision" && n != "visual") continue;
      Geometry geometry;
      if (!read_geometry(g, geometry, link.skipped)) continue;
      geometry.pose = compose(geometry_frame(s, own, element, g), geometry.pose);
      (n == "collision" ? link.collision : link.visual).push_back(std::move(geometry));
    }
  }

  /// The frame a geometry's pose is written in, in its link's frame: the link's own unless relative_to
  /// names another frame of the model.
  Pose geometry_frame(Scope& s, const std::string& link_name, const pugi::xml_node& link,
                      const pugi::xml_node& g) {
    const pugi::xml_node pose = g.child("pose");
    const std::string rt = relative_to_of(pose);
    if (rt.empty() || rt == link_name) return {};
    const Pose frame = resolve(s, {rt, pose, fmt::format("relative_to=\"{}\"", rt)}, 0);
    return compose(inverse(link_in_scope(s, link)), frame);
  }

  void read_inertial(Link& link, const std::string& own_name, const pugi::xml_node& element) {
    if (bool_attribute(xml_, element, "auto", false)) {
      // SDFormat 1.11: the simulator computes the inertial from the collisions (scaled to <mass> if
      // given), overriding any values written.
      if (!element.child("inertia")) {
        model_.notes.push_back(
            fmt::format("link '{}': <inertial auto=\"true\"> at line {}: the simulator computes "
                        "its inertial from the collisions, so it has none to audit",
                        link.name, xml_.line_of(element)));
        return;
      }
      model_.notes.push_back(
          fmt::format("link '{}': <inertial auto=\"true\"> at line {}: the simulator computes "
                      "its inertial from the collisions and ignores the values written, "
                      "which are audited here as written",
                      link.name, xml_.line_of(element)));
    }
    Inertial in;
    in.span = xml_.span_of(element);
    in.frame = pose_of(xml_, element);
    in.rotated = !in.frame.R.isIdentity(0.0);
    if (const std::string rt = relative_to_of(element.child("pose")); !rt.empty() && rt != own_name) {
      model_.notes.push_back(
          fmt::format("link '{}': <inertial><pose relative_to=\"{}\"> at line {}: an inertial's "
                      "pose is always in its link's frame (libsdformat ignores relative_to "
                      "here), and is read so",
                      link.name, rt, xml_.line_of(element.child("pose"))));
    }
    if (const pugi::xml_node mass = element.child("mass")) {
      in.mass = xml_.text_numbers(mass, 1)[0];
      in.mass_text = text_of(mass);
    } else {
      in.mass = 1.0;  // SDFormat's default, written back as "1" by a fix
      in.mass_text = number_text(in.mass);
      model_.notes.push_back(
          fmt::format("link '{}': <inertial> at line {} has no <mass>: SDFormat's default, 1 kg, "
                      "is used",
                      link.name, xml_.line_of(element)));
    }
    // SDFormat's defaults: moments 1, products 0.
    const pugi::xml_node I = element.child("inertia");
    std::vector<std::string> missing;
    const auto component = [&](const char* name, double fallback) {
      const pugi::xml_node c = I.child(name);
      if (!c) {
        missing.emplace_back(name);
        return fallback;
      }
      return xml_.text_numbers(c, 1)[0];
    };
    const double ixx = component("ixx", 1.0), ixy = component("ixy", 0.0), ixz = component("ixz", 0.0);
    const double iyy = component("iyy", 1.0), iyz = component("iyz", 0.0), izz = component("izz", 1.0);
    in.inertia_written << ixx, ixy, ixz, ixy, iyy, iyz, ixz, iyz, izz;
    if (!I) {
      model_.notes.push_back(
          fmt::format("link '{}': <inertial> at line {} has no <inertia>: SDFormat's default, "
                      "the identity (kg·m²), is used",
                      link.name, xml_.line_of(element)));
    } else if (!missing.empty()) {
      std::string list;
      for (const std::string& m : missing) list += (list.empty() ? "" : ", ") + m;
      model_.notes.push_back(
          fmt::format("link '{}': <inertia> at line {} lacks {}: SDFormat's defaults (moments 1, "
                      "products 0) are used",
                      link.name, xml_.line_of(I), list));
    }
    link.inertial = std::move(in);
  }

  /// A <collision> or <visual>'s shape and pose as written; false (and a line in `skipped`) for none.
  bool read_geometry(const pugi::xml_node& element, Geometry& g, std::vector<std::string>& skipped) {
    g.name = element.attribute("name").value();
    g.element = element.name();
    g.line = xml_.line_of(element);
    g.pose = pose_of(xml_, element);
    const std::string what = fmt::format("<{} name=\"{}\"> at line {}", g.element, g.name, g.line);
    pugi::xml_node shape;
    for (const pugi::xml_node& c : element.child("geometry").children())
      if (c.type() == pugi::node_element) {
        shape = c;
        break;
      }
    if (!shape) {
      skipped.push_back(fmt::format("{} has no <geometry>", what));
      return false;
    }
    const std::string_view kind = shape.name();
    if (kind == "box") {
      g.shape = Box{child_vector(xml_, shape, "size")};
    } else if (kind == "sphere") {
      g.shape = Sphere{child_number(xml_, shape, "radius")};
    } else if (kind == "cylinder") {
      g.shape = Cylinder{child_number(xml_, shape, "radius"), child_number(xml_, shape, "length")};
    } else if (kind == "capsule") {  // 1.9+: length is the cylindrical part's, as tumble's Capsule
      g.shape = Capsule{child_number(xml_, shape, "radius"), child_number(xml_, shape, "length")};
    } else if (kind == "ellipsoid") {  // 1.9+
      g.shape = Ellipsoid{child_vector(xml_, shape, "radii")};
    } else if (kind == "cone") {
      // 1.11+: SDFormat centres a cone on its bounding box (base at z = -length/2, libsdformat's Cone);
      // tumble's has its base at z = 0, so the shape sits half its length lower in the geometry's frame.
      const double radius = child_number(xml_, shape, "radius"), length = child_number(xml_, shape, "length");
      g.shape = Cone{radius, length};
      g.pose = compose(g.pose, Pose{Mat3::Identity(), Vec3(0, 0, -length / 2)});
    } else if (kind == "mesh") {
      const pugi::xml_node uri = shape.child("uri");
      g.mesh_uri = text_of(uri);
      if (g.mesh_uri.empty()) xml_.fail(shape, "needs <uri>...</uri> (the mesh file)");
      if (shape.child("submesh")) {
        skipped.push_back(
            fmt::format("{}: a <mesh> with a <submesh> uses one part of \"{}\"; tumble reads whole "
                        "mesh files only",
                        what, g.mesh_uri));
        return false;
      }
      g.scale = child_vector(xml_, shape, "scale", Vec3::Ones());
      g.mesh_path = mesh_file(xml_, g.mesh_uri);
    } else if (kind == "plane" || kind == "heightmap") {
      skipped.push_back(fmt::format("{}: a <{}> has no volume, so no mass", what, kind));
      return false;
    } else if (kind == "polyline" || kind == "image") {
      skipped.push_back(fmt::format("{}: an extruded <{}> is a shape tumble does not compute", what, kind));
      return false;
    } else if (kind == "empty") {
      skipped.push_back(fmt::format("{}: an <empty> geometry has no volume", what));
      return false;
    } else {
      skipped.push_back(fmt::format("{}: a <{}> geometry is not one tumble knows", what, kind));
      return false;
    }
    return true;
  }

  void read_joint(Scope& s, const pugi::xml_node& element) {
    Joint& joint = model_.joints.emplace_back();
    joint.name = s.prefix + required_name(element);
    joint.type = trimmed(element.attribute("type").value());
    if (joint.type.empty()) xml_.fail(element, "needs type=\"...\" (fixed, revolute, prismatic, ...)");
    joint.line = xml_.line_of(element);
    const pugi::xml_node parent = element.child("parent");
    const std::string parent_name = text_of(parent);
    if (parent_name.empty()) xml_.fail(element, "needs <parent>...</parent> (a link, or world)");
    const Ref child = child_of(element);
    const pugi::xml_node child_link = attached_link(s, child, 0);
    if (!child_link) xml_.fail(child.at, "the world cannot be a joint's child: swap parent and child");
    joint.child = links_.at(child_link).name;
    const Pose child_pose = link_pose(child_link);
    pugi::xml_node parent_link;
    if (parent_name != "world") {
      parent_link =
          attached_link(s, {parent_name, parent, fmt::format("<parent>{}</parent>", parent_name)}, 0);
    }
    if (!parent_link) {
      joint.parent = "world";
      joint.origin = child_pose;
    } else {
      joint.parent = links_.at(parent_link).name;
      joint.origin = compose(inverse(link_pose(parent_link)), child_pose);
    }
  }
};

}  // namespace

void read_sdf(const XmlSource& xml, const pugi::xml_node& sdf, RobotModel& model) {
  SdfReader(xml, model).read(sdf);
}

}  // namespace tumble::robot
