// [[body_tables]]: many bodies from one CSV file, a row per body, for scenes of 10⁴–10⁶ bodies.
//
// A [[bodies]] table costs about 30 µs to set up, 25 of them in toml++ building and freeing its tree
// (bench/scene_setup); a row of numbers read straight with std::from_chars costs about 1. No CSV
// library is among the dependencies, and this format needs none: a header of known column names, then
// numbers (and an optional name) separated by commas; '#' lines and blank lines are skipped.
//
// Each row is a body whose reference frame is its principal frame at the centre of mass: mass m and
// principal moments I1, I2, I3 about the reference axes (RigidBody::from_principal_moments), and the
// state as in [[bodies]] (position, orientation w first, velocity, angular velocity in the table's
// angular_velocity_frame).
#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <optional>

#include "scene_sections.hpp"
#include "tumble/dynamics/rigid_body.hpp"

namespace tumble::scene {
namespace {

/// The columns a body table may have. Groups (a vector, a quaternion) are all present or all absent.
enum Column : int { mass, I1, I2, I3, px, py, pz, qw, qx, qy, qz, vx, vy, vz, wx, wy, wz, kColumns };
constexpr std::array<std::string_view, kColumns> kColumnNames = {
    "mass", "I1", "I2", "I3", "px", "py", "pz", "qw", "qx", "qy", "qz", "vx", "vy", "vz", "wx", "wy", "wz"};
struct Group {
  int first, size;
  bool required;
  const char* meaning;
};
constexpr std::array<Group, 6> kGroups = {{{mass, 1, true, "the mass (kg)"},
                                           {I1, 3, true, "the principal moments (kg m^2)"},
                                           {px, 3, false, "the position of the centre of mass (m)"},
                                           {qw, 4, false, "the orientation, a unit quaternion w first"},
                                           {vx, 3, false, "the velocity of the centre of mass (m/s)"},
                                           {wx, 3, false, "the angular velocity (rad/s)"}}};

/// The CSV text and where a byte is in it, for messages "file:line:column: ...".
class CsvText {
 public:
  CsvText(std::string path, std::string bytes) : path_(std::move(path)), bytes_(std::move(bytes)) {}
  std::string_view view() const { return bytes_; }
  const std::string& path() const { return path_; }

  [[noreturn]] void fail(size_t pos, const std::string& message) const {
    const size_t line_start = bytes_.rfind('\n', pos == 0 ? 0 : pos - 1);
    const size_t column = line_start == std::string::npos || pos == 0 ? pos + 1 : pos - line_start;
    const auto line = 1 + std::count(bytes_.begin(), bytes_.begin() + static_cast<std::ptrdiff_t>(pos), '\n');
    throw SceneError(fmt::format("{}:{}:{}: {}", path_, line, column, message));
  }

