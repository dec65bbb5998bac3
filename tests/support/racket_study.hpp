#pragma once
// The study most ensemble tests run: test::racket_scene's box spun near its intermediate axis (no mesh:
// fast), with its flip event, and the [ensemble] table a test gives.
#include <string>

#include "scene_files.hpp"
#include "tumble/io/ensemble.hpp"

namespace tumble::test {

/// One [[ensemble.vary]] table, on lines of its own: the value at `path` drawn from `distribution`, whose
/// parameters are `keys` ("low = 0.0\nhigh = 1.0").
inline std::string vary(const std::string& path, const std::string& distribution,
                        const std::string& keys = "") {
  return "\n[[ensemble.vary]]\npath = \"" + path + "\"\ndistribution = \"" + distribution + "\"\n" + keys +
         (keys.empty() ? "" : "\n");
}

inline EnsembleStudy racket_study(const std::string& ensemble) {
  return EnsembleStudy::parse(racket_scene(8.0) + ensemble, "study.toml");
}

}  // namespace tumble::test
