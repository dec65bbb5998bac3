#pragma once
// Scalars and packs of lanes. The equations of tumble are templates on a number type T that is either
// `double` (one body) or a SIMD pack (one body per lane, tumble/math/simd.hpp). They are written
// branch-free on values: a choice between two values is `select(condition, a, b)`, never `if`, so
// every lane computes exactly what the scalar path computes for that body.
//
// Lanes<T> says how T meets memory: the number of bodies it holds and how it loads and stores a run
// of that many doubles from a column (columns are padded and aligned, dynamics/columns.hpp).
#include <cmath>
#include <cstddef>
#include <utility>

/// On the small equation templates: inlined into the loop over packs, they keep a pack's variables in
/// registers (measured: GCC 12 otherwise calls them out of line and the batched RK4 runs 2× slower).
#define TUMBLE_INLINE [[gnu::always_inline]] inline

namespace tumble {

template <class T>
struct Lanes;

template <>
struct Lanes<double> {
  static constexpr std::size_t width = 1;
  static double load(const double* p) { return *p; }
  static void store(double* p, double v) { *p = v; }
};

/// (sin x, cos x). On a pack, xsimd::sincos (found by argument-dependent lookup) reduces the argument
/// once for both and gives the bits of xsimd::sin and xsimd::cos: half the cost of calling both.
inline std::pair<double, double> sincos(double x) { return {std::sin(x), std::cos(x)}; }

/// The scalar form of a lane-wise choice: a where `condition` holds, else b.
inline double select(bool condition, double a, double b) { return condition ? a : b; }
/// Whether a condition holds in every lane (xsimd::all for a pack's mask): for skipping work whose
/// result every lane would discard, never for choosing a lane's value.
inline bool all(bool condition) { return condition; }

}  // namespace tumble
