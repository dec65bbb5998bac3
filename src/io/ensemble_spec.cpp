// [ensemble]: the study a scene file describes (ensemble.hpp) and the paths that address its values.
#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <numeric>

#include "ensemble_impl.hpp"
#include "tumble/error.hpp"
#include "tumble/sim/output_fields.hpp"

namespace tumble::ensemble {
namespace {

constexpr std::string_view kKinds[] = {"uniform",  "normal",    "lognormal", "truncated_normal",
                                       "rotation", "direction", "list",      "grid"};

/// The arrays of tables whose elements a path may name by their `name`.
bool named_array(std::string_view key) {
  return key == "bodies" || key == "particles" || key == "forces" || key == "events" || key == "body_tables";
}

}  // namespace

toml::node* resolve(toml::table& root, const std::string& path, std::string& error) {
  toml::node* node = &root;
  std::string_view rest = path;
  std::string walked;
  while (!rest.empty()) {
    // The next key: up to '.' or '['; a name in a named array may itself hold dots, so the longest
    // matching name is taken.
    toml::table* table = node->as_table();
    if (table == nullptr) {
      error = fmt::format("{} is not a table", walked.empty() ? "the scene" : walked);
      return nullptr;
    }
    const size_t end = rest.find_first_of(".[");
    const std::string key(rest.substr(0, end));
    node = table->get(key);
    if (node == nullptr) {
      error = fmt::format(
          "{}{} is not in the scene: write it in the file (with its default value if need be) so "
          "that the ensemble can vary it",
          walked.empty() ? std::string() : fmt::format("{}.", walked), key);
      return nullptr;
    }
    walked = walked.empty() ? key : fmt::format("{}.{}", walked, key);
    rest = end == std::string_view::npos ? std::string_view() : rest.substr(end);
    if (named_array(key) && node->is_array_of_tables() && !rest.empty() && rest.front() == '.') {
      rest.remove_prefix(1);
      toml::array& items = *node->as_array();
      toml::node* found = nullptr;
      size_t length = 0;
      for (toml::node& item : items) {
        const auto name = item.as_table()->get_as<std::string>("name");
        if (!name) continue;
        const std::string& n = name->get();
        if (rest.substr(0, n.size()) == n &&
            (rest.size() == n.size() || rest[n.size()] == '.' || rest[n.size()] == '[') &&
            n.size() > length) {
          found = &item;
          length = n.size();
        }
      }
      if (found == nullptr) {
        error =
            fmt::format("no element of {} is named \"{}\"", walked, rest.substr(0, rest.find_first_of(".[")));
        return nullptr;
      }
      walked = fmt::format("{}.{}", walked, rest.substr(0, length));
      rest.remove_prefix(length);
      node = found;
    }
    while (!rest.empty() && rest.front() == '[') {
      const size_t close = rest.find(']');
      size_t index = 0;
      const auto [p, ec] = std::from_chars(
          rest.data() + 1, rest.data() + (close == std::string_view::npos ? 1 : close), index);
      if (close == std::string_view::npos || ec != std::errc() || p != rest.data() + close) {
        error = fmt::format("'{}' is not an index [k] in {}",
                            rest.substr(0, close == std::string_view::npos ? rest.size() : close + 1), path);
        return nullptr;
      }
      toml::array* array = node->as_array();
      if (array == nullptr || index >= array->size()) {
        error = fmt::format("{}[{}] is not in the scene ({} {})", walked, index, walked,
                            array ? fmt::format("has {} elements", array->size())
                                  : std::string("is not an array"));
        return nullptr;
      }
      node = array->get(index);
      walked = fmt::format("{}[{}]", walked, index);
      rest.remove_prefix(close + 1);
    }
    if (!rest.empty()) {
      if (rest.front() != '.') {
        error = fmt::format("cannot read the path {} after {}", path, walked);
        return nullptr;
      }
      rest.remove_prefix(1);
    }
  }
  return node;
}

Study read_study(const toml::table& root, const scene::TomlFile& file) {
  Study s;
  const scene::TableReader top = scene::TableReader::any_keys(root, "scene", file);
  const auto e = top.table("ensemble", "[ensemble]", {"runs", "seed", "vary", "outputs"});
  if (!e)
    top.fail_here("no [ensemble] table: add one with runs = N and [[ensemble.vary]] (docs/ensembles.md)");
  const double seed = e->number("seed", 0.0, "", scene::Domain::non_negative);
  if (seed != std::floor(seed) || seed >= 0x1p53)
    e->fail_at("seed", "seed must be a whole number below 2^53");
  s.seed = static_cast<std::uint64_t>(seed);

  toml::table mutable_root = root;  // paths are checked against a copy
  const auto vary = e->tables("vary");
  long grid_points = 1;
  bool any_grid = false;
  for (size_t i = 0; i < vary.size(); ++i) {
    const scene::TableReader v(*vary[i], e->context().child_numbered(" vary #", i + 1), file,
                               {"path", "distribution", "low", "high", "mean", "std", "mu", "sigma",
                                "magnitude", "values"});
    Variation x;
    x.path = std::string(
        v.required_string("path", "the value to vary, e.g. path = \"bodies.handle.angular_velocity[1]\""));
    const std::string_view kind =
        v.required_string("distribution", "its distribution, e.g. distribution = \"normal\"");
    const auto k = std::find(std::begin(kKinds), std::end(kKinds), kind);
    if (k == std::end(kKinds)) {
      v.fail_at("distribution", fmt::format("unknown distribution \"{}\"; choose \"{}\"", kind,
                                            fmt::join(std::begin(kKinds), std::end(kKinds), "\", \"")));
    }
    x.kind = static_cast<Variation::Kind>(k - std::begin(kKinds));
    using K = Variation::Kind;
    const auto need = [&](std::string_view key) {
      if (!v.has(key)) v.fail_here(fmt::format("a {} distribution needs '{}'", kind, key));
    };
    switch (x.kind) {
      case K::uniform:
        need("low");
        need("high");
        x.low = *v.number("low", "");
        x.high = *v.number("high", "");
        if (!(x.low < x.high))
          v.fail_at("high", fmt::format("high ({}) must be above low ({})", x.high, x.low));
        // The draw inverts the tail's probability in long double (ensemble_draws.cpp), which holds it to
        // about 150 standard deviations (Q(150) ≈ 1e-4888); beyond, nothing is left to draw from.
        if (const double sigmas = std::max(x.low - x.mean, x.mean - x.high) / x.std; sigmas > 150.0) {
          v.fail_at("low", fmt::format("[low, high] = [{}, {}] lies {:.4g} standard deviations from the mean "
                                       "{}: too far in the tail to draw from (at most 150); move the mean or "
                                       "the bounds",
                                       x.low, x.high, sigmas, x.mean));
        }
        break;
      case K::normal:
        need("mean");
        need("std");
        x.mean = *v.number("mean", "");
        x.std = *v.number("std", "", scene::Domain::non_negative);
        break;
      case K::lognormal:
        need("mu");
        need("sigma");
        x.mu = *v.number("mu", "");
        x.sigma = *v.number("sigma", "", scene::Domain::non_negative);
        break;
      case K::truncated_normal:
        need("mean");
        need("std");
        need("low");
        need("high");
        x.mean = *v.number("mean", "");
        x.std = *v.number("std", "", scene::Domain::positive);
        x.low = *v.number("low", "");
        x.high = *v.number("high", "");
        if (!(x.low < x.high))
          v.fail_at("high", fmt::format("high ({}) must be above low ({})", x.high, x.low));
        // The draw inverts the tail's probability in long double (ensemble_draws.cpp), which holds it to
        // about 150 standard deviations (Q(150) ≈ 1e-4888); beyond, nothing is left to draw from.
        if (const double sigmas = std::max(x.low - x.mean, x.mean - x.high) / x.std; sigmas > 150.0) {
          v.fail_at("low", fmt::format("[low, high] = [{}, {}] lies {:.4g} standard deviations from the mean "
                                       "{}: too far in the tail to draw from (at most 150); move the mean or "
                                       "the bounds",
                                       x.low, x.high, sigmas, x.mean));
        }
        break;
      case K::rotation:
        x.width = 4;
        break;
      case K::direction:
        x.width = 3;
        x.magnitude = v.number("magnitude", 1.0, "", scene::Domain::non_negative);
        break;
      case K::list:
      case K::grid: {
        need("values");
        const toml::array* a = v.node("values")->as_array();
        if (a == nullptr || a->empty()) v.fail_at("values", "values must be a non-empty array of numbers");
        for (const toml::node& n : *a) {
          const auto d = n.value<double>();
          if (!d || !std::isfinite(*d)) v.fail_at("values", "values must be finite numbers");
          x.values.push_back(*d);
        }
        if (x.kind == K::grid) {
          any_grid = true;
          grid_points *= static_cast<long>(x.values.size());
          if (grid_points > (1L << 40)) v.fail_at("values", "the grid has more than 2^40 points");
        }
        break;
      }
    }
    // The path must name a number (or, for a rotation or direction, an array of 4 or 3 numbers).
    std::string error;
    if (x.path == "ensemble" || x.path.rfind("ensemble.", 0) == 0 || x.path.rfind("ensemble[", 0) == 0) {
      v.fail_at("path", fmt::format("path {}: a study cannot vary its own [ensemble] table; vary a value of "
                                    "the scene (simulation, bodies, forces, …)",
                                    x.path));
    }
    toml::node* target = resolve(mutable_root, x.path, error);
    if (target == nullptr) v.fail_at("path", fmt::format("path {}: {}", x.path, error));
    if (x.width == 1) {
      if (!target->is_number()) v.fail_at("path", fmt::format("{} is not a number in the scene", x.path));
      x.names = {x.path};
    } else {
      const toml::array* a = target->as_array();
      const bool numbers = a != nullptr && std::all_of(a->begin(), a->end(),
                                                       [](const toml::node& n) { return n.is_number(); });
      if (!numbers || a->size() != static_cast<size_t>(x.width)) {
        v.fail_at("path", fmt::format("a {} distribution sets {} numbers: {} must be an array of {} ({})",
                                      kind, x.width, x.path, x.width,
                                      x.width == 4 ? "a quaternion [w, x, y, z]" : "a vector [x, y, z]"));
      }
      for (int c = 0; c < x.width; ++c) x.names.push_back(fmt::format("{}[{}]", x.path, c));
    }
    for (const Variation& before : s.variations) {
      if (before.path == x.path) v.fail_at("path", fmt::format("{} is varied twice", x.path));
    }
    s.variations.push_back(std::move(x));
  }
  if (e->has("runs")) {
    const double runs = e->required_number("runs", "", scene::Domain::positive);
    if (runs != std::floor(runs) || runs > 0x1p40)
      e->fail_at("runs", "runs must be a whole number from 1 to 2^40");
    s.runs = static_cast<long>(runs);
  } else if (any_grid) {
    s.runs = grid_points;  // the full factorial, once
  } else {
    e->fail_here("missing 'runs': give the number of runs, e.g. runs = 1000");
  }
  s.grid_points = grid_points;

  if (const auto o = e->table("outputs", e->context().child(" outputs"),
                              {"final", "extrema", "events", "drift", "trajectories"})) {
    if (const auto* a = o->node("final") ? o->node("final")->as_array() : nullptr) {
      for (const toml::node& n : *a) s.outputs.final_fields.push_back(n.value<std::string>().value_or(""));
      if (s.outputs.final_fields.empty())
        o->fail_at("final", "final is empty: name output fields, e.g. [\"position\"]");
      try {
        body_fields(s.outputs.final_fields);
      } catch (const InvalidArgument& error) {
        o->fail_at("final", error.what());
      }
    }
    if (const auto* a = o->node("extrema") ? o->node("extrema")->as_array() : nullptr) {
      for (const toml::node& n : *a) {
        const std::string c = n.value<std::string>().value_or("");
        if (!find_column(c))
          o->fail_at("extrema",
                     fmt::format("no output column \"{}\" (e.g. \"w2\", \"com_z\"; docs/scene-format.md)",
                                 c));
        s.outputs.extrema.push_back(c);
      }
    }
    s.outputs.events = o->boolean("events").value_or(true);
    s.outputs.drift = o->boolean("drift").value_or(true);
    if (const auto t =
            o->table("trajectories", o->context().child(" trajectories"), {"every", "worst", "by"})) {
      // Whole counts from 1 (a value past the runs is as good as the runs; a cast of 1e30 or 0.5 is not).
      const auto count = [&](const char* key, const char* meaning) -> long {
        if (!t->has(key)) return 0;
        const double n = t->required_number(key, "", scene::Domain::positive);
        if (n != std::floor(n) || n > 0x1p40) {
          t->fail_at(key,
                     fmt::format("{} = {} must be a whole number from 1 to 2^40 ({}); leave it out for none",
                                 key, n, meaning));
        }
        return static_cast<long>(std::min<double>(n, static_cast<double>(s.runs)));
      };
      s.outputs.every = count("every", "every = N writes the trajectories of runs 0, N, 2N, …");
      s.outputs.worst = count("worst", "worst = N writes those of the N worst runs by the column `by`");
      if (s.outputs.worst > 0) {
        s.outputs.worst_by = std::string(
            t->required_string("by", "the column that ranks the runs, e.g. by = \"energy_drift_max\""));
      }
    }
  }
  return s;
}

}  // namespace tumble::ensemble
