#pragma once
// Typed, located access to the tables of a scene file (toml++). Every accessor checks the type,
// length and domain of a value and throws SceneError "file:line:column: context: what was expected,
// what was found; how to fix" pointing at the value (or at the table when a key is missing). A reader
// is built with the keys its table may hold and rejects any other, suggesting the closest one.
//
// A scene has a table per body, and a reader is made for each, but at most one message is ever
// written: a reader keeps what it needs for messages (the table's name, the value's name) as pieces,
// and formats them only when it throws. Strings it returns are views into the parsed TOML, valid as
// long as that is.
#include <fmt/format.h>
#include "toml.hpp"

#include <cstdint>
#include <initializer_list>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "tumble/dynamics/state.hpp"
#include "tumble/io/scene.hpp"
#include "tumble/math/types.hpp"

namespace tumble::scene {

/// The file a parsed TOML text is from, for messages: its name as the user gave it, and the line of the
/// file the text starts at (a scene's [[bodies]] are parsed a section at a time: body_sections.hpp).
struct TomlFile {
  std::string name;
  std::uint32_t first_line = 1;

  /// A position in the parsed text as one in the file.
  toml::source_position in_file(toml::source_position p) const {
    p.line += first_line - 1;
    return p;
  }
};

/// "file:line:column" of a region of a parsed text.
std::string location(const TomlFile& file, const toml::source_region& where);

/// Throws SceneError "file:line:column: message".
[[noreturn]] void fail(const TomlFile& file, const toml::source_region& where, const std::string& message);

/// "a string", "an array", ... for messages about what was found.
std::string type_name(const toml::node& node);

/// The candidate closest to `word` by edit distance, if it is close enough to be a likely typo.
std::optional<std::string> closest(const std::string& word, const std::vector<std::string>& candidates);

/// What a number may be.
enum class Domain { finite, positive, non_negative };

/// The keys a table may hold, in the order a message lists them: a braced list where the call is
/// ({"name", "mass"}), or a span of them (the [simulation] keys of sim/run_settings.hpp). It refers to
/// the list, which must outlive the call.
class Keys {
 public:
  Keys(std::initializer_list<std::string_view> keys) : keys_(keys.begin(), keys.size()) {}
  explicit Keys(std::span<const std::string_view> keys) : keys_(keys) {}
  auto begin() const { return keys_.begin(); }
  auto end() const { return keys_.end(); }

 private:
  std::span<const std::string_view> keys_;
};

/// What a table is called in messages: "[simulation]", "[[bodies]] #3", "body 'handle' shape (box)".
/// Kept as pieces — the enclosing table's Context, text, a number, a name from the file — that are
/// joined by str() only for a message. The enclosing Context and the text must outlive this one (they
/// are the enclosing reader, literals and the parsed TOML).
class Context {
 public:
  /// A fixed name, e.g. "[simulation]".
  Context(const char* text) : text_(text) {}  // implicit: readers are given literals
  /// `prefix` and a number: "[[bodies]] #3".
  static Context numbered(std::string_view prefix, size_t number);
  /// `kind` and a name in quotes: "body 'handle'".
  static Context named(std::string_view kind, std::string_view name);
  /// This name followed by text, a name and more text: "body 'a'" + " shape", or + " (" "box" ")".
  Context child(std::string_view text, std::string_view name = {}, std::string_view after = {}) const;
  /// This name followed by text and a number: "body 'a'" + " part " 2.
  Context child_numbered(std::string_view text, size_t number) const;

  std::string str() const;

 private:
  Context() = default;
  const Context* parent_ = nullptr;
  std::string_view text_;
  std::optional<size_t> number_;
  std::string_view name_;
  bool quoted_ = false;  // "body 'handle'"
  std::string_view after_;
};

/// The name of a value in messages: a key ("position") or an element under it ("position[1]",
/// "inertia[0][2]").
struct ValueName {
  ValueName(std::string_view name, int index = -1, int index2 = -1)
      : key(name), i(index), j(index2) {}  // implicit: a key
  std::string str() const;

  std::string_view key;
  int i, j;  // indices, -1 where absent
};

class TableReader {
 public:
  /// `context` names the table in messages; `allowed` lists the keys it may contain; anything else
  /// throws with the closest allowed key suggested. `file` names the scene file in messages and must
  /// outlive the reader.
  TableReader(const toml::table& table, Context context, const TomlFile& file, Keys allowed);
  TableReader(const toml::table&, Context, TomlFile&&, Keys) = delete;  // `file` would dangle
  /// A reader that accepts any key: for reading a table's name, before a reader that checks the keys
  /// (and names the table in its messages) can be made.
  static TableReader any_keys(const toml::table& table, Context context, const TomlFile& file);

