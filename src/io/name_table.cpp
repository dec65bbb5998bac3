#include "name_table.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <functional>

#include "tumble/io/scene.hpp"

namespace tumble::scene {
namespace {

std::uint64_t hash_of(std::string_view name) { return std::hash<std::string_view>{}(name); }

/// Whether a comes before b in the file (bodies before particles).
bool in_file_order(const NameTable::Entry& a, const NameTable::Entry& b) {
  return a.is_particle != b.is_particle ? b.is_particle : a.index < b.index;
}
/// The order of the sorted records: by hash, then in file order.
bool before(const NameTable::Entry& a, const NameTable::Entry& b) {
  return a.hash != b.hash ? a.hash < b.hash : in_file_order(a, b);
}

}  // namespace

std::uint32_t NameTable::add_origin(std::string file, size_t first_body) {
  origins_.push_back({std::move(file), first_body});
  return static_cast<std::uint32_t>(origins_.size() - 1);
}

void NameTable::add(std::string_view name, bool is_particle, size_t index, std::uint32_t origin,
                    std::uint32_t line, std::uint32_t column) {
  Entry e{};
  e.hash = hash_of(name);
  e.index = static_cast<std::uint32_t>(index);
  e.line = line;
  e.column = column;
  e.origin = origin;
  e.is_particle = is_particle;
  entries_.push_back(e);
}

std::string NameTable::context_of(const Entry& e) const {
  if (e.origin == 0) return fmt::format("[[{}]] #{}", e.is_particle ? "particles" : "bodies", e.index + 1);
  return fmt::format("row {}", e.index - origins_[e.origin].first_body + 1);
}

void NameTable::seal() {
  std::sort(entries_.begin(), entries_.end(), before);
  // Equal names are neighbours within a run of equal hashes, earlier in the file first. Of every pair,
  // the one reported is the repeat that comes first in the file, as if the names were checked in turn.
  const Entry* repeat = nullptr;
  const Entry* first = nullptr;
  for (size_t a = 0, b = 0; a < entries_.size(); a = b) {
    while (b < entries_.size() && entries_[b].hash == entries_[a].hash) ++b;
    for (size_t k = a + 1; k < b; ++k) {
      for (size_t m = a; m < k; ++m) {
        if (name_of(entries_[m]) != name_of(entries_[k])) continue;
        if (!repeat || in_file_order(entries_[k], *repeat)) {
          repeat = &entries_[k];
          first = &entries_[m];
        }
        break;
      }
    }
  }
  if (!repeat) return;
  const std::string& file = origins_[repeat->origin].file;
  const std::string there =
      first->origin == repeat->origin
          ? fmt::format("line {}, column {}", first->line, first->column)
          : fmt::format("{}:{}:{}", origins_[first->origin].file, first->line, first->column);
  throw SceneError(fmt::format(
      "{}:{}:{}: {}: duplicate name \"{}\" (first defined at {}): give every body and particle its own name",
      file, repeat->line, repeat->column, context_of(*repeat), name_of(*repeat), there));
}

const NameTable::Entry* NameTable::find(std::string_view name) const {
  const std::uint64_t h = hash_of(name);
  auto it = std::lower_bound(entries_.begin(), entries_.end(), h,
                             [](const Entry& e, std::uint64_t key) { return e.hash < key; });
  for (; it != entries_.end() && it->hash == h; ++it) {
    if (name_of(*it) == name) return &*it;
  }
  return nullptr;
}

}  // namespace tumble::scene
