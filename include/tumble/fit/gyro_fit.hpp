#pragma once
// A rigid body's inertia identified from its gyro telemetry (`tumble fit`, docs/fit.md).
//
// The gyro measures the body's angular velocity ω in its own (body-fixed) axes, the sensor's. In those
// axes Euler's equation with a known applied torque τ and a known wheel angular momentum h reads
// (tutorial, section V; h adds to the body's own momentum Jω):
//
//     J ω̇ = (J ω + h) × ω + τ − ḣ,
//
// with J the inertia tensor in sensor axes (symmetric positive definite). The gyro's samples are
// y_k = ω(t_k) + b + n_k, b an optional constant bias, n_k Gaussian with standard deviation σ per
// component. fit_gyro() finds J, ω(t₀) and b by weighted least squares (Ceres, Levenberg–Marquardt),
// ω(t) integrated by RK4 and its Jacobian by the same code on dual numbers (math/dual.hpp), and
// reports the covariance of the estimate and whether the data determine the inertia at all.
//
// Without τ or h the equation is homogeneous in J: J and cJ give the same motion, so only J up to a
// scale is observable and J is reported normalised to trace 1. With a known torque or wheel momentum
// J is absolute (kg·m²).
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Core>

#include "tumble/math/types.hpp"

namespace tumble::fit {

/// Gyro telemetry: the body's measured angular velocity in sensor axes, and what is known of the torque
/// and wheel momentum acting on it, in the same axes, at the same times.
struct Telemetry {
  std::vector<double> t;    ///< sample times (s), strictly increasing
  std::vector<Vec3> omega;  ///< measured angular velocity ω (rad/s), sensor axes
  std::vector<Vec3> tau;    ///< known applied torque τ (N·m) at each sample, or empty (none)
  std::vector<Vec3> h;      ///< known wheel angular momentum h (N·m·s) at each sample, or empty (none)
  std::vector<long> line;   ///< each sample's line in its file (empty for telemetry from arrays)
  std::string source = "telemetry";  ///< the file's name in messages
};

/// The fewest samples fit_gyro() accepts: 3 components each, more than the at most 12 unknowns, with
/// room left to judge the residuals.
inline constexpr std::size_t kMinSamples = 10;

/// Reads telemetry from a CSV file (format in docs/fit.md: a header line naming the columns t, wx, wy,
/// wz and optionally tau_x, tau_y, tau_z and h_x, h_y, h_z, in any order; then one sample per line;
/// blank lines and lines starting with '#' are skipped). Throws FileError naming file:line (and column)
/// for a file that cannot be read, a header that is not the one above, a line with the wrong number of
/// fields, a field that is not a number or not finite, times that do not increase, too few samples.
[[nodiscard]] Telemetry read_telemetry(const std::filesystem::path& path);
/// The same from the file's text; `source` names it in messages.
[[nodiscard]] Telemetry parse_telemetry(std::string_view text, const std::string& source);
/// Throws InvalidArgument (FileError when the samples have lines) unless the telemetry can be fitted:
/// as many ω as t (and τ, h, if given), every value finite, t strictly increasing, at least kMinSamples
/// samples. Messages name the sample's file:line, or its index and time.
void check_telemetry(const Telemetry& telemetry);

struct FitOptions {
  double sigma = 0.0;  ///< the gyro's noise, standard deviation per component (rad/s), > 0
  bool bias = false;   ///< also estimate a constant gyro bias b (3 unknowns)
  /// The longest RK4 step (s). Default: chosen from the data so that the integration error (estimated
  /// by step halving, Richardson) is below 0.1 σ/√(3n) at every sample (docs/fit.md, "Steps").
  std::optional<double> substep;
  int max_iterations = 100;  ///< of Levenberg–Marquardt, per start
};

/// A value and its standard deviation from the covariance (NaN when the data do not determine it).
struct Estimated3 {
  Vec3 value = Vec3::Zero();
  Vec3 sigma = Vec3::Zero();
};

struct FitResult {
  std::size_t samples = 0;
  double t0 = 0.0;        ///< the first sample's time: ω₀ is ω(t₀)
  double duration = 0.0;  ///< t_last − t₀
  double sigma = 0.0;     ///< the σ given
  bool absolute = false;  ///< true: J in kg·m² (a torque or wheel momentum is known); false: J / trace J
  bool bias_estimated = false;

  // The estimate.
  Mat3 J = Mat3::Identity();               ///< inertia tensor in sensor axes (kg·m², or / trace J)
  Mat3 J_sigma = Mat3::Zero();             ///< the standard deviation of each entry
  Estimated3 principal_moments;            ///< I₁ ≤ I₂ ≤ I₃, eigenvalues of J
  Mat3 principal_axes = Mat3::Identity();  ///< columns: the principal axes in sensor axes (det +1)
  Vec3 axis_sigma = Vec3::Zero();          ///< the standard deviation of each axis's direction (rad)
  Eigen::Vector2d ratios = Eigen::Vector2d::Zero();        ///< I₁/I₃, I₂/I₃
  Eigen::Vector2d ratios_sigma = Eigen::Vector2d::Zero();  ///< their standard deviations
  bool positive_definite = false;
  bool triangle_inequality = false;  ///< I₁ + I₂ ≥ I₃
  Estimated3 omega0;                 ///< ω(t₀), sensor axes (rad/s)
  Estimated3 bias;                   ///< b (rad/s), zero when not estimated

  // The parameters solved for and their covariance (from the whitened Jacobian at the solution,
  // (AᵀA)⁻¹); NaN when the data do not determine them.
  std::vector<std::string> parameter_names;
  Eigen::VectorXd parameters;
  Eigen::MatrixXd covariance;
  double condition_number = 0.0;  ///< of the whitened Jacobian with its columns scaled to unit norm

  // The residuals r = (y − ŷ)/σ at the solution.
  std::size_t residuals = 0;  ///< 3 per sample
  double chi2 = 0.0;          ///< Σ r²
  double rms_sigma = 0.0;     ///< √(Σ r² / residuals): about 1 when the model and σ fit the data
  double rms = 0.0;           ///< the same in rad/s

  // How it was solved.
  int iterations = 0;              ///< Levenberg–Marquardt iterations of the start kept
  int starts = 0;                  ///< starting points tried
  std::string termination;         ///< Ceres's message
  double substep = 0.0;            ///< the longest RK4 step used (s)
  double integration_error = 0.0;  ///< estimated max RK4 error of ŷ at the solution (rad/s)

  // The verdict.
  bool determined = false;
  std::string reason;              ///< why not, or what limits the estimate
  std::vector<std::string> notes;  ///< warnings worth reading (residuals larger than σ, ...)
};

/// Fits the model above to the telemetry (checked first: check_telemetry). Throws InvalidArgument for
/// σ ≤ 0 or not finite, a substep ≤ 0, max_iterations < 1; Error when the solver fails.
[[nodiscard]] FitResult fit_gyro(const Telemetry& telemetry, const FitOptions& options);

/// The result as the JSON `tumble fit` prints (docs/fit.md lists every key); a quantity the data do not
/// determine is null, never NaN.
[[nodiscard]] std::string fit_json(const FitResult& result);

}  // namespace tumble::fit
