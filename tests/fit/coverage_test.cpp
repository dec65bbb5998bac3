// The fit's reported uncertainty is calibrated: over 100 seeds of Gaussian gyro noise, the errors of
// the estimate divided by its reported standard deviations behave as standard normal variables.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "fit_support.hpp"

namespace tumble {
namespace {

TEST(GyroFitCoverage, ReportedSigmasAreCalibratedOverOneHundredSeeds) {
  // A well-excited tumble (the polhode about the major axis, several nutation periods over 200 samples
  // at 10 Hz), noise of 2e-3 rad/s per component (|ω| ~ 1.4 rad/s), a bias estimated too.
  const test::GyroTruth truth = test::tumbling_satellite();
  const Vec3 bias(0.004, -0.003, 0.002);
  const double sigma = 2e-3;
  const Mat3 J = truth.J() / truth.J().trace();
  const Vec3 I = truth.Lambda / truth.Lambda.sum();
  std::vector<double> z;
  int determined = 0;
  for (unsigned seed = 1; seed <= 100; ++seed) {
    const fit::Telemetry d = test::torque_free_telemetry(truth, 200, 0.1, bias, sigma, seed);
    const fit::FitResult f = fit::fit_gyro(d, test::fit_options(sigma, true));
    determined += f.determined ? 1 : 0;
    // z = (estimate − truth)/σ_reported for every reported quantity: the six entries of J/trace J, the
    // principal moments, ω₀ and the bias (15 per seed).
    for (int a = 0; a < 3; ++a) {
      for (int b = a; b < 3; ++b) z.push_back((f.J(a, b) - J(a, b)) / f.J_sigma(a, b));
    }
    for (int i = 0; i < 3; ++i) {
      z.push_back((f.principal_moments.value[i] - I[i]) / f.principal_moments.sigma[i]);
      z.push_back((f.omega0.value[i] - truth.omega0()[i]) / f.omega0.sigma[i]);
      z.push_back((f.bias.value[i] - bias[i]) / f.bias.sigma[i]);
    }
  }
  EXPECT_EQ(determined, 100);
  ASSERT_EQ(z.size(), 1500u);
  std::size_t inside = 0;
  double sum_z2 = 0.0;
  for (const double x : z) {
    ASSERT_TRUE(std::isfinite(x));
    inside += std::abs(x) <= 3.0 ? 1 : 0;
    sum_z2 += x * x;
  }
  const double fraction = static_cast<double>(inside) / static_cast<double>(z.size());
  const double mean_z2 = sum_z2 / static_cast<double>(z.size());
  // In --gtest_output=xml: what this draw gave.
  RecordProperty("fraction_within_3_sigma", std::to_string(fraction));
  RecordProperty("mean_z2", std::to_string(mean_z2));
  // Calibrated, |z| ≤ 3 holds with probability 99.73 %: of 1500 z's (15 per seed, correlated within a
  // seed, independent across the 100 seeds) about 4 fall outside; 97 % allows 45, which a calibrated
  // fit misses with a probability far below 1e-6 even if each seed's 15 were one variable (then 100
  // draws, 0.27 % each, would need 3 seeds out: P ≈ 2e-3 of one in a run — and they are not one).
  // Standard deviations reported half too small make |z| > 3 as likely as |z_true| > 1.5: 13 % out.
  EXPECT_GE(fraction, 0.97) << "mean z² = " << mean_z2;
  // E z² = 1 when calibrated; its standard error over 100 independent seeds is at most √(2/100) = 0.14
  // (all 15 of a seed perfectly correlated), ~0.04 with 1500 independent ones. An uncertainty inflated
  // by 25 % gives E z² = 0.64 and fails, one too small by 15 % gives 1.38 and fails.
  EXPECT_GE(mean_z2, 0.7);
  EXPECT_LE(mean_z2, 1.3);
}

}  // namespace
}  // namespace tumble
