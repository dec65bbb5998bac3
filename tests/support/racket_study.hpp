#pragma once
// The study most ensemble tests run: test::racket_scene's box spun near its intermediate axis (no mesh:
// fast), with its flip event, and the [ensemble] table a test gives.
#include <string>

#include "scene_files.hpp"
#include "tumble/io/ensemble.hpp"

namespace tumble::test {

inline EnsembleStudy racket_study(const std::string& ensemble) {
  return EnsembleStudy::parse(racket_scene(8.0) + ensemble, "study.toml");
}

}  // namespace tumble::test
