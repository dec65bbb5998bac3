#pragma once
// Eigen aliases and the skew-symmetric matrix [w]x of the tutorial (section II).
#include <Eigen/Core>
#include <Eigen/Geometry>

#include "tumble/math/lanes.hpp"

namespace tumble {

using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;
using Quat = Eigen::Quaterniond;  // Eigen stores (x, y, z, w); tumble's files and APIs say (w, x, y, z)

/// [w]x, the matrix with [w]x v = w x v:
///   (  0  -wz   wy )
///   (  wz   0  -wx )
///   ( -wy  wx    0 )
template <class Scalar>
TUMBLE_INLINE Eigen::Matrix<Scalar, 3, 3> skew(const Eigen::Matrix<Scalar, 3, 1>& w) {
  Eigen::Matrix<Scalar, 3, 3> S;
  S << Scalar(0), -w.z(), w.y(),  //
      w.z(), Scalar(0), -w.x(),   //
      -w.y(), w.x(), Scalar(0);
  return S;
}

}  // namespace tumble
