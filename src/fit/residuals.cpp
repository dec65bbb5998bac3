// The residuals of the gyro model and their Jacobian: the model of gyro_model.hpp run once on
// Dual<double, N>, N the number of unknowns (8, 9, 11 or 12), each unknown seeded along its own
// direction, so that every predicted sample carries its derivatives with respect to all of them.
#include <algorithm>
#include <limits>
#include <vector>

#include "fit_parts.hpp"

namespace tumble::fit {
namespace {

template <int N>
bool residuals_with_jacobian(const Telemetry& d, const Steps& steps, const Layout& layout, double sigma,
                             const double* p, double* r, double* jacobian) {
  using D = Dual<double, N>;
  D q[N];
  for (int j = 0; j < N; ++j) q[j] = D::variable(p[j], j);
  std::vector<Vec3T<D>> y_hat(d.t.size());
  if (!predict<D>(d, steps, layout, q, y_hat.data())) return false;
  const double w = 1.0 / sigma;
  for (std::size_t k = 0; k < d.t.size(); ++k) {
    for (int i = 0; i < 3; ++i) {
      const std::size_t row = 3 * k + static_cast<std::size_t>(i);
      r[row] = (d.omega[k][i] - y_hat[k][i].v) * w;  // r = (y − ŷ)/σ
      for (int j = 0; j < N; ++j) jacobian[row * N + static_cast<std::size_t>(j)] = -y_hat[k][i].d[j] * w;
    }
  }
  return true;
}

}  // namespace

bool whitened_residuals(const Telemetry& d, const Steps& steps, const Layout& layout, double sigma,
                        const double* p, double* r, double* jacobian) {
  if (jacobian == nullptr) {
    std::vector<Vec3> y_hat(d.t.size());
    if (!predict<double>(d, steps, layout, p, y_hat.data())) return false;
    for (std::size_t k = 0; k < d.t.size(); ++k) {
      for (int i = 0; i < 3; ++i)
        r[3 * k + static_cast<std::size_t>(i)] = (d.omega[k][i] - y_hat[k][i]) / sigma;
    }
    return true;
  }
  switch (layout.size()) {
    case 8:
      return residuals_with_jacobian<8>(d, steps, layout, sigma, p, r, jacobian);
    case 9:
      return residuals_with_jacobian<9>(d, steps, layout, sigma, p, r, jacobian);
    case 11:
      return residuals_with_jacobian<11>(d, steps, layout, sigma, p, r, jacobian);
    case 12:
      return residuals_with_jacobian<12>(d, steps, layout, sigma, p, r, jacobian);
    default:
      return false;  // no other layout exists (Layout: 5 or 6 + 3 + 0 or 3)
  }
}

double integration_error(const Telemetry& d, const Steps& steps, const Layout& layout, const double* p) {
  Steps halved = steps;
  for (int& n : halved.per_interval) n *= 2;
  halved.longest /= 2;
  std::vector<Vec3> coarse(d.t.size()), fine(d.t.size());
  if (!predict<double>(d, steps, layout, p, coarse.data()) ||
      !predict<double>(d, halved, layout, p, fine.data()))
    return std::numeric_limits<double>::infinity();
  double worst = 0.0;
  for (std::size_t k = 0; k < d.t.size(); ++k)
    worst = std::max(worst, (coarse[k] - fine[k]).cwiseAbs().maxCoeff());
  return worst * 16.0 / 15.0;
}

}  // namespace tumble::fit
