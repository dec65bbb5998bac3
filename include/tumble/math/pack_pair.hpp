#pragma once
// Two SIMD packs as one number type (2W lanes): every operation is applied to both halves in turn, so
// a long chain of dependent operations — the exact free flow's Landen levels and Carlson duplications,
// each waiting on the last square root or division — becomes two independent chains that the core
// overlaps. A lane computes exactly what it computes in a single pack (the same xsimd operation on the
// same value): splitting's drift evaluates two packs of flows at once with it (measured: 39 instead of
// 58 ns a body, build/release/bin/euler_poinsot_bench).
#include "tumble/math/simd.hpp"

namespace tumble {

/// The mask of a PackPair comparison.
struct MaskPair {
  using M = decltype(xsimd::batch<double>() < xsimd::batch<double>());
  M a, b;
  [[gnu::always_inline]] friend MaskPair operator&&(const MaskPair& x, const MaskPair& y) {
    return {x.a && y.a, x.b && y.b};
  }
  [[gnu::always_inline]] friend MaskPair operator||(const MaskPair& x, const MaskPair& y) {
    return {x.a || y.a, x.b || y.b};
  }
  [[gnu::always_inline]] friend MaskPair operator!(const MaskPair& x) { return {!x.a, !x.b}; }
  [[gnu::always_inline]] friend bool all(const MaskPair& x) { return xsimd::all(x.a) && xsimd::all(x.b); }
};

struct PackPair {
  using P = xsimd::batch<double>;
  P a, b;  // lanes 0 … W − 1 and W … 2W − 1
  PackPair() = default;
  TUMBLE_INLINE PackPair(double x) : a(x), b(x) {}  // NOLINT: implicit, like a SIMD broadcast
  TUMBLE_INLINE PackPair(const P& x, const P& y) : a(x), b(y) {}

#define TUMBLE_PAIR_BINARY(op, Result)                                                     \
  [[gnu::always_inline]] friend Result operator op(const PackPair& x, const PackPair& y) { \
    return {x.a op y.a, x.b op y.b};                                                       \
  }
  TUMBLE_PAIR_BINARY(+, PackPair)
  TUMBLE_PAIR_BINARY(-, PackPair)
  TUMBLE_PAIR_BINARY(*, PackPair)
  TUMBLE_PAIR_BINARY(/, PackPair)
  TUMBLE_PAIR_BINARY(<, MaskPair)
  TUMBLE_PAIR_BINARY(<=, MaskPair)
  TUMBLE_PAIR_BINARY(>, MaskPair)
  TUMBLE_PAIR_BINARY(>=, MaskPair)
  TUMBLE_PAIR_BINARY(==, MaskPair)
  TUMBLE_PAIR_BINARY(!=, MaskPair)
#undef TUMBLE_PAIR_BINARY
  [[gnu::always_inline]] friend PackPair operator-(const PackPair& x) { return {-x.a, -x.b}; }
  TUMBLE_INLINE PackPair& operator+=(const PackPair& y) { return *this = *this + y; }
  TUMBLE_INLINE PackPair& operator-=(const PackPair& y) { return *this = *this - y; }
  TUMBLE_INLINE PackPair& operator*=(const PackPair& y) { return *this = *this * y; }
  TUMBLE_INLINE PackPair& operator/=(const PackPair& y) { return *this = *this / y; }
  [[gnu::always_inline]] friend PackPair select(const MaskPair& m, const PackPair& x, const PackPair& y) {
    return {xsimd::select(m.a, x.a, y.a), xsimd::select(m.b, x.b, y.b)};
  }

#define TUMBLE_PAIR_UNARY(f) \
  [[gnu::always_inline]] friend PackPair f(const PackPair& x) { return {xsimd::f(x.a), xsimd::f(x.b)}; }
  TUMBLE_PAIR_UNARY(sqrt)
  TUMBLE_PAIR_UNARY(sin)
  TUMBLE_PAIR_UNARY(cos)
  TUMBLE_PAIR_UNARY(asin)
  TUMBLE_PAIR_UNARY(atan)
  TUMBLE_PAIR_UNARY(nearbyint)
  TUMBLE_PAIR_UNARY(floor)
  TUMBLE_PAIR_UNARY(abs)
#undef TUMBLE_PAIR_UNARY
  [[gnu::always_inline]] friend std::pair<PackPair, PackPair> sincos(const PackPair& x) {
    const auto [sin_a, cos_a] = xsimd::sincos(x.a);
    const auto [sin_b, cos_b] = xsimd::sincos(x.b);
    return {{sin_a, sin_b}, {cos_a, cos_b}};
  }
#define TUMBLE_PAIR_OF_TWO(f)                                                      \
  [[gnu::always_inline]] friend PackPair f(const PackPair& x, const PackPair& y) { \
    return {xsimd::f(x.a, y.a), xsimd::f(x.b, y.b)};                               \
  }
  TUMBLE_PAIR_OF_TWO(hypot)
  TUMBLE_PAIR_OF_TWO(copysign)
  TUMBLE_PAIR_OF_TWO(atan2)
#undef TUMBLE_PAIR_OF_TWO
  [[gnu::always_inline]] friend PackPair fma(const PackPair& x, const PackPair& y, const PackPair& z) {
    return {xsimd::fma(x.a, y.a, z.a), xsimd::fma(x.b, y.b, z.b)};
  }
};

template <>
struct Lanes<PackPair> {
  static constexpr std::size_t width = 2 * PackPair::P::size;
  TUMBLE_INLINE static PackPair load(const double* p) {
    return {PackPair::P::load_aligned(p), PackPair::P::load_aligned(p + PackPair::P::size)};
  }
  TUMBLE_INLINE static void store(double* p, const PackPair& v) {
    v.a.store_aligned(p);
    v.b.store_aligned(p + PackPair::P::size);
  }
};

}  // namespace tumble

namespace Eigen {
template <>
struct NumTraits<tumble::PackPair> : tumble::PackNumTraits<tumble::PackPair> {};
}  // namespace Eigen
