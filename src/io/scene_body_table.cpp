// [[body_tables]]: many bodies from one CSV file, a row per body, for scenes of 10⁴–10⁶ bodies.
//
// A [[bodies]] table costs about 30 µs to set up, 25 of them in toml++ building and freeing its tree
// (bench/scene_setup); a row of numbers read straight with std::from_chars costs about 1. No CSV
// library is among the dependencies, and this format needs none: a header of known column names, then
// numbers (and an optional name) separated by commas; '#' lines and blank lines are skipped.
//
// The file is read a megabyte at a time, never whole: a table of 10⁵ rows is 35 MB of text, and on a
// virtual machine the first touch of each fresh page of it cost more than parsing the rows.
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
#include "tumble/mass/input_file.hpp"
#include "tumble/math/huge_pages.hpp"

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

/// A line of the file (without its end) and its number, from 1.
struct Line {
  std::string_view text;
  std::uint32_t number;
};
/// A field of a line and its column, from 1.
struct Field {
  std::string_view text;
  std::uint32_t column;
};

/// The lines of a CSV file, read a piece at a time, and messages "file:line:column: ..." about them.
class CsvLines {
 public:
  CsvLines(const std::filesystem::path& path) : file_(path, "body table"), path_(path.string()) {
    buffer_.resize(kPiece);
  }
  const std::string& path() const { return path_; }

  /// The next line that is neither blank nor a '#' comment; its text is valid until the next call.
  std::optional<Line> next() {
    while (true) {
      size_t end = std::string_view(buffer_).substr(begin_, filled_ - begin_).find('\n');
      while (end == std::string_view::npos && fill()) {
        end = std::string_view(buffer_).substr(begin_, filled_ - begin_).find('\n');
      }
      if (begin_ == filled_) return std::nullopt;  // the file ended after a line end
      const size_t length = end == std::string_view::npos ? filled_ - begin_ : end;
      const Line line{std::string_view(buffer_).substr(begin_, length), ++line_number_};
      begin_ += std::min(length + 1, filled_ - begin_);
      const size_t first = line.text.find_first_not_of(" \t\r");
      if (first != std::string_view::npos && line.text[first] != '#') return line;
    }
  }

  /// About how many rows (lines neither blank nor comments) the file has, from those in the buffer: all
  /// of them when it holds the whole file. Blank lines do not count, so a file of nothing but line ends
  /// reserves nothing.
  size_t estimated_rows() const {
    const std::string_view held(buffer_.data(), filled_);
    size_t rows = 0;
    for (size_t pos = 0; pos < held.size();) {
      const size_t end = std::min(held.find('\n', pos), held.size());
      const size_t first = held.find_first_not_of(" \t\r", pos);
      rows += first < end && held[first] != '#';
      pos = end + 1;
    }
    if (filled_ == file_.size()) return rows;
    // 2 % more: rows vary in length, and a vector that outgrows its reservation is copied whole.
    return static_cast<size_t>(1.02 * static_cast<double>(file_.size()) / static_cast<double>(filled_) *
                               static_cast<double>(rows + 1));
  }

  [[noreturn]] void fail(std::uint32_t line, std::uint32_t column, const std::string& message) const {
    throw SceneError(fmt::format("{}:{}:{}: {}", path_, line, column, message));
  }

 private:
  static constexpr size_t kPiece = size_t{1} << 20;

  /// Moves the unread bytes to the front and reads more after them; false at the end of the file. A
  /// line longer than the buffer doubles it.
  bool fill() {
    std::copy(buffer_.begin() + static_cast<std::ptrdiff_t>(begin_),
              buffer_.begin() + static_cast<std::ptrdiff_t>(filled_), buffer_.begin());
    filled_ -= begin_;
    begin_ = 0;
    if (filled_ == buffer_.size()) buffer_.resize(2 * buffer_.size());
    const size_t got = file_.read(buffer_.data() + filled_, buffer_.size() - filled_);
    filled_ += got;
    return got > 0;
  }

  InputFile file_;
  std::string path_;
  std::string buffer_;
  size_t begin_ = 0, filled_ = 0;  // the unread bytes are buffer_[begin_, filled_)
  std::uint32_t line_number_ = 0;
};

