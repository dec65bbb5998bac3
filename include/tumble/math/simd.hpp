#pragma once
// xsimd packs of doubles as the number type of tumble's templated equations (math/lanes.hpp): the
// Lanes<> trait for them, and the Eigen::NumTraits (num_traits.hpp) that lets Eigen's fixed-size vectors, matrices and
// quaternions hold one body per lane. Comparisons give xsimd::batch_bool, which `select` (found by
// argument-dependent lookup in xsimd) turns into a blend.
#include <xsimd/xsimd.hpp>

#include "tumble/math/lanes.hpp"
#include "tumble/math/num_traits.hpp"
#include "tumble/math/types.hpp"

namespace tumble {

template <class Arch>
struct Lanes<xsimd::batch<double, Arch>> {
  using Pack = xsimd::batch<double, Arch>;
  static constexpr std::size_t width = Pack::size;
  TUMBLE_INLINE static Pack load(const double* p) { return Pack::load_aligned(p); }
  TUMBLE_INLINE static void store(double* p, const Pack& v) { v.store_aligned(p); }
};

}  // namespace tumble

namespace Eigen {

template <class Arch>
struct NumTraits<xsimd::batch<double, Arch>> : tumble::PackNumTraits<xsimd::batch<double, Arch>> {};

}  // namespace Eigen
