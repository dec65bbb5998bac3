// What a solution means: the estimate in the quantities users read (J, principal moments and axes,
// ratios), their standard deviations from the covariance of the unknowns, the residuals, and whether
// the data determine the inertia at all.
//
// Covariance. With Gaussian noise of the σ given, the unknowns' covariance at the solution is
// C = (AᵀA)⁻¹, A the Jacobian of the whitened residuals (y − ŷ)/σ (the linearised model; unscaled by
// the residuals, since σ is known). It is formed as D (D AᵀA D)⁻¹ D with D = diag(AᵀA)^(−½), so that the
// unknowns' units do not enter its conditioning. A derived quantity g(p) gets var g = ∇g C ∇gᵀ: a
// principal moment I_i = u_iᵀ J u_i has ∂I_i = u_iᵀ ∂J u_i, an axis u_i turns by u_lᵀ ∂J u_i / (I_i − I_l)
// towards each other axis u_l (first-order perturbation of a symmetric eigenproblem).
//
// Verdict. The inertia is "not determined" when A is rank-deficient to rounding (the scaled normal
// matrix's condition number above 1e16: some combination of unknowns changes no prediction, e.g. a
// spin about one principal axis says nothing about the moments), or when a principal moment's
// standard deviation exceeds a third of it (its 3σ range reaches zero).
#include <Eigen/Dense>
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "fit_parts.hpp"
#include "tumble/mass/mass_properties.hpp"

namespace tumble::fit {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

/// The scaled normal matrix's condition number past which A counts as rank-deficient: its smallest
/// eigenvalue is then below the rounding of its largest (the Jacobian from dual numbers is exact to
/// rounding, ~1e-16 relative).
constexpr double kRankDeficient = 1e16;

std::vector<std::string> parameter_names(const Layout& layout) {
  std::vector<std::string> names = {"J_xx", "J_yy"};
  if (layout.absolute) names.emplace_back("J_zz");
  for (const char* n : {"J_xy", "J_xz", "J_yz", "omega0_x", "omega0_y", "omega0_z"}) names.emplace_back(n);
  if (layout.bias) {
    for (const char* n : {"bias_x", "bias_y", "bias_z"}) names.emplace_back(n);
  }
  return names;
}

std::string vec_text(const Vec3& v) { return fmt::format("({:.3f}, {:.3f}, {:.3f})", v.x(), v.y(), v.z()); }

/// Why the data cannot determine the inertia, from the data themselves where the cause is plain (a body
/// at rest, a spin about one fixed axis), else from the combination of unknowns the fit cannot resolve.
std::string diagnosis(const Telemetry& d, double sigma, bool absolute, const std::vector<std::string>& names,
                      const Eigen::VectorXd& weakest, const std::string& fallback) {
  const std::size_t n = d.t.size();
  Vec3 mean = Vec3::Zero();
  Mat3 second = Mat3::Zero();
  double omega_max = 0.0;
  for (const Vec3& y : d.omega) {
    mean += y / static_cast<double>(n);
    second += y * y.transpose() / static_cast<double>(n);
    omega_max = std::max(omega_max, y.norm());
  }
  if (omega_max <= 5.0 * sigma) {
    return fmt::format(
        "the body is at rest within the noise (|omega| <= {:.3g} rad/s, sigma {:.3g}): a body that does not "
        "turn "
        "shows nothing of its inertia; record it tumbling",
        omega_max, sigma);
  }
  // The direction ω keeps: the dominant axis of Σ y yᵀ. The spread of y about its mean across that axis
  // (a bias only shifts the mean) within the noise means ω never left it.
  Eigen::SelfAdjointEigenSolver<Mat3> eig(second);
  const Vec3 u = eig.eigenvectors().col(2);
  double spread = 0.0;
  for (const Vec3& y : d.omega) {
    const Vec3 off = (y - mean) - (y - mean).dot(u) * u;
    spread += off.squaredNorm() / static_cast<double>(n);
  }
  spread = std::sqrt(spread);
  if (spread <= 3.0 * sigma) {
    const Vec3 axis = u * (u.dot(mean) < 0 ? -1.0 : 1.0);
    return fmt::format(
        "the body spins about one axis, {} in sensor axes (omega stays along it: its spread across it, "
        "{:.2g} rad/s, is within the noise): such data show only {}; the {}other two axes are not "
        "observable. Excite the other axes (a tumble, a nutation, or a known torque about another axis)",
        vec_text(axis), spread,
        absolute ? "the moment about this axis (the torque along it over the spin-up) and that it is a "
                   "principal axis"
                 : "that this axis is a principal axis",
        absolute ? "" : "moments and the ");
  }
  std::string involved;
  for (Eigen::Index j = 0; j < weakest.size(); ++j) {
    if (std::abs(weakest[j]) < 0.3 * weakest.cwiseAbs().maxCoeff()) continue;
    involved += fmt::format("{}{}", involved.empty() ? "" : ", ", names[static_cast<std::size_t>(j)]);
  }
  return fmt::format(
      "{}: the combination of {} is not determined by these data (it barely changes the "
      "predicted gyro samples); record a longer or livelier tumble",
      fallback, involved);
}

}  // namespace

