#pragma once
// Structure-of-arrays storage for many bodies: each quantity is a column of n doubles, so that a SIMD
// pack loads the same quantity of W consecutive bodies in one instruction (math/lanes.hpp).
//
// Columns are padded to a multiple of kColumnPadding and aligned to 64 bytes: a pack of any width up
// to 8 doubles loads aligned at every multiple of its width, and the last pack of a column never reads
// past its end. The padding lanes hold harmless values (set by the owner: identity quaternions, unit
// masses) and are never reported.
#include <algorithm>
#include <cstddef>
#include <cstdlib>
#include <memory>
#include <new>

#include "tumble/dynamics/newton_euler.hpp"

namespace tumble {

/// Bodies per padding unit: the widest pack (AVX-512, 8 doubles).
inline constexpr std::size_t kColumnPadding = 8;

/// n rounded up to whole padding units.
inline constexpr std::size_t padded_size(std::size_t n) {
  return (n + kColumnPadding - 1) / kColumnPadding * kColumnPadding;
}

/// `count` columns of n doubles each (padded), zero-initialised, in one 64-byte-aligned allocation.
class Columns {
 public:
  Columns() = default;
  Columns(std::size_t n, std::size_t count) { resize(n, count); }
  Columns(const Columns& other) { *this = other; }
  Columns(Columns&&) noexcept = default;
  Columns& operator=(Columns&&) noexcept = default;
  Columns& operator=(const Columns& other) {
    if (this == &other) return *this;
    if (other.n_ != n_ || other.count_ != count_) resize(other.n_, other.count_);
    std::copy(other.data_.get(), other.data_.get() + total(), data_.get());
    return *this;
  }

  /// Sizes for n values per column without touching the values when the shape is already right (the
  /// per-step path); a new shape is allocated and zeroed.
  void ensure(std::size_t n, std::size_t count) {
    if (n != n_ || count != count_ || (!data_ && n * count > 0)) resize(n, count);
  }

  /// Reallocates (only when the shape changes) and zeroes.
  void resize(std::size_t n, std::size_t count) {
    if (n != n_ || count != count_ || !data_) {
      n_ = n;
      count_ = count;
      stride_ = padded_size(n);
      data_.reset(total()
                      ? static_cast<double*>(::operator new[](total() * sizeof(double), std::align_val_t{64}))
                      : nullptr);
    }
    std::fill(data_.get(), data_.get() + total(), 0.0);
  }

  std::size_t size() const { return n_; }
  /// n rounded up to whole padding units: the length of every column.
  std::size_t stride() const { return stride_; }
  std::size_t count() const { return count_; }
  double* operator[](std::size_t column) { return data_.get() + column * stride_; }
  const double* operator[](std::size_t column) const { return data_.get() + column * stride_; }

 private:
  struct AlignedDelete {
    void operator()(double* p) const { ::operator delete[](p, std::align_val_t{64}); }
  };
  std::size_t total() const { return stride_ * count_; }
  std::size_t n_ = 0, stride_ = 0, count_ = 0;
  std::unique_ptr<double[], AlignedDelete> data_;
};

/// 13 columns of body variables (o, q as (w, x, y, z), v, ω) or of their rates, addressed by body
/// index i: row i is stored at position i − offset (a block's scratch holds rows begin … begin + B − 1
/// with offset = begin; whole-system columns have offset 0). For a pack of width W, i must be a multiple
/// of W and the pack holds bodies i … i + W − 1.
class BodyColumnsRef {
 public:
  enum : std::size_t { o = 0, q = 3, v = 7, omega = 10, kCount = 13 };

  BodyColumnsRef() = default;
  BodyColumnsRef(double* const* columns, std::size_t offset) : offset_(offset) {
    std::copy(columns, columns + kCount, c_);
  }