/// Splits a line at commas, trimming blanks; `fields` is reused between rows.
void split(std::string_view line, std::vector<Field>& fields) {
  fields.clear();
  size_t start = 0;
  while (true) {
    const size_t comma = std::min(line.find(',', start), line.size());
    size_t a = start, b = comma;
    while (a < b && (line[a] == ' ' || line[a] == '\t')) ++a;
    while (b > a && (line[b - 1] == ' ' || line[b - 1] == '\t' || line[b - 1] == '\r')) --b;
    fields.push_back({line.substr(a, b - a), static_cast<std::uint32_t>(a + 1)});
    if (comma == line.size()) return;
    start = comma + 1;
  }
}

/// The header: which field holds each column (-1: absent) and which holds the name.
struct Header {
  std::array<int, kColumns> field;
  int name = -1;
  size_t fields = 0;
};

Header read_header(const CsvLines& csv, const Line& line, std::vector<Field>& fields) {
  split(line.text, fields);
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
      csv.fail(line.number, fields[i].column,
               fmt::format("unknown column \"{}\"; {}the columns are: name, {}", word,
                           close ? fmt::format("did you mean \"{}\"? ", *close) : "",
                           fmt::join(kColumnNames, ", ")));
    }
    if (*slot >= 0)
      csv.fail(line.number, fields[i].column, fmt::format("column \"{}\" appears twice in the header", word));
    *slot = static_cast<int>(i);
  }
  for (const Group& g : kGroups) {
    int present = 0;
    for (int c = g.first; c < g.first + g.size; ++c) present += h.field[static_cast<size_t>(c)] >= 0;
    if (present == g.size || (present == 0 && !g.required)) continue;
    std::vector<std::string_view> names(kColumnNames.begin() + g.first,
                                        kColumnNames.begin() + g.first + g.size);
    csv.fail(line.number, 1,
             fmt::format("the header {} {}: give the column{} {}",
                         present == 0 ? "lacks" : "has only part of", g.meaning, g.size > 1 ? "s" : "",
                         fmt::join(names, ", ")));
  }
  return h;
}

double number(const CsvLines& csv, std::uint32_t line, const Field& f, std::string_view column) {
  double x = 0;
  const char* end = f.text.data() + f.text.size();
  const auto [ptr, ec] = std::from_chars(f.text.data(), end, x);
  if (f.text.empty() || ec == std::errc::invalid_argument || ptr != end) {
    csv.fail(line, f.column,
             fmt::format("column {}: expected a number, found \"{}\"", column,
                         f.text.size() > 40 ? std::string(f.text.substr(0, 40)) + "…" : std::string(f.text)));
  }
  if (ec == std::errc::result_out_of_range || !std::isfinite(x)) {
    csv.fail(line, f.column, fmt::format("column {}: {} is not a finite double", column, f.text));
  }
  return x;
}

