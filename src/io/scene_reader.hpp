#pragma once
// Typed, located access to the tables of a scene file (toml++). Every accessor checks the type,
// length and domain of a value and throws SceneError "file:line:column: context: what was expected,
// what was found; how to fix" pointing at the value (or at the table when a key is missing). A reader
// is built with the keys its table may hold and rejects any other, suggesting the closest one.
#include <toml++/toml.h>

#include <optional>
#include <string>
#include <vector>

#include "tumble/dynamics/state.hpp"
#include "tumble/io/scene.hpp"
#include "tumble/math/types.hpp"

namespace tumble::scene {

/// "file:line:column" of a region of the scene file.
std::string location(const std::string& file, const toml::source_region& where);

/// Throws SceneError "file:line:column: message".
[[noreturn]] void fail(const std::string& file, const toml::source_region& where, const std::string& message);

/// "a string", "an array", ... for messages about what was found.
std::string type_name(const toml::node& node);

/// The candidate closest to `word` by edit distance, if it is close enough to be a likely typo.
std::optional<std::string> closest(const std::string& word, const std::vector<std::string>& candidates);

/// What a number may be.
enum class Domain { finite, positive, non_negative };

class TableReader {
 public:
  /// `context` names the table in messages ("[simulation]", "body 'handle'"); `allowed` lists the
  /// keys it may contain; anything else throws with the closest allowed key suggested.
  TableReader(const toml::table& table, std::string context, std::string file,
              std::vector<std::string> allowed);

  const std::string& context() const { return context_; }
  const std::string& file() const { return file_; }
  const toml::table& table() const { return *table_; }
  bool has(const std::string& key) const { return table_->contains(key); }
  const toml::node* node(const std::string& key) const { return table_->get(key); }
  /// Where `key`'s value is, or the table itself when it is absent.
  const toml::source_region& where(const std::string& key) const;

  /// Throws at `key`'s value (or the table when absent): "file:l:c: context: message".
  [[noreturn]] void fail_at(const std::string& key, const std::string& message) const;
  /// Throws at the table's own position.
  [[noreturn]] void fail_here(const std::string& message) const;
  /// Throws unless exactly `count` of `keys` are present (0 or 1 for count = 1 with optional).
  void require_one_of(const std::vector<std::string>& keys) const;
  void at_most_one_of(const std::vector<std::string>& keys) const;

  std::optional<double> number(const std::string& key, const char* unit,
                               Domain domain = Domain::finite) const;
  double number(const std::string& key, double fallback, const char* unit,
                Domain domain = Domain::finite) const;
  double required_number(const std::string& key, const char* unit, Domain domain = Domain::finite) const;
  std::optional<std::string> string(const std::string& key) const;
  std::string required_string(const std::string& key, const char* what) const;
  std::optional<bool> boolean(const std::string& key) const;
  /// An array of exactly 3 finite numbers.
  std::optional<Vec3> vec3(const std::string& key, const char* unit, Domain domain = Domain::finite) const;
  Vec3 vec3(const std::string& key, const Vec3& fallback, const char* unit) const;
  /// An array of 4 numbers (w, x, y, z) of norm 1 ± kQuaternionNormSlack: normalised; else an error.
  std::optional<Quat> quaternion(const std::string& key) const;
  /// "world" or "body".
  Frame frame(const std::string& key, Frame fallback) const;
  /// A sub-table (inline or not) read with its own allowed keys.
  std::optional<TableReader> table(const std::string& key, const std::string& context,
                                   std::vector<std::string> allowed) const;
  /// An array of tables (`[[key]]`, or an array of inline tables); empty when absent.
  std::vector<const toml::table*> tables(const std::string& key) const;

 private:
  const toml::table* table_;
  std::string context_;
  std::string file_;
};

/// Quaternions whose norm is within this of 1 are normalised silently: hand-typed values such as
/// [0.7071, 0.7071, 0, 0] (|q| − 1 ≈ −2e-5) are meant to be unit. Beyond it the value is not a
/// rotation written with a few digits, but a mistake (a missing component, degrees, (x, y, z, w)).
inline constexpr double kQuaternionNormSlack = 1e-3;

/// A number from a node already known to exist (integer or float), checked for finiteness and domain.
double number_value(const TableReader& reader, const std::string& key, const toml::node& node,
                    const std::string& what, const char* unit, Domain domain);

}  // namespace tumble::scene
