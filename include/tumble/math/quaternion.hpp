#pragma once
// Quaternion helpers. tumble writes quaternions (w, x, y, z) at every boundary; Eigen stores them
// (x, y, z, w): convert here and nowhere else.
#include <cmath>

#include "tumble/math/lanes.hpp"
#include "tumble/math/types.hpp"

namespace tumble {

template <class T>
using Vec3T = Eigen::Matrix<T, 3, 1>;
template <class T>
using Mat3T = Eigen::Matrix<T, 3, 3>;
template <class T>
using QuatT = Eigen::Quaternion<T>;

/// The quaternion w + xi + yj + zk (as written in files and on the command line).
inline Quat quat_wxyz(double w, double x, double y, double z) { return Quat(w, x, y, z); }
/// (w, x, y, z) of q.
inline Eigen::Vector4d wxyz(const Quat& q) { return {q.w(), q.x(), q.y(), q.z()}; }

/// The pure quaternion (0, v).
template <class T>
TUMBLE_INLINE QuatT<T> pure(const Vec3T<T>& v) {
  return QuatT<T>(T(0), v.x(), v.y(), v.z());
}

/// The Hamilton product a ⊗ b, written out. The equations use this rather than Eigen's operator*, whose
/// double version is hand-vectorised with another order of operations than its generic one: double and
/// SIMD packs would then differ in the last bit.
template <class T>
TUMBLE_INLINE QuatT<T> quat_mul(const QuatT<T>& a, const QuatT<T>& b) {
  return QuatT<T>(a.w() * b.w() - a.x() * b.x() - a.y() * b.y() - a.z() * b.z(),
                  a.w() * b.x() + a.x() * b.w() + a.y() * b.z() - a.z() * b.y(),
                  a.w() * b.y() - a.x() * b.z() + a.y() * b.w() + a.z() * b.x(),
                  a.w() * b.z() + a.x() * b.y() - a.y() * b.x() + a.z() * b.w());
}

/// q ⊗ (0, u) and (0, u) ⊗ q: quat_mul with a pure quaternion, its products with the zero left out
/// (a·0 is not 0 in IEEE arithmetic, so the compiler keeps them). The same sums in the same order as
/// quat_mul: equal to it bit for bit but for the sign of a zero.
template <class T>
TUMBLE_INLINE QuatT<T> quat_mul_pure(const QuatT<T>& q, const Vec3T<T>& u) {
  return QuatT<T>(-(q.x() * u.x()) - q.y() * u.y() - q.z() * u.z(),
                  q.w() * u.x() + q.y() * u.z() - q.z() * u.y(),
                  q.w() * u.y() - q.x() * u.z() + q.z() * u.x(),
                  q.w() * u.z() + q.x() * u.y() - q.y() * u.x());
}
template <class T>
TUMBLE_INLINE QuatT<T> pure_mul_quat(const Vec3T<T>& u, const QuatT<T>& q) {
  return QuatT<T>(-(u.x() * q.x()) - u.y() * q.y() - u.z() * q.z(),
                  u.x() * q.w() + u.y() * q.z() - u.z() * q.y(),
                  -(u.x() * q.z()) + u.y() * q.w() + u.z() * q.x(),
                  u.x() * q.y() - u.y() * q.x() + u.z() * q.w());
}

/// R v for the unit quaternion q of R: v + w t + u × t with t = 2 u × v, q = (w, u) — Eigen's formula
/// for q * v, written here so that it inlines into the pack loops (Eigen's call is not inlined there,
/// and spilled the kernel's registers).
template <class T>
TUMBLE_INLINE Vec3T<T> rotate(const QuatT<T>& q, const Vec3T<T>& v) {
  const Vec3T<T> u = q.vec();
  Vec3T<T> t = u.cross(v);
  t += t;
  return v + q.w() * t + u.cross(t);
}
/// Rᵀ v.
template <class T>
TUMBLE_INLINE Vec3T<T> rotate_inverse(const QuatT<T>& q, const Vec3T<T>& v) {
  return rotate<T>(q.conjugate(), v);
}

/// |v|² and |q|², summed in one fixed order (Eigen's reductions may vectorise for double).
template <class T>
TUMBLE_INLINE T squared_norm(const Vec3T<T>& v) {
  return v.x() * v.x() + v.y() * v.y() + v.z() * v.z();
}
template <class T>
TUMBLE_INLINE T squared_norm(const QuatT<T>& q) {
  return q.w() * q.w() + q.x() * q.x() + q.y() * q.y() + q.z() * q.z();
}

/// exp of the rotation vector φ: the unit quaternion (cos(|φ|/2), sin(|φ|/2) φ/|φ|), i.e. the rotation
/// by |φ| about φ. Below |φ|² = 1e-8 the Taylor series (error < 1e-26, under rounding) replaces
/// sin(θ/2)/θ, whose quotient loses accuracy as θ → 0 and is 0/0 at 0. Branch-free: both forms are
/// computed and `select` keeps one per lane (the other may be 0/0 there, and is discarded).
template <class T>
TUMBLE_INLINE QuatT<T> quat_exp(const Vec3T<T>& phi) {
  using std::sqrt;
  const T theta2 = squared_norm<T>(phi);
  const T theta = sqrt(theta2);
  const auto small = theta2 < T(1e-8);
  const auto [sin_half, cos_half] = sincos(theta / T(2));
  const T c = select(small, T(1) - theta2 / T(8) + theta2 * theta2 / T(384), cos_half);
  const T s = select(small, T(0.5) - theta2 / T(48) + theta2 * theta2 / T(3840), sin_half / theta);
  return QuatT<T>(c, s * phi.x(), s * phi.y(), s * phi.z());
}

/// q/|q|, branch-free (Eigen's normalize() tests the norm, a branch on a value). Projects a stage or
/// step quaternion back onto the unit sphere.
template <class T>
TUMBLE_INLINE QuatT<T> normalized(const QuatT<T>& q) {
  using std::sqrt;
  const T inv_norm = T(1) / sqrt(squared_norm<T>(q));
  return QuatT<T>(q.w() * inv_norm, q.x() * inv_norm, q.y() * inv_norm, q.z() * inv_norm);
}

/// The rotation vector of a unit quaternion (angle in [0, π]).
inline Vec3 quat_log(const Quat& q_in) {
  const Quat q = q_in.w() < 0 ? Quat(-q_in.coeffs()) : q_in;
  const double s = q.vec().norm();
  if (s < 1e-12) return 2.0 * q.vec() / q.w();
  return 2.0 * std::atan2(s, q.w()) / s * q.vec();
}

/// The angle of the rotation that takes R1 to R2 (the angle of R1ᵀR2), in [0, π]; accurate for small
/// angles too (uses the skew part, not the trace alone).
inline double rotation_angle_between(const Mat3& R1, const Mat3& R2) {
  const Mat3 D = R1.transpose() * R2;
  const Vec3 axis(D(2, 1) - D(1, 2), D(0, 2) - D(2, 0), D(1, 0) - D(0, 1));
  return std::atan2(0.5 * axis.norm(), 0.5 * (D.trace() - 1.0));
}

}  // namespace tumble