 private:
  std::string path_;
  std::string bytes_;
};

/// A field of a line and where it starts.
struct Field {
  std::string_view text;
  size_t pos;
};

/// Splits a line (without its end) at commas, trimming blanks; `fields` is reused between rows.
void split(std::string_view line, size_t line_pos, std::vector<Field>& fields) {
  fields.clear();
  size_t start = 0;
  while (true) {
    const size_t comma = std::min(line.find(',', start), line.size());
    size_t a = start, b = comma;
    while (a < b && (line[a] == ' ' || line[a] == '\t')) ++a;
    while (b > a && (line[b - 1] == ' ' || line[b - 1] == '\t' || line[b - 1] == '\r')) --b;
    fields.push_back({line.substr(a, b - a), line_pos + a});
    if (comma == line.size()) return;
    start = comma + 1;
  }
}

/// The next line that is neither blank nor a '#' comment, from `pos` on; nullopt at the end.
std::optional<Field> next_line(std::string_view text, size_t& pos) {
  while (pos < text.size()) {
    const size_t end = std::min(text.find('\n', pos), text.size());
    const std::string_view line = text.substr(pos, end - pos);
    const size_t start = pos;
    pos = end + 1;
    const size_t first = line.find_first_not_of(" \t\r");
    if (first != std::string_view::npos && line[first] != '#') return Field{line, start};
  }
  return std::nullopt;
}

/// The header: which field holds each column (-1: absent) and which holds the name.
struct Header {
  std::array<int, kColumns> field;
  int name = -1;
  size_t fields = 0;
};

Header read_header(const CsvText& csv, const Field& line, std::vector<Field>& fields) {
  split(line.text, line.pos, fields);
  Header h;
  h.field.fill(-1);
  h.fields = fields.size();
  std::vector<std::string> known(kColumnNames.begin(), kColumnNames.end());
  known.emplace_back("name");
  for (size_t i = 0; i < fields.size(); ++i) {
    const std::string_view word = fields[i].text;
    const auto it = std::find(kColumnNames.begin(), kColumnNames.end(), word);
    int* slot = word == "name"             ? &h.name
                : it != kColumnNames.end() ? &h.field[static_cast<size_t>(it - kColumnNames.begin())]
                                           : nullptr;
    if (!slot) {
      const auto close = closest(std::string(word), known);
      csv.fail(fields[i].pos, fmt::format("unknown column \"{}\"; {}the columns are: name, {}", word,
                                          close ? fmt::format("did you mean \"{}\"? ", *close) : "",
                                          fmt::join(kColumnNames, ", ")));
    }
    if (*slot >= 0) csv.fail(fields[i].pos, fmt::format("column \"{}\" appears twice in the header", word));
    *slot = static_cast<int>(i);
  }
  for (const Group& g : kGroups) {
    int present = 0;
    for (int c = g.first; c < g.first + g.size; ++c) present += h.field[static_cast<size_t>(c)] >= 0;
    if (present == g.size || (present == 0 && !g.required)) continue;
    std::vector<std::string_view> names(kColumnNames.begin() + g.first,
                                        kColumnNames.begin() + g.first + g.size);
    csv.fail(line.pos, fmt::format("the header {} {}: give the column{} {}",
                                   present == 0 ? "lacks" : "has only part of", g.meaning,
                                   g.size > 1 ? "s" : "", fmt::join(names, ", ")));
  }
  return h;
}

double number(const CsvText& csv, const Field& f, std::string_view column) {
  double x = 0;
  const char* end = f.text.data() + f.text.size();
  const auto [ptr, ec] = std::from_chars(f.text.data(), end, x);
  if (f.text.empty() || ec == std::errc::invalid_argument || ptr != end) {
    csv.fail(f.pos,
             fmt::format("column {}: expected a number, found \"{}\"", column,
                         f.text.size() > 40 ? std::string(f.text.substr(0, 40)) + "…" : std::string(f.text)));
  }
  if (ec == std::errc::result_out_of_range || !std::isfinite(x)) {
    csv.fail(f.pos, fmt::format("column {}: {} is not a finite double", column, f.text));
  }
  return x;
}

}  // namespace

void read_body_tables(const TableReader& root, const std::filesystem::path& directory, NameTable& names,
                      std::deque<std::string>& name_storage, Scene& scene) {
  const auto tables = root.tables("body_tables");
  for (size_t t = 0; t < tables.size(); ++t) {
    const TableReader table(*tables[t], Context::numbered("[[body_tables]] #", t + 1), root.file(),
                            {"file", "name_prefix", "angular_velocity_frame"});
    const std::string_view file =
        table.required_string("file", "the CSV file of bodies, e.g. file = \"debris.csv\"");
    const std::filesystem::path path = directory / file;
    scene.input_files.push_back(path);  // never to be overwritten by the run's outputs
    const CsvText csv(path.string(), [&] {
      try {
        return read_file(path, "body table");
      } catch (const FileError& e) {
        table.fail_at("file",
                      fmt::format("{}; the path is relative to the scene file's directory", e.what()));
      }
    }());
    const std::string prefix(table.string("name_prefix").value_or(path.stem().string() + "_"));
    const Frame omega_frame = table.frame("angular_velocity_frame", Frame::world);
    const std::string source = fmt::format("body table {}", file);

    std::vector<Field> fields;
    size_t pos = 0;
    const auto header_line = next_line(csv.view(), pos);
    if (!header_line)
      table.fail_at("file", fmt::format("{} has no header line: start it with e.g. "
                                        "name,mass,I1,I2,I3,px,py,pz,qw,qx,qy,qz,vx,vy,vz,wx,wy,wz",
                                        file));
    const Header h = read_header(csv, *header_line, fields);

    // Every row is a line: reserve for them all, so that a large table is placed once rather than
    // copied as the vectors grow (fresh memory costs more than the rows' numbers, bench/scene_setup).
    const auto lines = static_cast<size_t>(std::count(csv.view().begin(), csv.view().end(), '\n')) + 1;
    scene.model.bodies.reserve(scene.model.bodies.size() + lines);
    scene.initial.bodies.reserve(scene.initial.bodies.size() + lines);
    scene.body_info.reserve(scene.body_info.size() + lines);
    names.reserve(names.size() + lines);
    size_t row = 0;
    while (const auto line = next_line(csv.view(), pos)) {
      split(line->text, line->pos, fields);
      if (fields.size() != h.fields) {
        csv.fail(line->pos,
                 fmt::format("row {} has {} fields, the header {}", row + 1, fields.size(), h.fields));
      }
      std::array<double, kColumns> x{};
      x[qw] = 1.0;  // absent columns: at rest at the origin, identity orientation
      for (size_t c = 0; c < kColumns; ++c) {
        if (h.field[c] >= 0) x[c] = number(csv, fields[static_cast<size_t>(h.field[c])], kColumnNames[c]);
      }
      const Field at = fields[0];
      std::string& name =
          name_storage.emplace_back(h.name >= 0 ? std::string(fields[static_cast<size_t>(h.name)].text)
                                                : fmt::format("{}{}", prefix, row));
      if (!valid_name(name)) {
        csv.fail(h.name >= 0 ? fields[static_cast<size_t>(h.name)].pos : at.pos,
                 fmt::format("name \"{}\" is not allowed: use letters, digits, '_', '-' and '.' only", name));
      }
      const auto [it, inserted] =
          names.try_emplace(name, NameEntry{toml::source_position{}, false, scene.model.bodies.size()});
      if (!inserted) {
        csv.fail(at.pos,
                 fmt::format("row {}: duplicate name \"{}\": give every body and particle its own name",
                             row + 1, name));
      }
      RigidBody rigid = [&] {
        try {
          return RigidBody::from_principal_moments(x[mass], Vec3(x[I1], x[I2], x[I3]), name);
        } catch (const InvalidMassProperties& e) {
          csv.fail(at.pos, e.what());  // the message names the body
        }
      }();
      const double q_norm = std::sqrt(x[qw] * x[qw] + x[qx] * x[qx] + x[qy] * x[qy] + x[qz] * x[qz]);
      if (!(std::abs(q_norm - 1.0) <= kQuaternionNormSlack)) {
        csv.fail(fields[static_cast<size_t>(h.field[qw])].pos,
                 fmt::format("body '{}': the orientation has norm {:.6g}, more than {:g} from 1: give a unit "
                             "quaternion (qw, qx, qy, qz; w first)",
                             name, q_norm, kQuaternionNormSlack));
      }
      const Quat q(x[qw] / q_norm, x[qx] / q_norm, x[qy] / q_norm, x[qz] / q_norm);
      // The reference origin is the centre of mass, so velocity_of "origin" and "com" agree.
      scene.initial.bodies.push_back(state_from_reference(rigid, Vec3(x[px], x[py], x[pz]), q,
                                                          Vec3(x[vx], x[vy], x[vz]),
                                                          Vec3(x[wx], x[wy], x[wz]), omega_frame));
      scene.body_info.push_back(
          {source, MassProperties{x[mass], Vec3::Zero(), Vec3(x[I1], x[I2], x[I3]).asDiagonal(), 0.0}, {}});
      scene.model.add_body(std::move(rigid));
      ++row;
    }
    if (row == 0) table.fail_at("file", fmt::format("{} has a header but no rows: add a row per body", file));
  }
}

}  // namespace tumble::scene
