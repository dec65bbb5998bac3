#include "scene_reader.hpp"

#include "scene_sanity.hpp"

#include "tumble/math/rotations.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace tumble::scene {

std::string location(const TomlFile& file, const toml::source_region& where) {
  const toml::source_position at = file.in_file(where.begin);
  return fmt::format("{}:{}:{}", file.name, at.line, at.column);
}

void fail(const TomlFile& file, const toml::source_region& where, const std::string& message) {
  throw SceneError(fmt::format("{}: {}", location(file, where), message));
}

std::string type_name(const toml::node& node) {
  switch (node.type()) {
    case toml::node_type::string:
      return fmt::format("the string \"{}\"", node.as_string()->get());
    case toml::node_type::integer:
      return fmt::format("the integer {}", node.as_integer()->get());
    case toml::node_type::floating_point:
      return fmt::format("the number {}", node.as_floating_point()->get());
    case toml::node_type::boolean:
      return fmt::format("the boolean {}", node.as_boolean()->get());
    case toml::node_type::array:
      return fmt::format("an array of {}", node.as_array()->size());
    case toml::node_type::table:
      return "a table";
    default:
      return "a date or time";
  }
}

namespace {

size_t edit_distance(const std::string& a, const std::string& b) {
  // Levenshtein distance, one row at a time.
  std::vector<size_t> row(b.size() + 1);
  for (size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (size_t i = 1; i <= a.size(); ++i) {
    size_t diagonal = row[0];
    row[0] = i;
    for (size_t j = 1; j <= b.size(); ++j) {
      const size_t up = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diagonal = up;
    }
  }
  return row[b.size()];
}

const char* domain_text(Domain d) {
  switch (d) {
    case Domain::positive:
      return "positive";
    case Domain::non_negative:
      return "zero or positive";
    case Domain::finite:
      break;
  }
  return "finite";
}

bool in_domain(double x, Domain d) {
  switch (d) {
    case Domain::positive:
      return x > 0;
    case Domain::non_negative:
      return x >= 0;
    case Domain::finite:
      break;
  }
  return true;
}

std::string with_unit(const char* unit) { return unit && *unit ? fmt::format(" ({})", unit) : ""; }

/// Whether `key` is one of `allowed`. Lengths and first letters are compared before the text: they
/// already tell most keys apart, and every key of every body table is checked.
bool is_allowed(std::string_view key, Keys allowed) {
  for (const std::string_view a : allowed) {
    if (a.size() == key.size() && a.front() == key.front() && a == key) return true;
  }
  return false;
}

}  // namespace

std::optional<std::string> closest(const std::string& word, const std::vector<std::string>& candidates) {
  std::optional<std::string> best;
  size_t best_d = 0;
  for (const auto& c : candidates) {
    const size_t d = edit_distance(word, c);
    if (!best || d < best_d) {
      best = c;
      best_d = d;
    }
  }
  // A typo changes a character or two, or a third of a long word; beyond that it is another word.
  if (best && (best_d <= 2 || best_d * 3 <= word.size())) return best;
  return std::nullopt;
}

Context Context::numbered(std::string_view prefix, size_t number) {
  Context c;
  c.text_ = prefix;
  c.number_ = number;
  return c;
}

Context Context::named(std::string_view kind, std::string_view name) {
  Context c;
  c.text_ = kind;
  c.name_ = name;
  c.quoted_ = true;
  return c;
}

Context Context::child(std::string_view text, std::string_view name, std::string_view after) const {
  Context c;
  c.parent_ = this;
  c.text_ = text;
  c.name_ = name;
  c.after_ = after;
  return c;
}

Context Context::child_numbered(std::string_view text, size_t number) const {
  Context c;
  c.parent_ = this;
  c.text_ = text;
  c.number_ = number;
  return c;
}

std::string Context::str() const {
  std::string s = parent_ ? parent_->str() : std::string();
  s += text_;
  if (number_) s += std::to_string(*number_);
  if (quoted_) {
    s += " '";
    s += name_;
    s += '\'';
  } else {
    s += name_;
  }
  s += after_;
  return s;
}

std::string ValueName::str() const {
  if (i < 0) return std::string(key);
  if (j < 0) return fmt::format("{}[{}]", key, i);
  return fmt::format("{}[{}][{}]", key, i, j);
}

double number_value(const TableReader& reader, const toml::node& node, const ValueName& what,
                    const char* unit, Domain domain) {
  if (!node.is_number()) {
    fail(reader.file(), node.source(),
         fmt::format("{}: {} must be a number{}, found {}", reader.context(), what, with_unit(unit),
                     type_name(node)));
  }
  const double x = node.value<double>().value_or(0.0);
  if (!std::isfinite(x)) {
    fail(reader.file(), node.source(),
         fmt::format("{}: {} is {}: give a finite number{}", reader.context(), what, x, with_unit(unit)));
  }
  if (!in_domain(x, domain)) {
    fail(reader.file(), node.source(),
         fmt::format("{}: {} is {}{}: it must be {}", reader.context(), what, x,
                     unit && *unit ? std::string(" ") + unit : "", domain_text(domain)));
  }
  return x;
}

TableReader::TableReader(const toml::table& table, Context context, const TomlFile& file, Keys allowed)
    : TableReader(table, context, file) {
  for (auto&& [k, v] : table) {
    if (!is_allowed(k.str(), allowed)) fail_unknown_key(k, allowed);
  }
}

TableReader TableReader::any_keys(const toml::table& table, Context context, const TomlFile& file) {
  return TableReader(table, context, file);
}

void TableReader::fail_unknown_key(const toml::key& k, Keys allowed) const {
  const std::vector<std::string> keys(allowed.begin(), allowed.end());
  const std::string key(k.str());
  const auto suggestion = closest(key, keys);
  fail(file(), k.source(),
       fmt::format("{}: unknown key '{}'; {}", context_, key,
                   suggestion ? fmt::format("did you mean '{}'?", *suggestion)
                              : fmt::format("the keys here are: {}", fmt::join(keys, ", "))));
}

const toml::source_region& TableReader::where(std::string_view key) const {
  const toml::node* n = node(key);
  return n ? n->source() : table_->source();
}

void TableReader::fail_at(std::string_view key, const std::string& message) const {
  fail(file(), where(key), fmt::format("{}: {}", context_, message));
}

void TableReader::fail_here(const std::string& message) const {
  fail(file(), table_->source(), fmt::format("{}: {}", context_, message));
}

void TableReader::require_one_of(Keys keys) const {
  if (!at_most_one_of(keys)) fail_here(fmt::format("missing {}: give one of them", fmt::join(keys, " or ")));
}

bool TableReader::at_most_one_of(Keys keys) const {
  const std::string_view* first = nullptr;
  for (const auto& k : keys) {
    if (!has(k)) continue;
    if (first) {
      fail_at(k, fmt::format("'{}' and '{}' exclude each other: keep one", *first, k));
    }
    first = &k;
  }
  return first != nullptr;
}

std::optional<double> TableReader::number(std::string_view key, const char* unit, Domain domain) const {
  const toml::node* n = node(key);
  if (!n) return std::nullopt;
  return number_value(*this, *n, key, unit, domain);
}

double TableReader::number(std::string_view key, double fallback, const char* unit, Domain domain) const {
  return number(key, unit, domain).value_or(fallback);
}

double TableReader::required_number(std::string_view key, const char* unit, Domain domain) const {
  const auto x = number(key, unit, domain);
  if (!x)
    fail_here(fmt::format("missing '{}': give a {} number{}", key, domain_text(domain), with_unit(unit)));
  return *x;
}

std::optional<std::string_view> TableReader::string(std::string_view key) const {
  const toml::node* n = node(key);
  if (!n) return std::nullopt;
  if (!n->is_string()) fail_at(key, fmt::format("{} must be a string, found {}", key, type_name(*n)));
  return std::string_view(n->as_string()->get());
}

std::string_view TableReader::required_string(std::string_view key, const char* what) const {
  const auto s = string(key);
  if (!s) fail_here(fmt::format("missing '{}': give {}", key, what));
  return *s;
}

std::optional<bool> TableReader::boolean(std::string_view key) const {
  const toml::node* n = node(key);
  if (!n) return std::nullopt;
  if (!n->is_boolean()) {
    fail_at(key, fmt::format("{} must be true or false, found {}", key, type_name(*n)));
  }
  return n->as_boolean()->get();
}

std::optional<Vec3> TableReader::vec3(std::string_view key, const char* unit, Domain domain) const {
  const toml::node* n = node(key);
  if (!n) return std::nullopt;
  const toml::array* a = n->as_array();
  if (!a || a->size() != 3) {
    fail_at(key,
            fmt::format("{} must be an array of 3 numbers{}, found {}", key, with_unit(unit), type_name(*n)));
  }
  Vec3 v;
  for (int i = 0; i < 3; ++i)
    v(i) = number_value(*this, *a->get(static_cast<size_t>(i)), {key, i}, unit, domain);
  return v;
}

Vec3 TableReader::vec3(std::string_view key, const Vec3& fallback, const char* unit) const {
  return vec3(key, unit, Domain::finite).value_or(fallback);
}

std::optional<Quat> TableReader::quaternion(std::string_view key, std::vector<std::string>* notes) const {
  const toml::node* n = node(key);
  if (!n) return std::nullopt;
  const toml::array* a = n->as_array();
  if (!a || a->size() != 4) {
    fail_at(key, fmt::format("{} must be a unit quaternion [w, x, y, z], found {}", key, type_name(*n)));
  }
  Eigen::Vector4d wxyz;
  for (int i = 0; i < 4; ++i) {
    wxyz(i) = number_value(*this, *a->get(static_cast<size_t>(i)), {key, i}, "", Domain::finite);
  }
  if (notes) {
    if (auto note = quaternion_order(key, wxyz))
      notes->push_back(location(file(), where(key)) + ": " + *note);
  }
  const double norm = wxyz.norm();
  if (!(std::abs(norm - 1.0) <= kQuaternionNormSlack)) {
    const std::string hint = norm > 0
                                 ? fmt::format("; normalised it would be [{:.6g}, {:.6g}, {:.6g}, {:.6g}]",
                                               wxyz(0) / norm, wxyz(1) / norm, wxyz(2) / norm, wxyz(3) / norm)
                                 : "";
    fail_at(key, fmt::format("{} has norm {:.6g}, more than {:g} from 1: give a unit quaternion "
                             "[w, x, y, z] (w first){}",
                             key, norm, kQuaternionNormSlack, hint));
  }
  wxyz /= norm;
  return Quat(wxyz(0), wxyz(1), wxyz(2), wxyz(3));
}

std::optional<Quat> TableReader::rotation(std::string_view key, std::vector<std::string>* notes) const {
  const toml::node* n = node(key);
  if (!n || !n->is_table()) return quaternion(key, notes);
  const TableReader t(*n->as_table(), context_.child(" ", key), *file_,
                      {"euler_zyx", "euler_zxz", "axis", "angle", "mrp"});
  const bool zyx = t.has("euler_zyx"), zxz = t.has("euler_zxz"), axis = t.has("axis") || t.has("angle"),
             sigma = t.has("mrp");
  if (zyx + zxz + axis + sigma != 1) {
    fail_at(key, fmt::format("{} as a table takes one of euler_zyx = [yaw, pitch, roll], euler_zxz = [phi, "
                             "theta, psi], axis = [x, y, z] with angle = a (rad), or mrp = [s1, s2, s3] "
                             "(modified Rodrigues parameters); or give a unit quaternion [w, x, y, z]",
                             key));
  }
  if (sigma) return from_mrp(*t.vec3("mrp", ""));  // any σ: a set and its shadow are one rotation
  // Angles beyond a full turn are probably degrees: a note, with the radians they would be.
  const auto check = [&](std::string_view angles_key, const Eigen::VectorXd& angles) {
    if (!notes) return;
    if (auto note = angles_in_degrees(angles_key, angles))
      notes->push_back(location(file(), t.where(angles_key)) + ": " + *note);
  };
  if (zyx || zxz) {
    const char* const which = zyx ? "euler_zyx" : "euler_zxz";
    const Vec3 angles = *t.vec3(which, "rad");
    check(which, angles);
    return Quat(zyx ? from_euler_zyx(angles) : from_euler_zxz(angles));
  }
  const Vec3 a = t.vec3("axis", Vec3::Zero(), "");
  if (!(a.norm() > 0))
    t.fail_at(t.has("axis") ? "axis" : "angle", "axis must be a non-zero vector [x, y, z]");
  const double angle = t.required_number("angle", "rad");
  check("angle", Eigen::VectorXd::Constant(1, angle));
  return Quat(Eigen::AngleAxisd(angle, a.normalized()));
}

Frame TableReader::frame(std::string_view key, Frame fallback) const {
  const auto s = string(key);
  if (!s) return fallback;
  if (*s == "world") return Frame::world;
  if (*s == "reference" || *s == "body") return Frame::reference;  // "body": the older name
  if (*s == "principal") return Frame::principal;
  fail_at(key, fmt::format("{} must be \"world\", \"reference\" (the body's own axes; \"body\" is the "
                           "older name) or \"principal\" (its principal axes), found \"{}\"",
                           key, *s));
}

std::optional<TableReader> TableReader::table(std::string_view key, Context context, Keys allowed) const {
  const toml::node* n = node(key);
  if (!n) return std::nullopt;
  if (!n->is_table()) fail_at(key, fmt::format("{} must be a table {{ ... }}, found {}", key, type_name(*n)));
  return TableReader(*n->as_table(), context, file(), allowed);
}

std::vector<const toml::table*> TableReader::tables(std::string_view key) const {
  std::vector<const toml::table*> out;
  const toml::node* n = node(key);
  if (!n) return out;
  const toml::array* a = n->as_array();
  if (!a)
    fail_at(key, fmt::format("{} must be an array of tables ([[{}]]), found {}", key, key, type_name(*n)));
  out.reserve(a->size());
  for (const toml::node& element : *a) {
    if (!element.is_table()) {
      fail(file(), element.source(),
           fmt::format("{}: each entry of {} must be a table, found {}", context_, key, type_name(element)));
    }
    out.push_back(element.as_table());
  }
  return out;
}

}  // namespace tumble::scene
