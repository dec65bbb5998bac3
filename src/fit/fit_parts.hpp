#pragma once
// The parts of fit_gyro(), one file each: residuals and their Jacobian (residuals.cpp), the RK4 steps
// (steps.cpp), the starting points (initial_guess.cpp), what the solution means (assess.cpp).
#include <Eigen/Core>
#include <optional>
#include <vector>

#include "gyro_model.hpp"

namespace tumble::fit {

/// The whitened residuals r_k = (y_k − ŷ_k)/σ (3 per sample) at the unknowns p, and when `jacobian` is
/// not null ∂r/∂p, row-major (3n × layout.size()), from the model on dual numbers. False where the
/// model is undefined (J not positive definite, a motion that is not finite).
bool whitened_residuals(const Telemetry& d, const Steps& steps, const Layout& layout, double sigma,
                        const double* p, double* residuals, double* jacobian);

/// An estimate of RK4's largest error in ŷ over the samples with these steps, by step halving
/// (Richardson: RK4's error at h ≈ (ŷ_h − ŷ_{h/2}) · 16/15); +∞ where the model is undefined.
double integration_error(const Telemetry& d, const Steps& steps, const Layout& layout, const double* p);

/// The steps for the fit: at most `substep` when given; otherwise the longest that keeps the estimated
/// integration error at p below `tolerance` (halving from min(spacing, 0.1/max|ω|)). `error` receives
/// the estimate for the steps returned.
Steps choose_steps(const Telemetry& d, const Layout& layout, const double* p, std::optional<double> substep,
                   double tolerance, double& error);

/// Starting points for the solver, best first: J from the linear least-squares fit of
/// J ω̇ − (J ω) × ω = h × ω + τ − ḣ to finite-difference rates of the data, then an isotropic J.
std::vector<Eigen::VectorXd> starting_points(const Telemetry& d, const Layout& layout);

/// Fills the result's estimate, covariance, residual statistics and verdict from the solution p, its
/// whitened residuals r and Jacobian A (3n × P).
void assess(const Telemetry& d, const Layout& layout, const Eigen::VectorXd& p, const Eigen::VectorXd& r,
            const Eigen::MatrixXd& A, FitResult& result);

}  // namespace tumble::fit