void assess(const Telemetry& d, const Layout& layout, const Eigen::VectorXd& p, const Eigen::VectorXd& r,
            const Eigen::MatrixXd& A, FitResult& result) {
  const int P = layout.size();
  const double sigma = result.sigma;
  result.parameter_names = parameter_names(layout);
  result.parameters = p;
  result.residuals = static_cast<std::size_t>(r.size());
  result.chi2 = r.squaredNorm();
  result.rms_sigma = std::sqrt(result.chi2 / static_cast<double>(r.size()));
  result.rms = result.rms_sigma * sigma;

  // The estimate.
  result.J = inertia_of(layout, p.data());
  const PrincipalAxes axes = principal_axes(result.J, {0.0});
  const Vec3& I = axes.Lambda;
  const Mat3& U = axes.U;
  result.principal_moments.value = I;
  result.principal_axes = U;
  result.ratios = Eigen::Vector2d(I[0] / I[2], I[1] / I[2]);
  result.positive_definite = I[0] > 0.0;
  result.triangle_inequality = I[0] + I[1] >= I[2];
  result.omega0.value = p.segment<3>(layout.omega0_index());
  if (layout.bias) result.bias.value = p.segment<3>(layout.bias_index());

  // The covariance, scaled as the header says.
  const Eigen::MatrixXd F = A.transpose() * A;
  const Eigen::VectorXd scale = F.diagonal().cwiseSqrt();
  bool rank_deficient = (scale.array() <= 0.0).any() || !F.allFinite();
  Eigen::VectorXd weakest = Eigen::VectorXd::Zero(P);
  Eigen::MatrixXd C = Eigen::MatrixXd::Constant(P, P, kNaN);
  if (!rank_deficient) {
    const Eigen::VectorXd Dinv = scale.cwiseInverse();
    const Eigen::MatrixXd Fs = Dinv.asDiagonal() * F * Dinv.asDiagonal();
    Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(Fs);
    const double lo = eig.eigenvalues()[0], hi = eig.eigenvalues()[P - 1];
    result.condition_number = lo > 0.0 ? std::sqrt(hi / lo) : std::numeric_limits<double>::infinity();
    weakest = Dinv.asDiagonal() * eig.eigenvectors().col(0);
    if (lo > 0.0 && hi / lo <= kRankDeficient) {
      C = Dinv.asDiagonal() *
          (eig.eigenvectors() * eig.eigenvalues().cwiseInverse().asDiagonal() *
           eig.eigenvectors().transpose()) *
          Dinv.asDiagonal();
    } else {
      rank_deficient = true;
    }
  } else {
    result.condition_number = std::numeric_limits<double>::infinity();
    for (Eigen::Index j = 0; j < P; ++j) weakest[j] = scale[j] <= 0.0 ? 1.0 : 0.0;
  }
  result.covariance = C;

  // ∂J/∂p_j (J is affine in p).
  std::vector<Mat3> dJ(static_cast<std::size_t>(layout.inertia_size()));
  {
    Eigen::VectorXd e = Eigen::VectorXd::Zero(P);
    const Mat3 J0 = inertia_of(layout, e.data());
    for (int j = 0; j < layout.inertia_size(); ++j) {
      e.setZero();
      e[j] = 1.0;
      dJ[static_cast<std::size_t>(j)] = inertia_of(layout, e.data()) - J0;
    }
  }
  // √(∇g C ∇gᵀ) for g whose gradient has only inertia components, given as g(∂J).
  const auto sd = [&](const auto& g) {
    Eigen::VectorXd grad = Eigen::VectorXd::Zero(P);
    for (int j = 0; j < layout.inertia_size(); ++j) grad[j] = g(dJ[static_cast<std::size_t>(j)]);
    const double var = grad.dot(C * grad);
    return var >= 0.0 ? std::sqrt(var) : kNaN;
  };
  for (int a = 0; a < 3; ++a) {
    for (int b = 0; b < 3; ++b) result.J_sigma(a, b) = sd([&](const Mat3& D) { return D(a, b); });
  }
  for (int i = 0; i < 3; ++i) {
    const Vec3 u = U.col(i);
    result.principal_moments.sigma[i] = sd([&](const Mat3& D) { return u.dot(D * u); });
    double var = 0.0;
    for (int l = 0; l < 3; ++l) {
      if (l == i) continue;
      const Vec3 v = U.col(l);
      const double gap = I[i] - I[l];
      const double s = gap != 0.0 ? sd([&](const Mat3& D) { return v.dot(D * u) / gap; }) : kNaN;
      var += s * s;
    }
    result.axis_sigma[i] = std::sqrt(var);
  }
  for (int i = 0; i < 2; ++i) {
    const Vec3 u = U.col(i), w = U.col(2);
    result.ratios_sigma[i] =
        sd([&](const Mat3& D) { return (u.dot(D * u) * I[2] - I[i] * w.dot(D * w)) / (I[2] * I[2]); });
  }
  for (int i = 0; i < 3; ++i) {
    const Eigen::Index o = layout.omega0_index() + i;
    result.omega0.sigma[i] = C(o, o) >= 0.0 ? std::sqrt(C(o, o)) : kNaN;
    if (layout.bias) {
      const Eigen::Index b = layout.bias_index() + i;
      result.bias.sigma[i] = C(b, b) >= 0.0 ? std::sqrt(C(b, b)) : kNaN;
    }
  }

  // The verdict.
  int loosest = 0;
  for (int i = 1; i < 3; ++i) {
    if (result.principal_moments.sigma[i] / I[i] > result.principal_moments.sigma[loosest] / I[loosest])
      loosest = i;
  }
  const double relative = result.principal_moments.sigma[loosest] / I[loosest];
  if (rank_deficient) {
    result.determined = false;
    result.reason = diagnosis(d, sigma, layout.absolute, result.parameter_names, weakest,
                              fmt::format("the fit's Jacobian is rank-deficient (condition number {:.2g})",
                                          result.condition_number));
  } else if (!(relative <= 1.0 / 3.0)) {
    result.determined = false;
    result.reason = diagnosis(
        d, sigma, layout.absolute, result.parameter_names, weakest,
        fmt::format("principal moment I{} = {:.4g} +- {:.2g} (1 sigma): its 3-sigma range reaches zero",
                    loosest + 1, I[loosest], result.principal_moments.sigma[loosest]));
  } else {
    result.determined = true;
    result.reason =
        fmt::format("the principal moments are determined to {:.2g} % (1 sigma) or better", 100 * relative);
  }

  // Notes.
  const double dof = static_cast<double>(r.size()) - P;
  if (result.chi2 > dof + 5.0 * std::sqrt(2.0 * dof)) {
    result.notes.push_back(fmt::format(
        "the residuals' RMS is {:.3g} sigma, more than the noise allows: sigma is too small, or the model "
        "misses "
        "something (an unknown torque, a drifting bias, a flexible mount, a clock offset); the standard "
        "deviations reported are then too small",
        result.rms_sigma));
  } else if (result.chi2 < dof - 5.0 * std::sqrt(2.0 * dof)) {
    result.notes.push_back(fmt::format(
        "the residuals' RMS is {:.3g} sigma, less than the noise given: sigma may be too large, and the "
        "standard deviations reported with it",
        result.rms_sigma));
  }
  if (!result.triangle_inequality) {
    const double excess = I[2] - I[0] - I[1], sigma_I3 = result.principal_moments.sigma[2];
    result.notes.push_back(fmt::format(
        "the estimate breaks the triangle inequality I1 + I2 >= I3 by {:.3g}{}: no rigid body has this "
        "inertia",
        excess,
        std::isfinite(sigma_I3) ? fmt::format(" ({:.2g} sigma of I3)", excess / sigma_I3) : std::string()));
  }
}

}  // namespace tumble::fit
