// The RK4 steps between samples. The step must make the integration error negligible against the
// noise: an error δ common to all 3n residuals can move an estimate by up to δ√(3n)/σ of its standard
// deviation, so the default keeps δ below 0.1 σ/√(3n) (a tenth of a standard deviation at most). δ is
// estimated by step halving at the point given (Richardson), starting from a step of one sample
// interval and at most 0.1/max|ω| (a tenth of a radian of rotation per step), halved until it passes.
#include <algorithm>
#include <cmath>

#include "fit_parts.hpp"

namespace tumble::fit {

Steps choose_steps(const Telemetry& d, const Layout& layout, const double* p, std::optional<double> substep,
                   double tolerance, double& error) {
  if (substep) {
    const Steps s = steps_of_at_most(d, *substep);
    error = integration_error(d, s, layout, p);
    return s;
  }
  double spacing = 0.0, omega_max = 0.0;
  for (std::size_t k = 0; k < d.t.size(); ++k) {
    if (k + 1 < d.t.size()) spacing = std::max(spacing, d.t[k + 1] - d.t[k]);
    omega_max = std::max(omega_max, d.omega[k].norm());
  }
  Steps s = steps_of_at_most(d, omega_max > 0.0 ? std::min(spacing, 0.1 / omega_max) : spacing);
  error = integration_error(d, s, layout, p);
  // RK4's error falls 16-fold per halving; once it falls less than 4-fold the estimate is rounding (or
  // the model is undefined at p) and more steps would not help.
  for (int halvings = 0; error > tolerance && halvings < 20; ++halvings) {
    Steps finer = s;
    for (int& n : finer.per_interval) n *= 2;
    finer.longest /= 2;
    const double e = integration_error(d, finer, layout, p);
    if (!(e < error / 4)) break;
    s = finer;
    error = e;
  }
  return s;
}

}  // namespace tumble::fit
