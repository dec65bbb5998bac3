#pragma once
// Shared by the libFuzzer targets (fuzz/*.cpp, docs/ARCHITECTURE.md "Fuzzing"). An input may end in a
// tumble::Error (the library refused it, with a message); anything else is a finding: a crash, a
// sanitizer report, an exception of another type (std::bad_alloc included: libFuzzer aborts on an
// uncaught exception), or a result that breaks the contract, which FUZZ_CHECK turns into an abort.
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "tumble/error.hpp"
#include "tumble/mass/triangle_mesh.hpp"

#define FUZZ_CHECK(condition)                                                                      \
  do {                                                                                             \
    if (!(condition)) {                                                                            \
      std::fprintf(stderr, "fuzz: contract broken: %s (%s:%d)\n", #condition, __FILE__, __LINE__); \
      std::abort();                                                                                \
    }                                                                                              \
  } while (0)

namespace tumble::fuzz {

/// Runs `f`; a tumble::Error is an expected outcome, every other exception escapes (a finding).
template <class F>
bool refused_or_ok(F&& f) {
  try {
    f();
    return true;
  } catch (const tumble::Error&) {
    return false;
  }
}

/// What every mesh a reader returns must be: triangles, every index a vertex, every coordinate finite.
inline void check_mesh_contract(const TriangleMesh& mesh) {
  FUZZ_CHECK(!mesh.triangles.empty());
  for (const auto& v : mesh.vertices)
    FUZZ_CHECK(std::isfinite(v.x()) && std::isfinite(v.y()) && std::isfinite(v.z()));
  for (const auto& t : mesh.triangles) {
    for (auto i : t) FUZZ_CHECK(i < mesh.vertices.size());
  }
}

}  // namespace tumble::fuzz
