#pragma once
// The inside of EnsembleStudy (ensemble.hpp): the [ensemble] table read, the paths into the scene's TOML,
// and the draws. Private to tumble_io.
#include <cstdint>
#include <string>
#include <vector>

#include "scene_sections.hpp"
#include "tumble/io/ensemble.hpp"

namespace tumble::ensemble {

struct Study {
  long runs = 0;
  std::uint64_t seed = 0;
  long grid_points = 1;  ///< product of the grid variations' sizes (1: no grid)
  std::vector<Variation> variations;
  EnsembleOutputs outputs;
};

/// The [ensemble] table of a scene file; SceneError at file:line:column for anything wrong in it.
Study read_study(const toml::table& root, const scene::TomlFile& file);

/// The node at `path` in a scene's TOML ("bodies.handle.angular_velocity[1]": a key, an element of
/// bodies/particles/forces/events by its name, an index); nullptr with `error` saying why.
toml::node* resolve(toml::table& root, const std::string& path, std::string& error);

/// The values of variation v for run i (v.width of them), from the counter (seed, i, v) alone.
std::vector<double> draw(const Study& study, size_t v, long i);

}  // namespace tumble::ensemble
