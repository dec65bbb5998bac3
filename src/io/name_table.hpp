#pragma once
// The names of a scene's bodies and particles: one namespace, since both are rows of the same
// trajectory. [[forces]] and [[events]] name them; every name must be unique.
//
// A scene of 10⁵ bodies registers 10⁵ names. A hash table costs a node and a cache miss for each (a
// fifth of a [[body_tables]] row's set-up, bench/scene_setup); here a name is a 24-byte record appended
// in file order — its hash, what it names, where it is written — and the records are sorted once, when
// every name is in (`seal`), which finds the duplicates; a look-up is a binary search on the hash. The
// names themselves stay where they are: in the model (RigidBody::name, Particle::name).
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "tumble/forces/model.hpp"
#include "tumble/math/huge_pages.hpp"

namespace tumble::scene {

class NameTable {
 public:
  /// What a name names.
  struct Entry {
    std::uint64_t hash;
    std::uint32_t index;        ///< in model.bodies or model.particles
    std::uint32_t line;         ///< where the name is written (1-based; 0: nowhere)
    std::uint32_t column;       ///< its column (1-based)
    std::uint32_t origin : 31;  ///< the file: 0 the scene, k a [[body_tables]] file (add_origin)
    std::uint32_t is_particle : 1;
  };

  /// The table reads the names from `model` (from seal() on), which must outlive it; `scene_file` names
  /// the scene in messages.
  NameTable(const Model& model, std::string scene_file) : model_(&model) {
    origins_.push_back({std::move(scene_file), 0});
  }

  /// A [[body_tables]] file whose rows name bodies from model.bodies[first_body] on: its number for add().
  std::uint32_t add_origin(std::string file, size_t first_body);
  void reserve(size_t names) {
    entries_.reserve(entries_.size() + names);
    prefer_huge_pages(entries_);
  }
  /// Registers `name` of body `index` (or particle `index`), written at line:column of `origin`. Bodies
  /// come before particles, each in file order; by seal() the model holds them under these names.
  void add(std::string_view name, bool is_particle, size_t index, std::uint32_t origin, std::uint32_t line,
           std::uint32_t column);
  /// Sorts the names for look-ups. Throws SceneError for the first name, in file order, that repeats
  /// an earlier one, at its place: "file:line:column: [[bodies]] #3: duplicate name "a" (first defined
  /// at line 4, column 8): give every body and particle its own name".
  void seal();

  /// The entry of `name`, or null. After seal().
  const Entry* find(std::string_view name) const;

 private:
  struct Origin {
    std::string file;
    size_t first_body;  // a body table's first row
  };
  const std::string& name_of(const Entry& e) const {
    return e.is_particle ? model_->particles[e.index].name : model_->bodies[e.index].name();
  }
  /// "[[bodies]] #3" or "row 2": what a message about the entry names first.
  std::string context_of(const Entry& e) const;

  const Model* model_;
  std::vector<Origin> origins_;
  std::vector<Entry> entries_;
};

}  // namespace tumble::scene
