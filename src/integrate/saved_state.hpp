#pragma once
// An integrator's state as a flat vector of doubles (Integrator::save_state): values, counts and flags
// (exact in a double up to 2^53) in a fixed order that load_state() reads back in the same order.
#include <fmt/format.h>

#include <cstddef>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "tumble/error.hpp"
#include "tumble/integrate/system_coordinates.hpp"

namespace tumble::saved {

class Writer {
 public:
  explicit Writer(std::vector<double>& out) : out_(out) {}
  void put(double v) { out_.push_back(v); }
  void put(const Vec3& v) { out_.insert(out_.end(), {v.x(), v.y(), v.z()}); }
  void put(const Quat& q) { out_.insert(out_.end(), {q.w(), q.x(), q.y(), q.z()}); }
  /// The first `n` values of each of `count` columns, after n.
  void put(const Columns& c) {
    put(static_cast<double>(c.size()));
    for (std::size_t k = 0; k < c.count(); ++k) out_.insert(out_.end(), c[k], c[k] + c.size());
  }
  void put(const std::vector<ParticleState>& particles) {
    put(static_cast<double>(particles.size()));
    for (const ParticleState& p : particles) put(p.x), put(p.v);
  }
  void put(const std::vector<Vec3>& vs) {
    put(static_cast<double>(vs.size()));
    for (const Vec3& v : vs) put(v);
  }
  void put(const SystemCoordinates& x) { put(x.t), put(x.bodies), put(x.particles); }

 private:
  std::vector<double>& out_;
};

class Reader {
 public:
  Reader(const std::vector<double>& in, std::string integrator)
      : in_(in), integrator_(std::move(integrator)) {}
  double get() {
    if (pos_ >= in_.size()) fail();
    return in_[pos_++];
  }
  /// A count or flag: a whole number in [0, limit].
  std::size_t count(std::size_t limit) {
    const double v = get();
    if (!(v >= 0 && v <= static_cast<double>(limit)) || v != static_cast<double>(static_cast<std::size_t>(v)))
      fail();
    return static_cast<std::size_t>(v);
  }
  bool flag() { return count(1) == 1; }
  Vec3 vec3() {
    const double x = get(), y = get(), z = get();
    return {x, y, z};
  }
  Quat quat() {
    const double w = get(), x = get(), y = get(), z = get();
    return {w, x, y, z};
  }
  /// Columns of `count` values each, written by Writer::put(const Columns&), into `c` (BodyColumns:
  /// count 13); n must be `n` unless n is 0.
  template <class C>
  void columns(C& c, std::size_t count, std::size_t n) {
    const std::size_t size = this->count(n);
    if (size != n && size != 0) fail();
    if constexpr (std::is_same_v<C, BodyColumns>) {
      c.resize(size);
    } else {
      c.resize(size, count);
    }
    for (std::size_t k = 0; k < count; ++k) {
      for (std::size_t i = 0; i < size; ++i) c[k][i] = get();
    }
  }
  std::vector<ParticleState> particles(std::size_t n) {
    std::vector<ParticleState> out(this->count(n));
    for (ParticleState& p : out) p.x = vec3(), p.v = vec3();
    return out;
  }
  std::vector<Vec3> vec3s(std::size_t n) {
    std::vector<Vec3> out(this->count(n));
    for (Vec3& v : out) v = vec3();
    return out;
  }
  SystemCoordinates coordinates(std::size_t bodies, std::size_t particles) {
    SystemCoordinates x;
    x.t = get();
    columns(x.bodies, BodyColumns::kCount, bodies);
    x.particles = this->particles(particles);
    return x;
  }
  /// Throws unless every value was read.
  void done() const {
    if (pos_ != in_.size()) fail();
  }
  [[noreturn]] void fail() const {
    throw InvalidArgument(fmt::format(
        "the saved state of integrator '{}' does not fit ({} values): it was saved by another integrator "
        "or for another model",
        integrator_, in_.size()));
  }

 private:
  const std::vector<double>& in_;
  std::string integrator_;
  std::size_t pos_ = 0;
};

}  // namespace tumble::saved
