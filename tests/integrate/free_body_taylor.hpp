#pragma once
// The tests' independent reference for the torque-free body: the Taylor-series method
// (integrate/free_body_taylor.hpp) in long double or __float128, and conversions to and from it.
#include "integrate/free_body_taylor.hpp"

namespace tumble::test {

template <class Real>
using FreeBodyStateT = tumble::FreeBodyStateT<Real>;
template <class Real>
using FreeBodyTaylorT = tumble::FreeBodyTaylorT<Real>;
using FreeBodyStateLd = FreeBodyStateT<long double>;
using FreeBodyTaylor = FreeBodyTaylorT<long double>;

template <class Real = long double>
FreeBodyStateT<Real> to_ld(const Quat& q, const Vec3& w) {
  return {{Real(w(0)), Real(w(1)), Real(w(2))}, {Real(q.w()), Real(q.x()), Real(q.y()), Real(q.z())}};
}
template <class Real>
Vec3 omega_of(const FreeBodyStateT<Real>& s) {
  return Vec3(static_cast<double>(s.w[0]), static_cast<double>(s.w[1]), static_cast<double>(s.w[2]));
}
template <class Real>
Quat quat_of(const FreeBodyStateT<Real>& s) {
  return Quat(static_cast<double>(s.q[0]), static_cast<double>(s.q[1]), static_cast<double>(s.q[2]),
              static_cast<double>(s.q[3]))
      .normalized();
}

}  // namespace tumble::test
