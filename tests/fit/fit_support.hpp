#pragma once
// Synthetic gyro telemetry for the fit's tests, from the exact torque-free motion (EulerPoinsot: Jacobi
// elliptic functions, a method independent of the fit's RK4) seen by a gyro whose axes are turned
// against the principal axes, so that J in sensor axes is a full matrix.
#include <fmt/format.h>

#include <random>
#include <string>

#include "tumble/error.hpp"
#include "tumble/fit/gyro_fit.hpp"
#include "tumble/integrate/euler_poinsot.hpp"

namespace tumble::test {

/// A body and its motion: principal moments Λ, the principal axes in sensor axes (columns of U), the
/// angular velocity in principal axes at t = 0.
struct GyroTruth {
  Vec3 Lambda;
  Mat3 U;
  Vec3 omega_b0;
  Mat3 J() const { return U * Lambda.asDiagonal() * U.transpose(); }
  Vec3 omega0() const { return U * omega_b0; }
};

/// A triaxial body tumbling well away from the separatrix (D = L²/2E between I₂ and I₃), its sensor
/// turned by a rotation with no special angle.
inline GyroTruth tumbling_satellite() {
  const Mat3 U = (Eigen::AngleAxisd(0.7, Vec3(1, 2, 3).normalized()) * Eigen::AngleAxisd(-0.4, Vec3::UnitX()))
                     .toRotationMatrix();
  return {Vec3(120.0, 180.0, 240.0), U, Vec3(0.75, 0.45, 1.05)};
}

/// n samples every dt of y = U ω_b(t) + bias + noise (Gaussian, standard deviation `noise` per component,
/// seeded), from t = t0.
inline fit::Telemetry torque_free_telemetry(const GyroTruth& truth, int n, double dt,
                                            const Vec3& bias = Vec3::Zero(), double noise = 0.0,
                                            unsigned seed = 1, double t0 = 0.0) {
  const EulerPoinsot motion(truth.Lambda, Quat::Identity(), truth.omega_b0);
  std::mt19937_64 engine(seed);
  std::normal_distribution<double> gauss(0.0, 1.0);
  fit::Telemetry d;
  for (int k = 0; k < n; ++k) {
    const double t = k * dt;
    Vec3 y = truth.U * motion.omega_b(t) + bias;
    if (noise > 0.0) {
      for (int i = 0; i < 3; ++i) y[i] += noise * gauss(engine);
    }
    d.t.push_back(t0 + t);
    d.omega.push_back(y);
  }
  return d;
}

/// Fit options with σ and the bias flag, the rest at their defaults.
inline fit::FitOptions fit_options(double sigma, bool bias = false) {
  fit::FitOptions o;
  o.sigma = sigma;
  o.bias = bias;
  return o;
}

/// The telemetry as the CSV `tumble fit` reads (17 significant digits: the doubles exactly).
inline std::string telemetry_csv(const fit::Telemetry& d) {
  std::string text = "t,wx,wy,wz";
  if (!d.tau.empty()) text += ",tau_x,tau_y,tau_z";
  if (!d.h.empty()) text += ",h_x,h_y,h_z";
  text += "\n";
  for (std::size_t k = 0; k < d.t.size(); ++k) {
    text += fmt::format("{:.17g},{:.17g},{:.17g},{:.17g}", d.t[k], d.omega[k].x(), d.omega[k].y(),
                        d.omega[k].z());
    if (!d.tau.empty())
      text += fmt::format(",{:.17g},{:.17g},{:.17g}", d.tau[k].x(), d.tau[k].y(), d.tau[k].z());
    if (!d.h.empty()) text += fmt::format(",{:.17g},{:.17g},{:.17g}", d.h[k].x(), d.h[k].y(), d.h[k].z());
    text += "\n";
  }
  return text;
}

}  // namespace tumble::test
