// Where the solver starts. Euler's equation is linear in J:
//     J ω̇ − (J ω) × ω = h × ω + τ − ḣ,
// so rates ω̇ from central differences of the samples give J by linear least squares (with neither τ nor
// h the right side is zero and J is the singular vector of the smallest singular value, scaled to
// trace 1). Differences of noisy samples make that J rough, but it is near the answer when the data
// are well sampled, which the nonlinear fit needs; an isotropic J is the second start, used when the
// first ends with residuals larger than the noise.
#include <Eigen/Dense>
#include <algorithm>

#include "fit_parts.hpp"

namespace tumble::fit {
namespace {

/// M(v), the 3×6 matrix with J v = M(v) (Jxx, Jyy, Jzz, Jxy, Jxz, Jyz).
Eigen::Matrix<double, 3, 6> times(const Vec3& v) {
  Eigen::Matrix<double, 3, 6> M;
  M << v.x(), 0, 0, v.y(), v.z(), 0,  //
      0, v.y(), 0, v.x(), 0, v.z(),   //
      0, 0, v.z(), 0, v.x(), v.y();
  return M;
}

Mat3 tensor(const Eigen::Matrix<double, 6, 1>& j) {
  Mat3 J;
  J << j[0], j[3], j[4],  //
      j[3], j[1], j[5],   //
      j[4], j[5], j[2];
  return J;
}

/// J with its eigenvalues raised to at least 2 % of its trace: a start must be positive definite.
Mat3 positive_definite(const Mat3& J) {
  Eigen::SelfAdjointEigenSolver<Mat3> eig(J);
  const double floor = 0.02 * std::max(J.trace(), 0.0);
  const Vec3 lambda = eig.eigenvalues().cwiseMax(floor);
  return eig.eigenvectors() * lambda.asDiagonal() * eig.eigenvectors().transpose();
}

Eigen::VectorXd start(const Telemetry& d, const Layout& layout, const Mat3& J) {
  Eigen::VectorXd p = Eigen::VectorXd::Zero(layout.size());
  p[0] = J(0, 0);
  p[1] = J(1, 1);
  const int o = layout.absolute ? 3 : 2;
  if (layout.absolute) p[2] = J(2, 2);
  p[o] = J(0, 1);
  p[o + 1] = J(0, 2);
  p[o + 2] = J(1, 2);
  p.segment<3>(layout.omega0_index()) = d.omega[0];  // ω(t₀) as measured (bias starts at 0)
  return p;
}

}  // namespace

std::vector<Eigen::VectorXd> starting_points(const Telemetry& d, const Layout& layout) {
  const std::size_t n = d.t.size();
  Eigen::MatrixXd A(3 * (n - 2), 6);
  Eigen::VectorXd rhs(3 * (n - 2));
  for (std::size_t k = 1; k + 1 < n; ++k) {
    const double span = d.t[k + 1] - d.t[k - 1];
    const Vec3 omega = d.omega[k];
    const Vec3 omega_dot = (d.omega[k + 1] - d.omega[k - 1]) / span;
    // −(J ω) × ω = ω × (J ω) = [ω]× M(ω) j.
    A.middleRows<3>(3 * static_cast<Eigen::Index>(k - 1)) = times(omega_dot) + skew(omega) * times(omega);
    Vec3 b = Vec3::Zero();
    if (!d.h.empty()) b += d.h[k].cross(omega) - (d.h[k + 1] - d.h[k - 1]) / span;
    if (!d.tau.empty()) b += d.tau[k];
    rhs.segment<3>(3 * static_cast<Eigen::Index>(k - 1)) = b;
  }

  std::vector<Eigen::VectorXd> starts;
  double scale = 1.0;  // trace J of the isotropic start
  if (layout.absolute) {
    const Eigen::Matrix<double, 6, 1> j = A.colPivHouseholderQr().solve(rhs);
    const Mat3 J = tensor(j);
    if (J.allFinite() && J.trace() > 0.0) {
      starts.push_back(start(d, layout, positive_definite(J)));
      scale = J.trace();
    }
  } else {
    const Eigen::Matrix<double, 6, 6> N = A.transpose() * A;
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, 6, 6>> eig(N);
    const Eigen::Matrix<double, 6, 1> j = eig.eigenvectors().col(0);  // the smallest singular value's
    const double trace = j[0] + j[1] + j[2];
    if (j.allFinite() && std::abs(trace) > 1e-3 * j.norm()) {
      const Mat3 J = positive_definite(tensor(j / trace));
      starts.push_back(start(d, layout, J / J.trace()));
    }
  }
  starts.push_back(start(d, layout, Mat3::Identity() * (scale / 3.0)));
  return starts;
}

}  // namespace tumble::fit
