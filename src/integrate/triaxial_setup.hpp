#pragma once
// The constants of a triaxial torque-free flow from the body in sorted axes and q₀, written once as
// templates on the number type: double for TriaxialRotation (euler_poinsot_triaxial.cpp, where the
// formulas are derived), dual numbers for the flow's derivatives (free_flow_tangent.cpp, issue 25).
// The special functions enter through two overloads on the number type, declared below:
//   elliptic_constants(m, m₁, n)  the Jacobi constants of parameter m and Π(n | m)'s,
//   elliptic_first_kind(J, s, c, d, m)  F(φ | m) at sin φ = s, cos φ = c, Δ = d,
// on double the accurate evaluations of jacobi_elliptic.hpp; on dual numbers their derivatives.
// Branches (the pole, the signs σ₁, σ₃) are decided on values.
#include <cmath>
#include <utility>

#include "euler_poinsot_flows.hpp"
#include "tumble/dynamics/tangent.hpp"

namespace tumble::detail {

/// The Jacobi constants of parameter m and the constants of Π(n; am u | m), written into J and P (double:
/// JacobiElliptic and EllipticPi; dual numbers: free_flow_tangent.cpp).
void elliptic_constants(double m, double m1, double n, JacobiConstants<double>& J, PiConstants<double>& P);
void elliptic_constants(const TangentScalar& m, const TangentScalar& m1, const TangentScalar& n,
                        JacobiConstants<TangentScalar>& J, PiConstants<TangentScalar>& P);
/// F(φ | m) for |φ| ≤ π/2 from s = sin φ, c = cos φ, d = √(1 − m s²).
double elliptic_first_kind(const JacobiConstants<double>& J, double s, double c, double d, double m);
TangentScalar elliptic_first_kind(const JacobiConstants<TangentScalar>& J, const TangentScalar& s,
                                  const TangentScalar& c, const TangentScalar& d, const TangentScalar& m);

/// What the steps of the set-up hand each other besides the constants.
template <class T>
struct TriaxialParts {
  bool separatrix = false;
  int pole = 3;
  T N = T(0);             // Π's characteristic is −N
  T m = T(0), m1 = T(0);  // m = k², m₁ = k′²
  T x = T(0), y = T(0);   // ∝ (cn u₀, sn u₀) (sech, tanh on the separatrix)
  double s1 = 1.0, s3 = 1.0;
};

/// The invariant differences, the pole, the regime and every constant that needs no special function
/// (the formulas at the top of euler_poinsot_triaxial.cpp).
template <class T>
TriaxialParts<T> triaxial_amplitudes(const SortedBodyT<T>& b, TriaxialConstants<T>& k) {
  using std::abs, std::sqrt;
  const auto sign_of = [](const T& x) { return std::signbit(value_of(x)) ? -1.0 : 1.0; };
  TriaxialParts<T> out;
  k.P = b.P.template cast<T>();
  const T I1 = b.I(0), I2 = b.I(1), I3 = b.I(2);
  const T w1 = b.w(0), w2 = b.w(1), w3 = b.w(2);
  const T d1 = I2 * (I2 - I1) * w2 * w2 + I3 * (I3 - I1) * w3 * w3;
  const T d3 = I1 * (I3 - I1) * w1 * w1 + I2 * (I3 - I2) * w2 * w2;
  const T t1 = I1 * (I2 - I1) * w1 * w1, t3 = I3 * (I3 - I2) * w3 * w3;
  const T d2 = t1 - t3;
  out.separatrix = abs(value_of(d2)) <= EulerPoinsot::kSeparatrixTolerance * value_of(t1 + t3);
  out.pole = value_of(d2) >= 0.0 ? 1 : 3;
  k.pole = T(out.pole);

  const Vec3T<T> L_s = b.I.cwiseProduct(b.w);
  const T L = sqrt(L_s.squaredNorm());  // |L| in scaled units
  T lambda;
  Vec3T<T> A;
  if (out.pole == 3) {
    lambda = sqrt((I3 - I2) * d1 / (I1 * I2 * I3));
    out.m = (I2 - I1) * d3 / ((I3 - I2) * d1);
    out.m1 = (I3 - I1) * (-d2) / ((I3 - I2) * d1);
    A = Vec3T<T>(sqrt(d3 / (I1 * (I3 - I1))), sqrt(d3 / (I2 * (I3 - I2))), sqrt(d1 / (I3 * (I3 - I1))));
    out.s1 = out.separatrix ? sign_of(w1) : 1.0;
    out.s3 = sign_of(w3);
    out.N = I3 * (I2 - I1) / (I1 * (I3 - I2));
    k.kappa = (I3 - I1) * L / (I1 * I3 * lambda);
    k.c = sqrt(I3 * d1 / (I3 - I1)) / L;
    k.rho = sqrt(d3) / L;
    k.h1 = sqrt(I1 / (I3 - I1));
    k.h2 = sqrt(I2 / (I3 - I2));
    out.x = out.s1 * w1 * sqrt(I1 * (I3 - I1));
    out.y = out.s1 * out.s3 * w2 * sqrt(I2 * (I3 - I2));
  } else {
    lambda = sqrt((I2 - I1) * d3 / (I1 * I2 * I3));
    out.m = (I3 - I2) * d1 / ((I2 - I1) * d3);
    out.m1 = (I3 - I1) * d2 / ((I2 - I1) * d3);
    A = Vec3T<T>(sqrt(d3 / (I1 * (I3 - I1))), sqrt(d1 / (I2 * (I2 - I1))), sqrt(d1 / (I3 * (I3 - I1))));
    out.s1 = sign_of(w1);
    out.s3 = out.separatrix ? sign_of(w3) : 1.0;
    out.N = I1 * (I3 - I2) / (I3 * (I2 - I1));
    k.kappa = -(I3 - I1) * L / (I1 * I3 * lambda);
    k.c = sqrt(I1 * d3 / (I3 - I1)) / L;
    k.rho = sqrt(d1) / L;
    k.h1 = sqrt(I2 / (I2 - I1));
    k.h2 = sqrt(I3 / (I3 - I1));
    out.x = out.s3 * w3 * sqrt(I3 * (I3 - I1));
    out.y = out.s1 * out.s3 * w2 * sqrt(I2 * (I2 - I1));
  }
  const double s1 = out.s1, s3 = out.s3;
  k.A = T(b.omega_scale) * Vec3T<T>(s1 * A(0), s1 * s3 * A(1), s3 * A(2));
  k.lambda = T(b.omega_scale) * lambda;
  k.rate = T(b.omega_scale) * L / (out.pole == 3 ? I3 : I1);  // |L|/I_p (rad/s)
  return out;
}

/// Off the separatrix: the Jacobi and Π constants, the initial phase u₀ from (cn u₀, sn u₀) ∝ (x, y),
/// and Π₀ = Π(−N; am u₀ | m); sn, cn, dn at u₀ into f0.
template <class T>
void triaxial_phase(const TriaxialParts<T>& parts, TriaxialConstants<T>& k, SnCnDn<T>& f0) {
  using std::copysign, std::hypot, std::sqrt;
  elliptic_constants(parts.m, parts.m1, -parts.N, k.jacobi, k.pi);
  const T norm = hypot(parts.x, parts.y);
  const bool moving = value_of(norm) > 0.0;
  const T cn0 = moving ? parts.x / norm : T(1.0), sn0 = moving ? parts.y / norm : T(0.0);
  const T dn0 = sqrt(cn0 * cn0 + parts.m1 * sn0 * sn0);
  // u₀ = F(φ₀ | m) = sn R_F(cn², dn², 1) for |φ₀| ≤ π/2; F(±π − φ) = ±2K − F(φ) beyond.
  const T F = elliptic_first_kind(k.jacobi, sn0, cn0, dn0, parts.m);
  k.u0 = value_of(cn0) >= 0.0 ? F : copysign(T(2.0) * k.jacobi.K, sn0) - F;
  const LandenPoint<T> p0 = landen_point<T>(k.jacobi, k.u0);
  f0 = jacobi_sn_cn_dn<T>(k.jacobi, p0);
  k.Pi0 = elliptic_pi<T>(k.pi, p0);
}

/// C P and G: C takes the pole axis to +e₃ with μ = (T₁, T₂, c dn) (det C = +1), and R(0) = G B(0) C P
/// = R₀ gives G = R₀ (CP)ᵀ B(0)ᵀ.
template <class T>
void triaxial_frame(const TriaxialParts<T>& parts, const QuatT<T>& q0, const SnCnDn<T>& f0,
                    TriaxialConstants<T>& k, const Mat3& P) {
  const double s1 = parts.s1, s3 = parts.s3;
  Mat3 C;
  if (parts.pole == 3) {
    C = Vec3(s1, s1 * s3, s3).asDiagonal();
  } else {
    Mat3 cyclic;  // (v₁, v₂, v₃) ↦ (v₂, v₃, v₁)
    cyclic << 0, 1, 0, 0, 0, 1, 1, 0, 0;
    C = Vec3(s1 * s3, s3, s1).asDiagonal() * cyclic;
  }
  k.CP = Quat(Mat3(C * P)).template cast<T>();
  k.G = q0 * k.CP.conjugate() * triaxial_body_part<T>(k, T(0.0), f0).conjugate();
}

}  // namespace tumble::detail
