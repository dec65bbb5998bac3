// [[events]]: conditions watched during a run (sim/event_specs.hpp), each on one body or particle.
#include <fmt/format.h>

#include <cmath>
#include <numbers>

#include "scene_sections.hpp"
#include "tumble/sim/event_specs.hpp"

namespace tumble {
namespace scene {
namespace {

/// Every column of the output-field table, for a message.
std::vector<std::string> all_columns() {
  std::vector<std::string> columns;
  for (const BodyField& f : body_fields()) {
    for (int k = 0; k < f.width; ++k) columns.emplace_back(f.columns[static_cast<size_t>(k)]);
  }
  return columns;
}

size_t watched_row(const TableReader& t, const NameTable& names, const Scene& scene) {
  const std::string_view name =
      t.required_string("body", "the body or particle to watch, e.g. body = \"handle\"");
  if (const auto* found = names.find(name)) {
    return found->is_particle ? scene.model.bodies.size() + found->index : found->index;
  }
  const std::vector<std::string> rows = row_names(scene.model);
  const auto s = closest(std::string(name), rows);
  t.fail_at("body", fmt::format("no body or particle named \"{}\"; {}", name,
                                s ? fmt::format("did you mean \"{}\"?", *s)
                                  : fmt::format("the scene has: {}", fmt::join(rows, ", "))));
}

int crossing_direction(const TableReader& t) {
  const std::string_view d = t.string("direction").value_or("both");
  if (d == "both") return 0;
  if (d == "rising") return +1;
  if (d == "falling") return -1;
  t.fail_at("direction",
            fmt::format("unknown direction \"{}\"; choose \"both\" (default), \"rising\" (g goes from "
                        "below to above) or \"falling\"",
                        d));
}

}  // namespace

std::vector<EventSpec> read_events(const TableReader& root, const NameTable& names, const Scene& scene) {
  std::vector<EventSpec> specs;
  const auto events = root.tables("events");
  for (size_t i = 0; i < events.size(); ++i) {
    const auto untitled =
        TableReader::any_keys(*events[i], Context::numbered("[[events]] #", i + 1), root.file());
    const std::string_view name = untitled.required_string("name", "the event a name, e.g. name = \"flip\"");
    if (!valid_name(name)) {
      untitled.fail_at("name", fmt::format("event name \"{}\": use letters, digits, '_', '-' and '.'", name));
    }
    const TableReader t(*events[i], Context::named("event", name), root.file(),
                        {"name", "body", "column", "value", "axis", "toward", "angle_deg", "direction",
                         "stop"});
    EventSpec e;
    e.name = std::string(name);
    e.row = watched_row(t, names, scene);
    e.direction = crossing_direction(t);
    e.stop = t.boolean("stop").value_or(false);
    if (!t.at_most_one_of({"column", "axis"})) {  // both: an error there; neither: false
      t.fail_here(
          "say what to watch: column = \"w2\" (a column of the output table crossing `value`) or "
          "axis, toward and angle_deg (the angle between a body axis and a world direction)");
    }
    if (t.has("column")) {
      const std::string_view column = *t.string("column");
      const auto found = find_column(column);
      if (!found) {
        const auto s = closest(std::string(column), all_columns());
        t.fail_at("column",
                  fmt::format("no output column \"{}\"; {}", column,
                              s ? fmt::format("did you mean \"{}\"?", *s)
                                : fmt::format("the columns are: {}", fmt::join(all_columns(), ", "))));
      }
      if (found->first->of_orbit) {
        t.fail_at("column",
                  fmt::format("\"{}\" is relative to the orbit frame (LVLH): events watch columns in "
                              "world or body axes (yaw, w1, com_z, ...)",
                              column));
      }
      e.kind = EventSpec::Kind::column;
      e.field = found->first;
      e.component = found->second;
      e.value = t.number("value", 0.0, std::string(e.field->unit).c_str());
      if (t.has("toward") || t.has("angle_deg")) t.fail_here("toward and angle_deg go with axis, not column");
    } else {
      e.kind = EventSpec::Kind::angle;
      const auto axis = t.vec3("axis", "1 (reference frame)");
      const auto toward = t.vec3("toward", "1 (world)");
      if (!toward)
        t.fail_here("missing 'toward': the world direction the axis is measured from, e.g. [0, 0, 1]");
      if (axis->norm() == 0)
        t.fail_at("axis", "axis is the zero vector: give a direction in the body's frame");
      if (toward->norm() == 0) t.fail_at("toward", "toward is the zero vector: give a world direction");
      e.axis = *axis;
      e.toward = *toward;
      const double deg = t.required_number("angle_deg", "degrees", Domain::non_negative);
      if (deg > 180)
        t.fail_at("angle_deg",
                  fmt::format("angle_deg = {}: an angle between two directions is 0 to 180", deg));
      e.angle = deg * std::numbers::pi / 180;
      if (t.has("value")) t.fail_here("value goes with column; an angle event crosses angle_deg");
    }
    specs.push_back(std::move(e));
  }
  return specs;
}

}  // namespace scene

std::vector<EventSpec> parse_events(const Scene& s, const std::string& text,
                                    const std::filesystem::path& path) {
  const scene::TomlFile file{path.string()};
  const toml::table root = scene::parse_toml(text, file);
  const scene::TableReader r(root, "events", file, {"events"});
  // The names as the scene file registered them: bodies, then particles.
  scene::NameTable names(s.model, s.path.string());
  for (size_t i = 0; i < s.model.bodies.size(); ++i) names.add(s.model.bodies[i].name(), false, i, 0, 0, 0);
  for (size_t i = 0; i < s.model.particles.size(); ++i)
    names.add(s.model.particles[i].name, true, i, 0, 0, 0);
  names.seal();
  return scene::read_events(r, names, s);
}

}  // namespace tumble
