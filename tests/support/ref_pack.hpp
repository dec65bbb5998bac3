#pragma once
// A reference pack: W doubles with every operation applied lane by lane by the scalar C++ operator or
// <cmath> function. Instantiating an equation on it checks that the template is written for packs
// (branch-free on values: select, not if) independently of any SIMD library, and it equals the double
// instantiation lane by lane by construction — the yardstick for the SIMD pack.
#include <array>
#include <cmath>
#include <cstddef>

#include "tumble/math/lanes.hpp"
#include "tumble/math/simd.hpp"
#include "tumble/math/types.hpp"

namespace tumble::test {

template <std::size_t W>
struct RefMask {
  std::array<bool, W> b{};
};

template <std::size_t W>
struct RefPack {
  std::array<double, W> v{};
  RefPack() = default;
  RefPack(double x) { v.fill(x); }  // NOLINT: implicit, like a SIMD broadcast

  template <class F>
  static RefPack map(F&& f, const RefPack& a) {
    RefPack r;
    for (std::size_t i = 0; i < W; ++i) r.v[i] = f(a.v[i]);
    return r;
  }
  template <class F>
  static RefPack zip(F&& f, const RefPack& a, const RefPack& b) {
    RefPack r;
    for (std::size_t i = 0; i < W; ++i) r.v[i] = f(a.v[i], b.v[i]);
    return r;
  }
  friend RefPack operator+(const RefPack& a, const RefPack& b) {
    return zip([](double x, double y) { return x + y; }, a, b);
  }
  friend RefPack operator-(const RefPack& a, const RefPack& b) {
    return zip([](double x, double y) { return x - y; }, a, b);
  }
  friend RefPack operator*(const RefPack& a, const RefPack& b) {
    return zip([](double x, double y) { return x * y; }, a, b);
  }
  friend RefPack operator/(const RefPack& a, const RefPack& b) {
    return zip([](double x, double y) { return x / y; }, a, b);
  }
  friend RefPack operator-(const RefPack& a) {
    return map([](double x) { return -x; }, a);
  }
  RefPack& operator+=(const RefPack& b) { return *this = *this + b; }
  RefPack& operator-=(const RefPack& b) { return *this = *this - b; }
  RefPack& operator*=(const RefPack& b) { return *this = *this * b; }
  RefPack& operator/=(const RefPack& b) { return *this = *this / b; }
  friend RefMask<W> operator<(const RefPack& a, const RefPack& b) {
    RefMask<W> m;
    for (std::size_t i = 0; i < W; ++i) m.b[i] = a.v[i] < b.v[i];
    return m;
  }
  friend RefPack select(const RefMask<W>& m, const RefPack& a, const RefPack& b) {
    RefPack r;
    for (std::size_t i = 0; i < W; ++i) r.v[i] = m.b[i] ? a.v[i] : b.v[i];
    return r;
  }
  friend RefPack sqrt(const RefPack& a) {
    return map([](double x) { return std::sqrt(x); }, a);
  }
  friend RefPack sin(const RefPack& a) {
    return map([](double x) { return std::sin(x); }, a);
  }
  friend RefPack cos(const RefPack& a) {
    return map([](double x) { return std::cos(x); }, a);
  }
  friend RefPack abs(const RefPack& a) {
    return map([](double x) { return std::abs(x); }, a);
  }
};

}  // namespace tumble::test

namespace tumble {
template <std::size_t W>
struct Lanes<test::RefPack<W>> {
  static constexpr std::size_t width = W;
  static test::RefPack<W> load(const double* p) {
    test::RefPack<W> r;
    for (std::size_t i = 0; i < W; ++i) r.v[i] = p[i];
    return r;
  }
  static void store(double* p, const test::RefPack<W>& x) {
    for (std::size_t i = 0; i < W; ++i) p[i] = x.v[i];
  }
};
}  // namespace tumble

namespace Eigen {
template <std::size_t W>
struct NumTraits<tumble::test::RefPack<W>> : tumble::PackNumTraits<tumble::test::RefPack<W>> {};
}  // namespace Eigen
