// `tumble fit` as a user runs it: the JSON on standard output or in --out, the exit statuses (0
// determined, 3 not determined, 1 bad input, 2 bad command line), and the input never overwritten.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "../fit/fit_support.hpp"
#include "../support/run.hpp"
#include "../support/scratch_dir.hpp"

namespace tumble {
namespace {

std::string slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

std::string write_csv(const std::string& name, const fit::Telemetry& d) {
  const std::string dir = test::scratch_dir("fit_cli").string();
  const std::string path = dir + "/" + name;
  std::ofstream(path) << test::telemetry_csv(d);
  return path;
}

TEST(FitCli, PrintsTheFitAsJsonAndWritesItBesideNeverOverTheInput) {
  const test::GyroTruth truth = test::tumbling_satellite();
  const std::string csv =
      write_csv("gyro.csv", test::torque_free_telemetry(truth, 120, 0.1, Vec3::Zero(), 1e-3, 3));
  const test::CommandResult r =
      test::run_shell_command(std::string(TUMBLE_CLI) + " fit " + csv + " --sigma 1e-3 2>/dev/null");
  ASSERT_EQ(r.status, 0) << r.output;
  const nlohmann::json j = nlohmann::json::parse(r.output);
  EXPECT_EQ(j["verdict"], "determined");
  EXPECT_EQ(j["scale"], "trace");
  EXPECT_EQ(j["samples"], 120);
  EXPECT_TRUE(j["bias"].is_null());
  // The trace-normalised moments, within 5 of their reported σ (a loose bound for one noisy draw; the
  // calibration itself is GyroFitCoverage's).
  const Vec3 I = truth.Lambda / truth.Lambda.sum();
  for (int i = 0; i < 3; ++i) {
    const double value = j["inertia"]["principal_moments"][i],
                 sigma = j["inertia"]["principal_moments_sigma"][i];
    EXPECT_LT(std::abs(value - I[i]), 5 * sigma) << i;
  }
  EXPECT_EQ(j["covariance"]["parameters"].size(), 8u);

  // --out: the file holds the same JSON, standard output a one-line summary.
  const std::string out = (test::scratch_dir("fit_cli") / "fit.json").string();
  std::filesystem::remove(out);
  const test::CommandResult written = test::run_tumble("fit " + csv + " --sigma 1e-3 --out " + out);
  ASSERT_EQ(written.status, 0) << written.output;
  EXPECT_NE(written.output.find("determined (120 samples"), std::string::npos) << written.output;
  EXPECT_EQ(nlohmann::json::parse(slurp(out)), j);

  // Never over the input.
  const std::string before = slurp(csv);
  const test::CommandResult same = test::run_tumble("fit " + csv + " --sigma 1e-3 --out " + csv);
  EXPECT_EQ(same.status, 1);
  EXPECT_NE(same.output.find("never overwrites an input"), std::string::npos) << same.output;
  EXPECT_EQ(slurp(csv), before);
}

TEST(FitCli, ExitStatusSaysWhenTheDataDoNotDetermineTheInertia) {
  test::GyroTruth truth = test::tumbling_satellite();
  truth.omega_b0 = Vec3(0.9, 0.0, 0.0);  // a spin about the minor axis
  const std::string csv =
      write_csv("spin.csv", test::torque_free_telemetry(truth, 60, 0.1, Vec3::Zero(), 1e-3, 5));
  const test::CommandResult r =
      test::run_shell_command(std::string(TUMBLE_CLI) + " fit " + csv + " --sigma 1e-3 --bias 2>/dev/null");
  EXPECT_EQ(r.status, 3) << r.output;
  const nlohmann::json j = nlohmann::json::parse(r.output);
  EXPECT_EQ(j["verdict"], "not determined");
  EXPECT_NE(j["reason"].get<std::string>().find("spins about one axis"), std::string::npos) << j["reason"];
}

TEST(FitCli, BadInputAndCommandLinesAreOneLineErrors) {
  const std::string dir = test::scratch_dir("fit_cli").string();
  const std::string bad = dir + "/bad.csv";
  std::ofstream(bad) << "t,wx,wy,wz\n0,1,2,3\n0.1,1,two,3\n";
  const test::CommandResult r = test::run_tumble("fit " + bad + " --sigma 1e-3");
  EXPECT_EQ(r.status, 1);
  EXPECT_EQ(r.output, "tumble: error: " + bad + ":3:7: 'two' in column 'wy' is not a number\n");
  const test::CommandResult no_sigma = test::run_tumble("fit " + bad);
  EXPECT_EQ(no_sigma.status, 2);
  EXPECT_NE(no_sigma.output.find("--sigma is required"), std::string::npos) << no_sigma.output;
  const std::string good =
      write_csv("good.csv", test::torque_free_telemetry(test::tumbling_satellite(), 20, 0.1));
  const test::CommandResult zero = test::run_tumble("fit " + good + " --sigma 0");
  EXPECT_EQ(zero.status, 1);
  EXPECT_NE(zero.output.find("sigma = 0: give the gyro's noise"), std::string::npos) << zero.output;
  const test::CommandResult help = test::run_tumble("fit --help");
  EXPECT_EQ(help.status, 0);
  EXPECT_NE(help.output.find("tau_x, tau_y, tau_z"), std::string::npos);
  EXPECT_NE(help.output.find("tumble fit gyro.csv --sigma"), std::string::npos);
}

}  // namespace
}  // namespace tumble
