// audit_model: each link's geometry weighed (link_mass.cpp) and the authored inertial judged against it
// (findings.cpp); fixed joints welded on request.
#include "tumble/robot/audit.hpp"

#include <algorithm>
#include <map>

#include <fmt/format.h>

#include "findings.hpp"
#include "link_mass.hpp"
#include "tumble/error.hpp"
#include "tumble/mass/mass_spec.hpp"
#include "tumble/mass/tessellate.hpp"

namespace tumble::robot {

bool ModelAudit::has_errors() const {
  for (const LinkAudit& l : links)
    for (const Finding& f : l.findings)
      if (f.severity == Severity::error) return true;
  return false;
}

namespace {

/// Segments of a full turn when a primitive is tessellated for the convex hull: the inscribed polygon
/// falls short of the surface by r (1 − cos(π/24)) < 0.9 % of r (findings.cpp allows for it).
constexpr int kHullSegments = 24;

std::string plural(std::size_t n, const char* one, const char* many) {
  return fmt::format("{} {}", n, n == 1 ? one : many);
}

/// What a link's geometry was made of, in words: each kind once, counted, in the order it first appears
/// ("collision 1 mesh, 20 boxes, cylinder").
std::string describe(const std::vector<const Geometry*>& used) {
  std::vector<std::pair<std::string, std::size_t>> kinds;
  for (const Geometry* g : used) {
    const std::string kind = g->shape ? shape_name(*g->shape) : "mesh";
    auto it = std::find_if(kinds.begin(), kinds.end(), [&](const auto& k) { return k.first == kind; });
    if (it == kinds.end()) {
      kinds.emplace_back(kind, 1);
    } else {
      ++it->second;
    }
  }
  std::string out = used.empty() ? "" : used.front()->element + " ";
  for (std::size_t i = 0; i < kinds.size(); ++i) {
    const auto& [kind, n] = kinds[i];
    const std::string many = kind == "torus"                   ? "tori"
                             : kind == "box" || kind == "mesh" ? kind + "es"
                                                               : kind + "s";
    out += (i > 0 ? ", " : "") + (n == 1 && kind != "mesh" ? kind : plural(n, kind.c_str(), many.c_str()));
  }
  return out;
}

/// The geometries that carry a link's mass (audit.hpp: the format's rule and the option).
std::vector<const Geometry*> mass_geometries(const Link& link, Format format, GeometryChoice choice) {
  const std::vector<Geometry>* first = &link.collision;
  const std::vector<Geometry>* second = &link.visual;
  if (format != Format::mjcf && choice == GeometryChoice::visual) std::swap(first, second);
  const std::vector<Geometry>& used = first->empty() ? *second : *first;
  std::vector<const Geometry*> out;
  for (const Geometry& g : used) out.push_back(&g);
  return out;
}

/// One link weighed: its geometry at unit density, then at the link's mass (audit.hpp says which).
/// Findings for geometry that cannot be used; none computed then.
std::optional<LinkSolids> weigh(const RobotModel& model, const Link& link, const AuditOptions& options,
                                MeshLibrary& meshes, LinkAudit& audit) {
  const std::vector<const Geometry*> used = mass_geometries(link, model.format, options.geometry);
  if (used.empty()) return std::nullopt;
  LinkSolids solids;
  bool usable = true;
  MassProperties unit_total, weighted;
  bool any_weight = false;
  const std::string where = fmt::format("{}:{}", model.path.string(), link.line);
  for (const Geometry* g : used) {
    LinkSolids::Solid solid;
    solid.pose = g->pose;
    MassProperties unit;
    if (g->shape) {
      try {
        unit = solid_mass_properties(*g->shape, MassSpec::density(1.0));
        solid.shape = g->shape;
        const TriangleMesh surface = tessellate(*g->shape, kHullSegments);
        for (const Vec3& v : surface.vertices) solids.points.push_back(g->pose.R * v + g->pose.p);
      } catch (const InvalidArgument& e) {
        audit.findings.push_back({"bad_geometry", Severity::error,
                                  fmt::format("link '{}' ({}): its {} at line {}: {}; fix the geometry",
                                              link.name, where, g->element, g->line, e.what())});
        usable = false;
        continue;
      }
    } else {
      std::string why;
      const std::filesystem::path file =
          resolve_mesh(*g, model.path.parent_path(), options.package_paths, why);
      if (file.empty()) {
        audit.findings.push_back({"missing_mesh", Severity::error,
                                  fmt::format("link '{}' ({}): the mesh of its {} at line {}: {}. Its mass "
                                              "properties are not computed; its inertial is left as it is",
                                              link.name, where, g->element, g->line, why)});
        usable = false;
        continue;
      }
      const auto& [mesh, error] = meshes.get(file, g->scale);
      if (!mesh) {
        audit.findings.push_back({"open_mesh", Severity::warning,
                                  fmt::format("link '{}' ({}): the mesh of its {} at line {} bounds no "
                                              "solid: {}. Its mass properties "
                                              "are not computed and its inertial is left as it is; close the "
                                              "mesh, or give the link a "
                                              "primitive geometry",
                                              link.name, where, g->element, g->line, error)});
        usable = false;
        continue;
      }
      for (const std::string& note : mesh->notes)
        solids.notes.push_back(fmt::format("link '{}': {}", link.name, note));
      unit = mesh->unit;
      solid.mesh = &mesh->mesh;
      solids.from_meshes = true;
      for (const Vec3& v : mesh->mesh.vertices) solids.points.push_back(g->pose.R * v + g->pose.p);
    }
    unit = unit.transformed(g->pose.R, g->pose.p);
    unit_total += unit;
    // MJCF weighs each geom by its own mass or density (MuJoCo's inference); --density overrides.
    if (model.format == Format::mjcf) {
      const MassSpec spec = options.density ? MassSpec::density(*options.density)
                            : g->mass       ? MassSpec::mass(*g->mass)
                                            : MassSpec::density(g->density.value_or(1000.0));
      weighted += spec.apply(unit);
      any_weight = true;
    }
    solids.solids.push_back(solid);
  }
  if (!usable || unit_total.mass <= 0) return std::nullopt;
  ComputedMass computed;
  computed.geometry = describe(used);
  computed.from_meshes = solids.from_meshes;
  const double authored_mass = link.inertial ? link.inertial->mass : 0.0;
  if (any_weight) {
    computed.properties = weighted;
    computed.basis = options.density ? fmt::format("{} kg/m³ (--density)", *options.density)
                                     : "each geom's mass or density (MuJoCo's rule)";
  } else if (options.density) {
    computed.properties = MassSpec::density(*options.density).apply(unit_total);
    computed.basis = fmt::format("{} kg/m³ (--density)", *options.density);
  } else if (authored_mass > 0) {
    computed.properties = MassSpec::mass(authored_mass).apply(unit_total);
    computed.basis = "the authored mass, uniform";
  } else {
    computed.properties = MassSpec::density(1000.0).apply(unit_total);
    computed.basis = "1000 kg/m³ (no authored mass)";
  }
  computed.properties.volume = unit_total.mass;
  audit.computed = std::move(computed);
  return solids;
}

LinkAudit audit_link(const RobotModel& model, const Link& link, const AuditOptions& options,
                     MeshLibrary& meshes, std::vector<std::string>& notes) {
  LinkAudit audit;
  audit.name = link.name;
  audit.line = link.line;
  audit.authored = link.inertial;
  audit.skipped = link.skipped;
  const std::optional<LinkSolids> solids = weigh(model, link, options, meshes, audit);
  if (solids) {
    for (const std::string& n : solids->notes) notes.push_back(n);
  }
  judge(model, link, audit, solids ? &*solids : nullptr, audit.findings);
  return audit;
}

/// A body's mass properties moved into another frame by a pose.
MassProperties placed(const MassProperties& m, const Pose& pose) { return m.transformed(pose.R, pose.p); }

/// The bodies that fixed joints weld together, each audited as one: the authored inertials composed,
/// and the computed ones, in the frame of the body's root link.
void lump_fixed(const RobotModel& model, ModelAudit& audit) {
  std::map<std::string, std::size_t> index;
  for (std::size_t i = 0; i < audit.links.size(); ++i) index[audit.links[i].name] = i;
  // Each link's fixed parent, and the pose of the link in it.
  std::map<std::string, std::pair<std::string, Pose>> up;
  for (const Joint& j : model.joints)
    if (j.type == "fixed" && index.count(j.parent) && index.count(j.child))
      up[j.child] = {j.parent, j.origin};
  // Each link's root (the nearest ancestor not fixed to its parent) and its pose there.
  std::map<std::string, std::vector<std::pair<std::string, Pose>>> groups;
  for (const LinkAudit& l : audit.links) {
    std::string root = l.name;
    Pose pose;
    for (std::size_t guard = 0; up.count(root) && guard <= up.size(); ++guard) {
      const auto& [parent, origin] = up.at(root);
      pose = {origin.R * pose.R, origin.R * pose.p + origin.p};
      root = parent;
    }
    groups[root].push_back({l.name, pose});
  }
  for (const auto& [root, members] : groups) {
    if (members.size() < 2) continue;
    LinkAudit lumped;
    lumped.name = fmt::format("{} (lumped)", root);
    lumped.line = audit.links[index[root]].line;
    std::optional<MassProperties> authored, computed;
    bool all_computed = true;
    for (const auto& [name, pose] : members) {
      const LinkAudit& part = audit.links[index[name]];
      lumped.parts.push_back(name);
      if (part.authored && part.authored->mass > 0) {
        const Inertial& in = *part.authored;
        const MassProperties m =
            placed(MassProperties::from_inertia(in.mass, in.frame.p, in.inertia_link()), pose);
        authored = authored ? *authored + m : m;
      }
      if (part.computed) {
        const MassProperties m = placed(part.computed->properties, pose);
        computed = computed ? *computed + m : m;
      } else {
        all_computed = false;
      }
    }
    if (authored) {
      Inertial in;
      in.mass = authored->mass;
      in.mass_text = fmt::format("{}", authored->mass);
      in.frame.p = authored->center_of_mass;
      in.inertia_written = authored->inertia;
      lumped.authored = in;
    }
    if (computed && all_computed) {
      ComputedMass c;
      c.properties = *computed;
      c.geometry = fmt::format("the {} links welded by fixed joints", members.size());
      lumped.computed = std::move(c);
    }
    judge_lumped(model, lumped, lumped.findings);
    audit.links.push_back(std::move(lumped));
  }
}

}  // namespace

ModelAudit audit_model(const std::filesystem::path& path, const AuditOptions& options) {
  if (options.density && !(std::isfinite(*options.density) && *options.density > 0)) {
    throw InvalidArgument(
        fmt::format("density {} kg/m³ is invalid: give a positive density", *options.density));
  }
  ModelAudit audit;
  audit.model = read_robot_model(path);
  audit.notes = audit.model.notes;
  MeshLibrary meshes;
  std::vector<std::pair<std::filesystem::path, Vec3>> files;
  for (const Link& link : audit.model.links) {
    for (const Geometry* g : mass_geometries(link, audit.model.format, options.geometry)) {
      std::string why;  // a mesh that cannot be found is a finding, made when its link is weighed
      if (g->shape) continue;
      const std::filesystem::path file =
          resolve_mesh(*g, audit.model.path.parent_path(), options.package_paths, why);
      if (!file.empty()) files.emplace_back(file, g->scale);
    }
  }
  meshes.preload(files);
  // The links one per thread: each reads the meshes (all read by now) and writes only its own audit.
  const std::vector<Link>& links = audit.model.links;
  std::vector<std::vector<std::string>> notes(links.size());
  audit.links.resize(links.size());
  for_each_index(links.size(), 0, [&](std::size_t i) {
    audit.links[i] = audit_link(audit.model, links[i], options, meshes, notes[i]);
  });
  for (const std::vector<std::string>& n : notes) audit.notes.insert(audit.notes.end(), n.begin(), n.end());
  if (options.lump_fixed) lump_fixed(audit.model, audit);
  return audit;
}

}  // namespace tumble::robot
