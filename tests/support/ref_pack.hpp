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

/// A mask of W lanes, with the operators of xsimd's batch_bool (8.1): ==, != and the logical & | ^ ~
/// and ! && || lane by lane. A template meant for double too writes && || ! (on bool, ~ is an int).
template <std::size_t W>
struct RefMask {
  std::array<bool, W> b{};

  template <class F>
  static RefMask zip(F&& f, const RefMask& m, const RefMask& n) {
    RefMask r;
    for (std::size_t i = 0; i < W; ++i) r.b[i] = f(m.b[i], n.b[i]);
    return r;
  }
  friend RefMask operator==(const RefMask& m, const RefMask& n) {
    return zip([](bool x, bool y) { return x == y; }, m, n);
  }
  friend RefMask operator!=(const RefMask& m, const RefMask& n) {
    return zip([](bool x, bool y) { return x != y; }, m, n);
  }
  friend RefMask operator&(const RefMask& m, const RefMask& n) {
    return zip([](bool x, bool y) { return x && y; }, m, n);
  }
  friend RefMask operator|(const RefMask& m, const RefMask& n) {
    return zip([](bool x, bool y) { return x || y; }, m, n);
  }
  friend RefMask operator^(const RefMask& m, const RefMask& n) {
    return zip([](bool x, bool y) { return x != y; }, m, n);
  }
  friend RefMask operator&&(const RefMask& m, const RefMask& n) { return m & n; }
  friend RefMask operator||(const RefMask& m, const RefMask& n) { return m | n; }
  friend RefMask operator!(const RefMask& m) {
    RefMask r;
    for (std::size_t i = 0; i < W; ++i) r.b[i] = !m.b[i];
    return r;
  }
  friend RefMask operator~(const RefMask& m) { return !m; }
  /// Whether every lane is set (xsimd::all for batch_bool).
  friend bool all(const RefMask& m) {
    for (bool x : m.b) {
      if (!x) return false;
    }
    return true;
  }
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
  template <class F>
  static RefPack zip(F&& f, const RefPack& a, const RefPack& b, const RefPack& c) {
    RefPack r;
    for (std::size_t i = 0; i < W; ++i) r.v[i] = f(a.v[i], b.v[i], c.v[i]);
    return r;
  }
  template <class F>
  static RefMask<W> compare(F&& f, const RefPack& a, const RefPack& b) {
    RefMask<W> m;
    for (std::size_t i = 0; i < W; ++i) m.b[i] = f(a.v[i], b.v[i]);
    return m;
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
    return compare([](double x, double y) { return x < y; }, a, b);
  }
  friend RefMask<W> operator<=(const RefPack& a, const RefPack& b) {
    return compare([](double x, double y) { return x <= y; }, a, b);
  }
  friend RefMask<W> operator>(const RefPack& a, const RefPack& b) {
    return compare([](double x, double y) { return x > y; }, a, b);
  }
  friend RefMask<W> operator>=(const RefPack& a, const RefPack& b) {
    return compare([](double x, double y) { return x >= y; }, a, b);
  }
  friend RefMask<W> operator==(const RefPack& a, const RefPack& b) {
    return compare([](double x, double y) { return x == y; }, a, b);
  }
  friend RefMask<W> operator!=(const RefPack& a, const RefPack& b) {
    return compare([](double x, double y) { return x != y; }, a, b);
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
  friend std::pair<RefPack, RefPack> sincos(const RefPack& a) { return {sin(a), cos(a)}; }
  friend RefPack asin(const RefPack& a) {
    return map([](double x) { return std::asin(x); }, a);
  }
  friend RefPack atan(const RefPack& a) {
    return map([](double x) { return std::atan(x); }, a);
  }
  friend RefPack atan2(const RefPack& y, const RefPack& x) {
    return zip([](double a, double b) { return std::atan2(a, b); }, y, x);
  }
  friend RefPack hypot(const RefPack& a, const RefPack& b) {
    return zip([](double x, double y) { return std::hypot(x, y); }, a, b);
  }
  friend RefPack copysign(const RefPack& magnitude, const RefPack& sign) {
    return zip([](double x, double y) { return std::copysign(x, y); }, magnitude, sign);
  }
  friend RefPack fma(const RefPack& a, const RefPack& b, const RefPack& c) {
    return zip([](double x, double y, double z) { return std::fma(x, y, z); }, a, b, c);
  }
  friend RefPack nearbyint(const RefPack& a) {
    return map([](double x) { return std::nearbyint(x); }, a);
  }
  friend RefPack floor(const RefPack& a) {
    return map([](double x) { return std::floor(x); }, a);
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
