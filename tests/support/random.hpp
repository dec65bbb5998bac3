#pragma once
// Seeded random inputs for property tests: every run draws the same numbers.
#include <random>

#include "tumble/mass/mass_properties.hpp"

namespace tumble::test {

class Random {
 public:
  explicit Random(unsigned seed) : engine_(seed) {}
  double uniform(double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(engine_); }
  Vec3 vec(double lo, double hi) { return Vec3(uniform(lo, hi), uniform(lo, hi), uniform(lo, hi)); }
  /// Uniformly distributed rotation (normalised Gaussian quaternion).
  Mat3 rotation() {
    std::normal_distribution<double> n;
    Quat q(n(engine_), n(engine_), n(engine_), n(engine_));
    return q.normalized().toRotationMatrix();
  }
  /// A physically valid body: random principal moments obeying the triangle inequality, rotated.
  MassProperties body() {
    const double m = uniform(0.1, 10.0);
    // Moments from a random box's extents satisfy the triangle inequality by construction.
    const Vec3 s = vec(0.1, 2.0);
    const Vec3 d(s.y() * s.y() + s.z() * s.z(), s.x() * s.x() + s.z() * s.z(), s.x() * s.x() + s.y() * s.y());
    const Mat3 R = rotation();
    return MassProperties{m, vec(-1.0, 1.0), R * (m / 12.0 * d).asDiagonal() * R.transpose(), s.prod()};
  }

 private:
  std::mt19937_64 engine_;
};

/// Largest absolute entry of A − B relative to the largest absolute entry of B.
inline double rel_diff(const Mat3& A, const Mat3& B) {
  return (A - B).cwiseAbs().maxCoeff() / B.cwiseAbs().maxCoeff();
}

}  // namespace tumble::test
