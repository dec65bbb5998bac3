#pragma once
// Eigen::NumTraits for tumble's number types made of doubles (a SIMD pack, a pair of packs, the tests'
// reference pack, the benchmarks' counting double, a dual number): Eigen's specialisation for each
// derives from this. `Cost` is what an addition or a multiplication costs in doubles' operations
// (Eigen's unrolling heuristics read it): 1 for a pack, more for a dual number's tangents.
#include "tumble/math/types.hpp"

namespace tumble {

template <class T, int AddCostOfT = 1, int MulCostOfT = 1>
struct PackNumTraits : Eigen::GenericNumTraits<double> {
  using Real = T;
  using NonInteger = T;
  using Literal = T;
  using Nested = T;
  enum {
    IsComplex = 0,
    IsInteger = 0,
    IsSigned = 1,
    RequireInitialization = 1,
    ReadCost = 1,
    AddCost = AddCostOfT,
    MulCost = MulCostOfT
  };
  static T epsilon() { return T(Eigen::NumTraits<double>::epsilon()); }
  static T dummy_precision() { return T(Eigen::NumTraits<double>::dummy_precision()); }
  static int digits10() { return Eigen::NumTraits<double>::digits10(); }
};

}  // namespace tumble