  template <class T = double>
  TUMBLE_INLINE Coordinates<T> load(std::size_t i) const {
    return {vec3<T>(o, i), quat<T>(i), vec3<T>(v, i), vec3<T>(omega, i)};
  }
  template <class T = double>
  TUMBLE_INLINE CoordinateRates<T> load_rates(std::size_t i) const {
    return {vec3<T>(o, i), quat<T>(i), vec3<T>(v, i), vec3<T>(omega, i)};
  }
  template <class T>
  TUMBLE_INLINE void store(std::size_t i, const Coordinates<T>& x) const {
    store_vec3<T>(o, i, x.o);
    store_quat<T>(i, x.q);
    store_vec3<T>(v, i, x.v);
    store_vec3<T>(omega, i, x.omega);
  }
  template <class T>
  TUMBLE_INLINE void store(std::size_t i, const CoordinateRates<T>& r) const {
    store_vec3<T>(o, i, r.o_dot);
    store_quat<T>(i, r.q_dot);
    store_vec3<T>(v, i, r.v_dot);
    store_vec3<T>(omega, i, r.omega_dot);
  }
  /// Columns first … first+2 of body (or pack) i as a vector.
  template <class T = double>
  TUMBLE_INLINE Vec3T<T> vec3(std::size_t first, std::size_t i) const {
    return {Lanes<T>::load(at(first, i)), Lanes<T>::load(at(first + 1, i)), Lanes<T>::load(at(first + 2, i))};
  }
  template <class T = double>
  TUMBLE_INLINE QuatT<T> quat(std::size_t i) const {
    return QuatT<T>(Lanes<T>::load(at(q, i)), Lanes<T>::load(at(q + 1, i)), Lanes<T>::load(at(q + 2, i)),
                    Lanes<T>::load(at(q + 3, i)));
  }
  template <class T>
  TUMBLE_INLINE void store_vec3(std::size_t first, std::size_t i, const Vec3T<T>& u) const {
    for (std::size_t k = 0; k < 3; ++k) Lanes<T>::store(at(first + k, i), u(static_cast<Eigen::Index>(k)));
  }
  template <class T>
  TUMBLE_INLINE void store_quat(std::size_t i, const QuatT<T>& u) const {
    Lanes<T>::store(at(q, i), u.w());
    Lanes<T>::store(at(q + 1, i), u.x());
    Lanes<T>::store(at(q + 2, i), u.y());
    Lanes<T>::store(at(q + 3, i), u.z());
  }
  /// Where column k of body i is stored.
  double* at(std::size_t k, std::size_t i) const { return c_[k] + (i - offset_); }

 private:
  double* c_[kCount] = {};
  std::size_t offset_ = 0;
};

/// The integrated variables of n bodies in one formulation (newton_euler.hpp's Coordinates), or their
/// rates, as 13 whole-system columns (BodyColumnsRef's layout, offset 0).
class BodyColumns : public Columns {
 public:
  enum : std::size_t { o = 0, q = 3, v = 7, omega = 10, kCount = 13 };

  BodyColumns() = default;
  explicit BodyColumns(std::size_t n) { resize(n); }
  /// n bodies; every quaternion (padding lanes too) starts as the identity.
  void resize(std::size_t n) {
    Columns::resize(n, kCount);
    std::fill((*this)[q], (*this)[q] + stride(), 1.0);
  }
  /// resize(n) unless already sized for n bodies (then the values are kept).
  void ensure(std::size_t n) {
    if (n != size() || count() != kCount) resize(n);
  }

  /// The columns as a view (for the kernels, which address whole-system and block storage alike).
  BodyColumnsRef ref() {
    double* c[kCount];
    for (std::size_t k = 0; k < kCount; ++k) c[k] = (*this)[k];
    return {c, 0};
  }
  /// Read-only use of the same view: the view's store() must not be called on it.
  BodyColumnsRef ref() const { return const_cast<BodyColumns*>(this)->ref(); }

  template <class T = double>
  Coordinates<T> load(std::size_t i) const {
    return ref().load<T>(i);
  }
  template <class T = double>
  CoordinateRates<T> load_rates(std::size_t i) const {
    return ref().load_rates<T>(i);
  }
  template <class T>
  void store(std::size_t i, const Coordinates<T>& x) {
    ref().store<T>(i, x);
  }
  template <class T>
  void store(std::size_t i, const CoordinateRates<T>& r) {
    ref().store<T>(i, r);
  }
  template <class T = double>
  Vec3T<T> vec3(std::size_t first, std::size_t i) const {
    return ref().vec3<T>(first, i);
  }
  template <class T = double>
  QuatT<T> quat(std::size_t i) const {
    return ref().quat<T>(i);
  }
  template <class T>
  void store_quat(std::size_t i, const QuatT<T>& u) {
    ref().store_quat<T>(i, u);
  }
};

}  // namespace tumble
