#pragma once
// Forward-mode derivatives: a dual number x + Σ_j x'_j ε_j (ε_j ε_k = 0), over double or a SIMD pack,
// as the number type of tumble's templated equations (math/lanes.hpp). An equation instantiated on
// Dual<T, N> computes its value exactly as on T and, beside it, the derivatives of that value along N
// seeded directions, by the chain rule applied to each operation: one source of each equation, no
// hand-derived tangent copy (issue 25). On a pack each lane carries its own body's value and tangents.
//
// Branch-free as the other number types: a comparison compares values and gives T's condition, and
// select() chooses values and tangents together, so a lane's derivative is that of the branch it took.
#include <array>
#include <cmath>
#include <type_traits>

#include "tumble/math/lanes.hpp"
#include "tumble/math/num_traits.hpp"
#include "tumble/math/types.hpp"

namespace tumble {

template <class T, int N>
struct Dual {
  T v;                 ///< the value
  std::array<T, N> d;  ///< its derivatives along the N seeded directions

  Dual() : v(0.0) { d.fill(T(0.0)); }
  /// A constant (all derivatives zero): lets literals and parameters meet variables.
  Dual(const T& value) : v(value) { d.fill(T(0.0)); }  // NOLINT: implicit, as double converts to T
  template <class U = T>
  requires(!std::is_same_v<U, double>) Dual(double value)
      : v(value) {  // NOLINT: implicit, for literals when T is a pack
    d.fill(T(0.0));
  }
  /// The independent variable j: value x, derivative 1 along direction j, 0 along the others.
  static Dual variable(const T& x, int j) {
    Dual r(x);
    r.d[static_cast<std::size_t>(j)] = T(1.0);
    return r;
  }

  /// A number whose tangents the caller writes next (every operation below): the zeros a constant
  /// starts with would be stores the compiler does not always remove (on packs it did not, measured).
  struct Unset {};
  explicit Dual(Unset) {}

  // Each rule is the chain rule of its operation: (f ∘ x)' = f'(x) x'.
  friend Dual operator+(const Dual& a, const Dual& b) {
    Dual r{Unset{}};
    r.v = a.v + b.v;
    for (int j = 0; j < N; ++j) r.d[j] = a.d[j] + b.d[j];
    return r;
  }
  friend Dual operator-(const Dual& a, const Dual& b) {
    Dual r{Unset{}};
    r.v = a.v - b.v;
    for (int j = 0; j < N; ++j) r.d[j] = a.d[j] - b.d[j];
    return r;
  }
  friend Dual operator-(const Dual& a) {
    Dual r{Unset{}};
    r.v = -a.v;
    for (int j = 0; j < N; ++j) r.d[j] = -a.d[j];
    return r;
  }
  friend Dual operator*(const Dual& a, const Dual& b) {  // (ab)' = a'b + ab'
    Dual r{Unset{}};
    r.v = a.v * b.v;
    for (int j = 0; j < N; ++j) r.d[j] = a.d[j] * b.v + a.v * b.d[j];
    return r;
  }
  friend Dual operator/(const Dual& a, const Dual& b) {  // (a/b)' = (a' − (a/b) b') / b
    Dual r{Unset{}};
    r.v = a.v / b.v;
    const T inv = T(1.0) / b.v;
    for (int j = 0; j < N; ++j) r.d[j] = (a.d[j] - r.v * b.d[j]) * inv;
    return r;
  }
  Dual& operator+=(const Dual& b) { return *this = *this + b; }
  Dual& operator-=(const Dual& b) { return *this = *this - b; }
  Dual& operator*=(const Dual& b) { return *this = *this * b; }
  Dual& operator/=(const Dual& b) { return *this = *this / b; }

