// `tumble model check` and `tumble model fix`: the inertials of a robot description (URDF, MJCF, SDF)
// against its geometry, and the file with them recomputed and nothing else changed.
#include <fmt/format.h>

#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "commands.hpp"
#include "tumble/error.hpp"
#include "tumble/io/text_file.hpp"
#include "tumble/robot/audit.hpp"
#include "tumble/robot/fix.hpp"

namespace tumble::cli {
namespace {

struct ModelOptions {
  std::string model;
  bool json = false;
  std::vector<std::string> package_paths;
  std::string geometry = "collision";
  std::optional<double> density;
  bool lump_fixed = false;
  bool all = false;
  std::string out;
  std::string keep = "mass";
  std::vector<std::string> only;
};

robot::AuditOptions audit_options(const ModelOptions& o) {
  robot::AuditOptions a;
  for (const std::string& p : o.package_paths) a.package_paths.emplace_back(p);
  a.geometry = o.geometry == "visual" ? robot::GeometryChoice::visual : robot::GeometryChoice::collision;
  a.density = o.density;
  a.lump_fixed = o.lump_fixed;
  return a;
}

/// The options both commands take: the model, where its meshes are, which geometry weighs, a density.
void add_common(CLI::App* cmd, ModelOptions& o) {
  cmd->add_option("model", o.model,
                  "a URDF, MJCF or SDF file (the format is read from its root element, not its name); xacro "
                  "templates must be expanded first")
      ->required();
  cmd->add_option(
         "--package-path", o.package_paths,
         "directories where package://PKG/... and model://PKG/... meshes are: DIR/PKG, or DIR itself "
         "when it is named PKG (repeat, or separate with ':'); then ROS_PACKAGE_PATH, AMENT_PREFIX_PATH "
         "(PREFIX/share/PKG), GZ_SIM_RESOURCE_PATH and GAZEBO_MODEL_PATH. ROS itself is not needed")
      ->delimiter(':');
  cmd->add_option(
         "--geometry", o.geometry,
         "which geometry carries a URDF or SDF link's mass: its collision geometries (default), or its "
         "visual ones; a link without the one uses the other. MJCF follows MuJoCo: every geom within "
         "inertiagrouprange, weighted by its own mass or density")
      ->check(CLI::IsMember({"collision", "visual"}));
  cmd->add_option(
         "--density", o.density,
         "compute every link's mass from this uniform density (kg/m^3) instead of spreading the authored "
         "mass over the geometry (MJCF: instead of each geom's density)")
      ->check(CLI::PositiveNumber);
}

int run_check(const ModelOptions& o) {
  const robot::ModelAudit audit = robot::audit_model(o.model, audit_options(o));
  const std::string text = o.json ? robot::audit_json(audit) : robot::audit_table(audit);
  std::fputs(text.c_str(), stdout);
  return audit.has_errors() ? 1 : 0;
}

robot::Keep keep_of(const std::string& k) {
  if (k == "mass+com") return robot::Keep::mass_and_com;
  if (k == "none") return robot::Keep::none;
  return robot::Keep::mass;
}

int run_fix(const ModelOptions& o) {
  const robot::AuditOptions a = audit_options(o);
  const robot::ModelAudit audit = robot::audit_model(o.model, a);
  const robot::FixResult fixed = robot::fix_model(audit, {keep_of(o.keep), o.only, o.all}, a);
  const std::filesystem::path inputs[] = {o.model};
  write_text_file(o.out, fixed.text, inputs, "the fixed model");
  // The report goes where the model does not: stderr when the model went to stdout.
  std::FILE* report = o.out == "-" ? stderr : stdout;
  std::size_t changed = 0;
  for (const robot::LinkFix& l : fixed.links) {
    if (l.changed) {
      ++changed;
      std::string diff = fmt::format("link '{}' (line {}):\n", l.name, l.line);
      std::size_t start = 0;
      for (const std::string* side : {&l.before, &l.after}) {
        const char mark = side == &l.before ? '-' : '+';
        start = 0;
        while (start <= side->size()) {
          const std::size_t end = std::min(side->find('\n', start), side->size());
          diff += fmt::format("{} {}\n", mark, side->substr(start, end - start));
          start = end + 1;
        }
      }
      std::fputs(diff.c_str(), report);
    } else {
      std::fputs(fmt::format("link '{}' (line {}): left as it was: {}\n", l.name, l.line, l.reason).c_str(),
                 report);
    }
  }
  std::fputs(fmt::format("{}: {} inertial{} rewritten, nothing else changed\n", o.out, changed,
                         changed == 1 ? "" : "s")
                 .c_str(),
             report);
  // Nothing but the inertials changes, so mesh paths relative to MODEL's directory stay as written: name
  // the one that no longer resolves from OUT's.
  if (o.out != "-") {
    std::error_code ec;
    const auto dir = [&](const std::string& f) {
      return std::filesystem::weakly_canonical(std::filesystem::absolute(f, ec).parent_path(), ec);
    };
    if (dir(o.out) != dir(o.model)) {
      for (const robot::Link& link : audit.model.links) {
        for (const auto* list : {&link.collision, &link.visual}) {
          for (const robot::Geometry& g : *list) {
            if (g.mesh_uri.empty() || g.mesh_uri.find("://") != std::string::npos ||
                std::filesystem::path(g.mesh_uri).is_absolute())
              continue;
            std::fputs(fmt::format("note: {} names its meshes relative to its directory (\"{}\", link '{}'), "
                                   "and {} is "
                                   "in another: put it beside {} for them to resolve\n",
                                   o.model, g.mesh_uri, link.name, o.out, o.model)
                           .c_str(),
                       report);
            return 0;
          }
        }
      }
    }
  }
  return 0;
}

}  // namespace

Runner add_model_command(CLI::App& app) {
  auto o = std::make_shared<ModelOptions>();
  CLI::App* model = app.add_subcommand(
      "model",
      "Robot descriptions (URDF, MJCF, SDF): each link's inertial against the mass properties of its "
      "geometry (meshes exactly, primitives in closed form), and the file with them recomputed. "
      "docs/robot-models.md lists every finding, its trigger and threshold.\n\nExamples:\n"
      "  tumble model check arm.urdf --package-path ~/ws/src\n"
      "  tumble model check arm.xml --json > audit.json      (exit status 1 when an error is found: for CI)\n"
      "  tumble model fix arm.urdf -o arm.fixed.urdf          (the authored masses kept, COM and tensors "
      "recomputed)");
  model->require_subcommand(1);

  CLI::App* check = model->add_subcommand(
      "check",
      "Audit every link's <inertial>: a valid tensor (positive definite, triangle inequality), the density "
      "its "
      "mass implies, a mesh in the wrong units, the centre of mass inside the geometry, and the tensor "
      "against "
      "the geometry's at the same mass (about the origin? rotated? permuted? a product's sign?). Prints a "
      "table "
      "and the findings (--json: one object). Exit status: 0 without error findings, 1 with any, 2 for a "
      "command line that cannot be used.");
  add_common(check, *o);
  check->add_flag(
      "--json", o->json,
      "print {\"model\", \"format\", \"links\": [{\"name\", \"authored\", \"computed\", \"findings\": "
      "[{\"code\", \"severity\", \"message\"}]}], ...} instead of the table");
  check->add_flag(
      "--lump-fixed", o->lump_fixed,
      "also audit the bodies that fixed joints weld together (as engines lump them): the authored "
      "inertials composed, against the geometry of all their links");

  CLI::App* fix = model->add_subcommand(
      "fix",
      "Write the model with its links' inertials recomputed from their geometry, and nothing else changed: "
      "every byte outside the rewritten <inertial> elements stays as it was. Each rewritten one says in a "
      "comment that tumble computed it, and from what; the changes are printed. A link without an inertial "
      "gets none; one whose geometry cannot be used keeps its own, with the reason.");
  add_common(fix, *o);
  fix->add_option("-o,--output", o->out, "the fixed model (never the input; '-' for standard output)")
      ->required();
  fix->add_option(
         "--keep", o->keep,
         "what to keep of the authored inertial: mass (default: the mass exactly as written; COM and "
         "tensor from the geometry), mass+com (the tensor about the authored COM), none (all from "
         "--density; MJCF: from the geoms' densities)")
      ->check(CLI::IsMember({"mass", "mass+com", "none"}));
  fix->add_option(
         "--only", o->only,
         "rewrite these links (comma-separated names), findings or not; by default those whose findings "
         "a recomputed inertial answers")
      ->delimiter(',');
  fix->add_flag("--all", o->all, "rewrite every link whose geometry can be used, findings or not");

  return [o, check, fix]() -> int {
    if (check->parsed()) return run_check(*o);
    if (fix->parsed()) return run_fix(*o);
    return 2;
  };
}

}  // namespace tumble::cli