/// The rows of one body table into `scene`, their names into `names`.
void read_rows(CsvLines& csv, const TableReader& table, std::string_view file, NameTable& names,
               Scene& scene) {
  std::string prefix(table.string("name_prefix").value_or(std::filesystem::path(file).stem().string() + "_"));
  const Frame omega_frame = table.frame("angular_velocity_frame", Frame::world);
  const auto source = std::make_shared<const std::string>(fmt::format("body table {}", file));  // every row's
  const std::uint32_t origin = names.add_origin(csv.path(), scene.model.bodies.size());

  std::vector<Field> fields;
  const auto header_line = csv.next();
  if (!header_line)
    table.fail_at("file", fmt::format("{} has no header line: start it with e.g. "
                                      "name,mass,I1,I2,I3,px,py,pz,qw,qx,qy,qz,vx,vy,vz,wx,wy,wz",
                                      file));
  const Header h = read_header(csv, *header_line, fields);

  // Reserved for every row at once, so that a large table is placed once rather than copied as the
  // vectors grow (fresh memory costs more than the rows' numbers, bench/scene_setup).
  const size_t rows = csv.estimated_rows();
  scene.model.bodies.reserve(scene.model.bodies.size() + rows);
  scene.initial.bodies.reserve(scene.initial.bodies.size() + rows);
  scene.body_info.reserve(scene.body_info.size() + rows);
  names.reserve(rows);
  prefer_huge_pages(scene.model.bodies);
  prefer_huge_pages(scene.initial.bodies);
  prefer_huge_pages(scene.body_info);
  size_t row = 0;
  while (const auto line = csv.next()) {
    split(line->text, fields);
    if (fields.size() != h.fields) {
      csv.fail(line->number, 1,
               fmt::format("row {} has {} fields, the header {}", row + 1, fields.size(), h.fields));
    }
    std::array<double, kColumns> x{};
    x[qw] = 1.0;  // absent columns: at rest at the origin, identity orientation
    for (size_t c = 0; c < kColumns; ++c) {
      if (h.field[c] >= 0)
        x[c] = number(csv, line->number, fields[static_cast<size_t>(h.field[c])], kColumnNames[c]);
    }
    const Field& name_field = h.name >= 0 ? fields[static_cast<size_t>(h.name)] : fields[0];
    std::string name = h.name >= 0 ? std::string(name_field.text) : prefix + std::to_string(row);
    if (!valid_name(name)) {
      csv.fail(line->number, name_field.column,
               fmt::format("name \"{}\" is not allowed: use letters, digits, '_', '-' and '.' only", name));
    }
    names.add(name, false, scene.model.bodies.size(), origin, line->number, name_field.column);
    RigidBody rigid = [&] {
      try {
        return RigidBody::from_principal_moments(x[mass], Vec3(x[I1], x[I2], x[I3]), std::move(name));
      } catch (const InvalidMassProperties& e) {
        csv.fail(line->number, fields[0].column, e.what());  // the message names the body
      }
    }();
    const double q_norm = std::sqrt(x[qw] * x[qw] + x[qx] * x[qx] + x[qy] * x[qy] + x[qz] * x[qz]);
    if (!(std::abs(q_norm - 1.0) <= kQuaternionNormSlack)) {
      csv.fail(line->number, fields[static_cast<size_t>(h.field[qw])].column,
               fmt::format("body '{}': the orientation has norm {:.6g}, more than {:g} from 1: give a unit "
                           "quaternion (qw, qx, qy, qz; w first)",
                           rigid.name(), q_norm, kQuaternionNormSlack));
    }
    const Quat q(x[qw] / q_norm, x[qx] / q_norm, x[qy] / q_norm, x[qz] / q_norm);
    // The reference origin is the centre of mass, so velocity_of "origin" and "com" agree.
    scene.initial.bodies.push_back(state_from_reference(rigid, Vec3(x[px], x[py], x[pz]), q,
                                                        Vec3(x[vx], x[vy], x[vz]), Vec3(x[wx], x[wy], x[wz]),
                                                        omega_frame));
    scene.body_info.push_back({source, nullptr});
    scene.model.add_body(std::move(rigid));
    ++row;
  }
  if (row == 0) table.fail_at("file", fmt::format("{} has a header but no rows: add a row per body", file));
}

}  // namespace

void read_body_tables(const TableReader& root, const std::filesystem::path& directory, NameTable& names,
                      Scene& scene) {
  const auto tables = root.tables("body_tables");
  for (size_t t = 0; t < tables.size(); ++t) {
    const TableReader table(*tables[t], Context::numbered("[[body_tables]] #", t + 1), root.file(),
                            {"file", "name_prefix", "angular_velocity_frame"});
    const std::string_view file =
        table.required_string("file", "the CSV file of bodies, e.g. file = \"debris.csv\"");
    const std::filesystem::path path = directory / file;
    scene.input_files.push_back(path);  // never to be overwritten by the run's outputs
    try {
      CsvLines csv(path);
      read_rows(csv, table, file, names, scene);
    } catch (const FileError& e) {  // it cannot be opened, or it shrank while it was read
      table.fail_at("file", fmt::format("cannot read body table {}; the path is relative to the scene file's "
                                        "directory",
                                        e.what()));
    }
  }
}

}  // namespace tumble::scene