  const Context& context() const { return context_; }
  const TomlFile& file() const { return *file_; }
  const toml::table& table() const { return *table_; }
  bool has(std::string_view key) const { return table_->contains(key); }
  const toml::node* node(std::string_view key) const { return table_->get(key); }
  /// Where `key`'s value is, or the table itself when it is absent.
  const toml::source_region& where(std::string_view key) const;

  /// Throws at `key`'s value (or the table when absent): "file:l:c: context: message".
  [[noreturn]] void fail_at(std::string_view key, const std::string& message) const;
  /// Throws at the table's own position.
  [[noreturn]] void fail_here(const std::string& message) const;
  /// Throws unless exactly one of `keys` is present.
  void require_one_of(Keys keys) const;
  /// Throws if more than one of `keys` is present; returns whether one is.
  bool at_most_one_of(Keys keys) const;

  std::optional<double> number(std::string_view key, const char* unit, Domain domain = Domain::finite) const;
  double number(std::string_view key, double fallback, const char* unit,
                Domain domain = Domain::finite) const;
  double required_number(std::string_view key, const char* unit, Domain domain = Domain::finite) const;
  std::optional<std::string_view> string(std::string_view key) const;
  std::string_view required_string(std::string_view key, const char* what) const;
  std::optional<bool> boolean(std::string_view key) const;
  /// An array of exactly 3 finite numbers.
  std::optional<Vec3> vec3(std::string_view key, const char* unit, Domain domain = Domain::finite) const;
  Vec3 vec3(std::string_view key, const Vec3& fallback, const char* unit) const;
  /// An array of 4 numbers (w, x, y, z) of norm 1 ± kQuaternionNormSlack: normalised; else an error.
  /// `notes`, if given, receives a note on numbers that look like another order (scene_sanity.hpp).
  std::optional<Quat> quaternion(std::string_view key, std::vector<std::string>* notes = nullptr) const;
  /// An orientation: a unit quaternion [w, x, y, z], or a table { euler_zyx = [yaw, pitch, roll] },
  /// { euler_zxz = [phi, theta, psi] } or { axis = [x, y, z], angle = a } (rad; math/rotations.hpp).
  /// `notes`, if given, receives notes on angles that look like degrees and quaternions like (x, y, z, w).
  std::optional<Quat> rotation(std::string_view key, std::vector<std::string>* notes = nullptr) const;
  /// "world" or "body".
  Frame frame(std::string_view key, Frame fallback) const;
  /// A sub-table (inline or not) read with its own allowed keys.
  std::optional<TableReader> table(std::string_view key, Context context, Keys allowed) const;
  /// An array of tables (`[[key]]`, or an array of inline tables); empty when absent.
  std::vector<const toml::table*> tables(std::string_view key) const;

 private:
  TableReader(const toml::table& table, Context context, const TomlFile& file)
      : table_(&table), context_(context), file_(&file) {}
  [[noreturn]] void fail_unknown_key(const toml::key& key, Keys allowed) const;

  const toml::table* table_;
  Context context_;
  const TomlFile* file_;
};

/// Quaternions whose norm is within this of 1 are normalised silently: hand-typed values such as
/// [0.7071, 0.7071, 0, 0] (|q| − 1 ≈ −2e-5) are meant to be unit. Beyond it the value is not a
/// rotation written with a few digits, but a mistake (a missing component, degrees, (x, y, z, w)).
inline constexpr double kQuaternionNormSlack = 1e-3;

/// A number from a node already known to exist (integer or float), checked for finiteness and domain.
double number_value(const TableReader& reader, const toml::node& node, const ValueName& what,
                    const char* unit, Domain domain);

}  // namespace tumble::scene

/// Contexts and value names format as their text: fmt::format("{}: ...", reader.context()).
template <>
struct fmt::formatter<tumble::scene::Context> : fmt::formatter<std::string_view> {
  auto format(const tumble::scene::Context& c, format_context& ctx) const {
    return fmt::formatter<std::string_view>::format(c.str(), ctx);
  }
};
template <>
struct fmt::formatter<tumble::scene::ValueName> : fmt::formatter<std::string_view> {
  auto format(const tumble::scene::ValueName& v, format_context& ctx) const {
    return fmt::formatter<std::string_view>::format(v.str(), ctx);
  }
};
