#pragma once
// A human-readable summary of a scene: settings, bodies (mass, principal moments), forces, and the
// initial energy and momenta. Printed by `tumble check`, and by `tumble run` before it starts.
#include <cstdio>

#include "tumble/io/scene.hpp"

namespace tumble::cli {

void print_scene_summary(std::FILE* out, const Scene& scene);

/// Prints the scene's warnings to stderr, one "tumble: warning: ..." line each; with `strict`, then
/// throws InvalidArgument if there were any.
void print_scene_warnings(const Scene& scene, bool strict = false);

}  // namespace tumble::cli
