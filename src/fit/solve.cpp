// fit_gyro(): the least-squares problem handed to Ceres. One cost function holds all 3n residuals
// (y_k − ŷ_k)/σ and fills its Jacobian from the model on dual numbers (residuals.cpp); Ceres minimises
// ½ Σ r² by Levenberg–Marquardt with a dense QR factorisation (a handful of unknowns against thousands
// of residuals). The steps and the starts are chosen here, the solution judged in assess.cpp.
#include <ceres/ceres.h>
#include <fmt/format.h>

#include <cmath>
#include <limits>

#include "fit_parts.hpp"
#include "tumble/error.hpp"

namespace tumble::fit {
namespace {

class GyroCost final : public ceres::CostFunction {
 public:
  GyroCost(const Telemetry& d, const Steps& steps, const Layout& layout, double sigma)
      : d_(d), steps_(steps), layout_(layout), sigma_(sigma) {
    set_num_residuals(static_cast<int>(3 * d.t.size()));
    mutable_parameter_block_sizes()->push_back(layout.size());
  }
  bool Evaluate(double const* const* parameters, double* residuals, double** jacobians) const override {
    return whitened_residuals(d_, steps_, layout_, sigma_, parameters[0], residuals,
                              jacobians != nullptr ? jacobians[0] : nullptr);
  }

 private:
  const Telemetry& d_;
  const Steps& steps_;
  Layout layout_;
  double sigma_;
};

struct Solved {
  Eigen::VectorXd p;
  double cost = std::numeric_limits<double>::infinity();  ///< ½ Σ r²
  int iterations = 0;
  std::string message;
  bool usable = false;
};

Solved solve_from(const Telemetry& d, const Steps& steps, const Layout& layout, double sigma,
                  Eigen::VectorXd p, int max_iterations) {
  ceres::Problem::Options problem_options;
  ceres::Problem problem(problem_options);  // owns the cost function
  problem.AddResidualBlock(new GyroCost(d, steps, layout, sigma), nullptr, p.data());
  ceres::Solver::Options o;
  o.minimizer_type = ceres::TRUST_REGION;
  o.trust_region_strategy_type = ceres::LEVENBERG_MARQUARDT;
  o.linear_solver_type = ceres::DENSE_QR;
  o.max_num_iterations = max_iterations;
  // Relative tolerances well below what the data can say (a noiseless fit is checked to 1e-9), and no
  // absolute gradient test (the gradient's size depends on σ).
  o.function_tolerance = 1e-14;
  o.parameter_tolerance = 1e-12;
  o.gradient_tolerance = 0.0;
  o.num_threads = 1;
  o.logging_type = ceres::SILENT;
  o.minimizer_progress_to_stdout = false;
  ceres::Solver::Summary summary;
  ceres::Solve(o, &problem, &summary);
  Solved s;
  s.usable = summary.IsSolutionUsable() && std::isfinite(summary.final_cost);
  s.cost = summary.final_cost;
  s.iterations = summary.num_successful_steps + summary.num_unsuccessful_steps;
  s.message = summary.message;
  s.p = p;
  return s;
}

}  // namespace

FitResult fit_gyro(const Telemetry& d, const FitOptions& options) {
  if (!(options.sigma > 0.0) || !std::isfinite(options.sigma)) {
    throw InvalidArgument(
        fmt::format("sigma = {}: give the gyro's noise, the standard deviation of each component (rad/s), a "
                    "finite number > 0",
                    options.sigma));
  }
  if (options.substep && (!(*options.substep > 0.0) || !std::isfinite(*options.substep))) {
    throw InvalidArgument(fmt::format(
        "substep = {}: the longest RK4 step must be a finite number of seconds > 0", *options.substep));
  }
  if (options.max_iterations < 1) {
    throw InvalidArgument(fmt::format("max_iterations = {}: give at least 1", options.max_iterations));
  }
  check_telemetry(d);

  FitResult result;
  Layout layout;
  layout.bias = options.bias;
  const auto nonzero = [](const std::vector<Vec3>& v) {
    for (const Vec3& x : v) {
      if (x != Vec3::Zero()) return true;
    }
    return false;
  };
  layout.absolute = nonzero(d.tau) || nonzero(d.h);
  if (!layout.absolute && (!d.tau.empty() || !d.h.empty())) {
    result.notes.push_back(
        "the torque and wheel momentum given are zero throughout: without them the motion is the same for J "
        "and any multiple of J, so J is reported normalised to trace 1");
  }
  result.samples = d.t.size();
  result.t0 = d.t.front();
  result.duration = d.t.back() - d.t.front();
  result.sigma = options.sigma;
  result.absolute = layout.absolute;
  result.bias_estimated = layout.bias;

  // An integration error δ in every residual can shift an estimate by up to δ√(3n)/σ standard
  // deviations: keep that below a tenth (steps.cpp).
  const double m = 3.0 * static_cast<double>(d.t.size());
  const double tolerance = 0.1 * options.sigma / std::sqrt(m);
  const double dof = m - layout.size();

  std::vector<Eigen::VectorXd> starts = starting_points(d, layout);
  Solved best;
  Steps steps;
  double error = 0.0;
  for (int refinement = 0; refinement < 4; ++refinement) {
    const std::vector<int> before = steps.per_interval;
    steps = choose_steps(d, layout, starts.front().data(), options.substep, tolerance, error);
    if (refinement > 0 && steps.per_interval == before) break;  // no finer steps help (rounding)
    for (const Eigen::VectorXd& p0 : starts) {
      const Solved s = solve_from(d, steps, layout, options.sigma, p0, options.max_iterations);
      ++result.starts;
      if (s.usable && (!best.usable || s.cost < best.cost)) best = s;
      // Residuals about the size of the noise: this start found the minimum the data have.
      if (best.usable && 2.0 * best.cost <= dof + 10.0 * std::sqrt(2.0 * dof)) break;
    }
    if (!best.usable) break;
    error = integration_error(d, steps, layout, best.p.data());
    if (options.substep || error <= tolerance) break;
    starts = {best.p};  // the steps were chosen away from the solution: choose them there, and solve again
  }
  if (!best.usable) {
    throw Error(
        fmt::format("{}: the fit failed from every starting point ({}): is sigma the gyro's noise, and is "
                    "the body rigid and free of unknown torques?",
                    d.source, best.message.empty() ? "no usable solution" : best.message));
  }
  result.iterations = best.iterations;
  result.termination = best.message;
  result.substep = steps.longest;
  result.integration_error = error;
  if (error > tolerance) {
    result.notes.push_back(fmt::format(
        "the RK4 integration error at the solution is about {:.3g} rad/s ({:.2g} sigma){}: it may shift the "
        "estimate; a smaller substep removes it",
        error, error / options.sigma,
        options.substep ? fmt::format(" with the substep given, {} s", *options.substep) : std::string()));
  }

  const Eigen::Index rows = static_cast<Eigen::Index>(m);
  Eigen::VectorXd r(rows);
  Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> A(rows, layout.size());
  if (!whitened_residuals(d, steps, layout, options.sigma, best.p.data(), r.data(), A.data())) {
    throw Error(fmt::format("{}: the model is undefined at the solution (internal)", d.source));
  }
  assess(d, layout, best.p, r, A, result);
  return result;
}

}  // namespace tumble::fit
