// Scene files: parsing (toml++), [simulation], and the order in which the sections are read.
#include "tumble/io/scene.hpp"

#include <fmt/format.h>

#include "scene_sections.hpp"
#include "tumble/integrate/integrator.hpp"
#include "tumble/mass/input_file.hpp"
#include "tumble/sim/output_fields.hpp"

namespace tumble {
namespace scene {
namespace {

void read_simulation(const TableReader& root, Scene& scene) {
  const auto sim = root.table("simulation", "[simulation]",
                              {"duration", "timestep", "integrator", "formulation", "output_interval", "rtol",
                               "atol", "drift_threshold"});
  if (!sim) root.fail_here("missing [simulation]: give at least duration = T (s)");
  RunSettings& s = scene.settings;
  s.duration = sim->required_number("duration", "s", Domain::non_negative);
  s.timestep = sim->number("timestep", 1e-3, "s", Domain::positive);
  s.output_interval = sim->number("output_interval", 0.01, "s", Domain::non_negative);
  s.tolerances.relative = sim->number("rtol", s.tolerances.relative, "", Domain::positive);
  s.tolerances.absolute = sim->number("atol", s.tolerances.absolute, "", Domain::positive);
  scene.drift_threshold = sim->number("drift_threshold", scene.drift_threshold, "", Domain::non_negative);
  if (const auto name = sim->string("integrator")) {
    const auto names = integrator_names();
    if (std::find(names.begin(), names.end(), *name) == names.end()) {
      const auto close = closest(std::string(*name), names);
      sim->fail_at("integrator", fmt::format("unknown integrator \"{}\"; {}choose one of: {}", *name,
                                             close ? fmt::format("did you mean \"{}\"? ", *close) : "",
                                             fmt::join(names, ", ")));
    }
    s.integrator = *name;
  }
  if (const auto f = sim->string("formulation")) {
    try {
      s.formulation = parse_formulation(std::string(*f));
    } catch (const InvalidArgument&) {
      sim->fail_at("formulation",
                   fmt::format("formulation must be \"world\", \"mixed\" or \"body\", found \"{}\"", *f));
    }
  }
}

/// [output] fields = ["position", ...]: what `tumble run` writes for each body unless --fields says.
void read_output(const TableReader& root, Scene& scene) {
  const auto out = root.table("output", "[output]", {"fields"});
  if (!out || !out->has("fields")) return;
  const toml::array* a = out->node("fields")->as_array();
  if (!a) out->fail_at("fields", "fields must be a list of field names, e.g. [\"position\", \"euler_zyx\"]");
  std::vector<std::string> names;
  for (const toml::node& n : *a) {
    const auto name = n.value<std::string>();
    if (!name) out->fail_at("fields", "fields must be a list of strings, e.g. [\"position\", \"euler_zyx\"]");
    names.push_back(*name);
  }
  try {
    body_fields(names);  // unknown or repeated names, with the list of fields
  } catch (const InvalidArgument& e) {
    out->fail_at("fields", e.what());
  }
  scene.output_fields = std::move(names);
}

}  // namespace

std::string read_file(const std::filesystem::path& path, const char* what) {
  // A regular file within the input limit: never a FIFO or a device that could be read forever.
  try {
    return read_input_file(path, what);
  } catch (const FileError& e) {
    throw FileError(fmt::format("cannot read {} {}", what, e.what()));
  }
}

toml::table parse_toml(const std::string& text, const std::string& file) {
  try {
    return toml::parse(text, file);
  } catch (const toml::parse_error& e) {
    fail(file, e.source(), fmt::format("TOML syntax error: {}", e.description()));
  }
}

Scene read_scene(const toml::table& root, std::string text, const std::filesystem::path& path) {
  Scene scene;
  scene.path = path;
  scene.text = std::move(text);
  scene.input_files.push_back(path);       // then every mesh, as it is read
  const std::string file = path.string();  // for messages; outlives every reader
  const TableReader r(root, "scene", file,
                      {"simulation", "output", "world", "bodies", "body_tables", "particles", "forces",
                       "events", "ensemble"});
  read_simulation(r, scene);
  read_output(r, scene);
  NameTable names;
  std::deque<std::string> table_names;  // the names of [[body_tables]] rows, viewed by `names`
  read_bodies(r, path.parent_path(), names, scene);
  read_body_tables(r, path.parent_path(), names, table_names, scene);
  read_particles(r, names, scene);
  if (scene.model.bodies.empty() && scene.model.particles.empty()) {
    r.fail_here("the scene has nothing to simulate: add [[bodies]], [[body_tables]] or [[particles]]");
  }
  read_forces(r, names, scene);
  scene.events = read_events(r, names, scene);
  return scene;
}

}  // namespace scene

Scene parse_scene(const std::string& text, const std::filesystem::path& path) {
  return scene::read_scene(scene::parse_toml(text, path.string()), text, path);
}

Scene load_scene(const std::filesystem::path& path) {
  std::string text = scene::read_file(path);
  const toml::table root = scene::parse_toml(text, path.string());
  return scene::read_scene(root, std::move(text), path);
}

}  // namespace tumble