  // Comparisons are of values: T's condition (bool, or a pack's mask).
  friend auto operator<(const Dual& a, const Dual& b) { return a.v < b.v; }
  friend auto operator>(const Dual& a, const Dual& b) { return a.v > b.v; }
  friend auto operator<=(const Dual& a, const Dual& b) { return a.v <= b.v; }
  friend auto operator>=(const Dual& a, const Dual& b) { return a.v >= b.v; }
  friend auto operator==(const Dual& a, const Dual& b) { return a.v == b.v; }
  friend auto operator!=(const Dual& a, const Dual& b) { return a.v != b.v; }
};

namespace dual_detail {
/// f(x) with f'(x) given: the value f and the tangents f' x'.
template <class T, int N>
Dual<T, N> chain(const Dual<T, N>& x, const T& f, const T& df) {
  Dual<T, N> r{typename Dual<T, N>::Unset{}};
  r.v = f;
  for (int j = 0; j < N; ++j) r.d[j] = df * x.d[j];
  return r;
}
}  // namespace dual_detail

// The functions the equations use, each by its derivative; T's own (std:: for double, xsimd's for a
// pack) found by argument-dependent lookup or the using-declarations.
template <class T, int N>
Dual<T, N> sqrt(const Dual<T, N>& x) {
  using std::sqrt;
  const T s = sqrt(x.v);
  return dual_detail::chain(x, s, T(0.5) / s);
}
template <class T, int N>
Dual<T, N> sin(const Dual<T, N>& x) {
  using std::cos;
  using std::sin;
  return dual_detail::chain(x, T(sin(x.v)), T(cos(x.v)));
}
template <class T, int N>
Dual<T, N> cos(const Dual<T, N>& x) {
  using std::cos;
  using std::sin;
  return dual_detail::chain(x, T(cos(x.v)), T(-sin(x.v)));
}
template <class T, int N>
std::pair<Dual<T, N>, Dual<T, N>> sincos(const Dual<T, N>& x) {
  const auto [s, c] = sincos(x.v);
  return {dual_detail::chain(x, s, c), dual_detail::chain(x, c, T(-s))};
}
template <class T, int N>
Dual<T, N> exp(const Dual<T, N>& x) {
  using std::exp;
  const T e = exp(x.v);
  return dual_detail::chain(x, e, e);
}
template <class T, int N>
Dual<T, N> log(const Dual<T, N>& x) {
  using std::log;
  return dual_detail::chain(x, T(log(x.v)), T(T(1.0) / x.v));
}
template <class T, int N>
Dual<T, N> atan(const Dual<T, N>& x) {
  using std::atan;
  return dual_detail::chain(x, T(atan(x.v)), T(T(1.0) / (T(1.0) + x.v * x.v)));
}
/// atan2(y, x)' = (x y' − y x') / (x² + y²).
template <class T, int N>
Dual<T, N> atan2(const Dual<T, N>& y, const Dual<T, N>& x) {
  using std::atan2;
  Dual<T, N> r(T(atan2(y.v, x.v)));
  const T inv = T(1.0) / (x.v * x.v + y.v * y.v);
  for (int j = 0; j < N; ++j) r.d[j] = (x.v * y.d[j] - y.v * x.d[j]) * inv;
  return r;
}
/// |x|' = sign(x) x' (0 taken as +).
template <class T, int N>
Dual<T, N> abs(const Dual<T, N>& x) {
  return select(x.v < T(0.0), -x, x);
}
/// hypot(x, y) = √(x² + y²), its derivative (x x' + y y') / hypot.
template <class T, int N>
Dual<T, N> hypot(const Dual<T, N>& x, const Dual<T, N>& y) {
  using std::hypot;
  Dual<T, N> r(T(hypot(x.v, y.v)));
  const T inv = T(1.0) / r.v;
  for (int j = 0; j < N; ++j) r.d[j] = (x.v * x.d[j] + y.v * y.d[j]) * inv;
  return r;
}
/// copysign(x, s): |x| with the sign of s; its derivative ±x', the sign that multiplied x.
template <class T, int N>
Dual<T, N> copysign(const Dual<T, N>& x, const Dual<T, N>& s) {
  using std::copysign, std::signbit;
  Dual<T, N> r(T(copysign(x.v, s.v)));
  const T flip = select(signbit(x.v) != signbit(s.v), T(-1.0), T(1.0));
  for (int j = 0; j < N; ++j) r.d[j] = flip * x.d[j];
  return r;
}
/// Functions that are constant between their jumps: derivative 0 (a lane at a jump takes the side its
/// value rounded to).
template <class T, int N>
Dual<T, N> nearbyint(const Dual<T, N>& x) {
  using std::nearbyint;
  return Dual<T, N>(T(nearbyint(x.v)));
}
template <class T, int N>
Dual<T, N> floor(const Dual<T, N>& x) {
  using std::floor;
  return Dual<T, N>(T(floor(x.v)));
}
/// a·b + c with the value rounded once, as fma(a.v, b.v, c.v).
template <class T, int N>
Dual<T, N> fma(const Dual<T, N>& a, const Dual<T, N>& b, const Dual<T, N>& c) {
  using std::fma;
  Dual<T, N> r(T(fma(a.v, b.v, c.v)));
  for (int j = 0; j < N; ++j) r.d[j] = a.d[j] * b.v + a.v * b.d[j] + c.d[j];
  return r;
}
/// The value of a number without its tangents (a double or a pack is its own value).
template <class T, int N>
const T& value_of(const Dual<T, N>& x) {
  return x.v;
}
inline double value_of(double x) { return x; }

/// A lane-wise choice of value and tangents together.
template <class T, int N, class Condition>
Dual<T, N> select(const Condition& condition, const Dual<T, N>& a, const Dual<T, N>& b) {
  Dual<T, N> r{typename Dual<T, N>::Unset{}};
  r.v = select(condition, a.v, b.v);
  for (int j = 0; j < N; ++j) r.d[j] = select(condition, a.d[j], b.d[j]);
  return r;
}

template <class T, int N>
struct Lanes<Dual<T, N>> {
  static constexpr std::size_t width = Lanes<T>::width;
};

}  // namespace tumble

namespace Eigen {

/// An addition costs a dual number N + 1 of T's, a multiplication 2N + 1.
template <class T, int N>
struct NumTraits<tumble::Dual<T, N>> : tumble::PackNumTraits<tumble::Dual<T, N>, N + 1, 2 * N + 1> {};

}  // namespace Eigen
