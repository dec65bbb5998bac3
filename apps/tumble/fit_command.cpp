// `tumble fit`: a rigid body's inertia from its gyro telemetry (include/tumble/fit/gyro_fit.hpp,
// docs/fit.md). The JSON goes to standard output, or to --out (never over the input).
#include <fmt/format.h>

#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>

#include "commands.hpp"
#include "tumble/fit/gyro_fit.hpp"
#include "tumble/io/text_file.hpp"

namespace tumble::cli {
namespace {

struct FitCommandOptions {
  std::string telemetry;
  double sigma = 0.0;
  bool bias = false;
  std::optional<double> substep;
  std::string out = "-";
  int max_iterations = 100;
};

/// Exit status when the fit ran but the data do not determine the inertia (the JSON says why).
constexpr int kExitNotDetermined = 3;

int run_fit(const FitCommandOptions& o) {
  const fit::Telemetry telemetry = fit::read_telemetry(o.telemetry);
  const fit::FitResult result = fit::fit_gyro(
      telemetry,
      {.sigma = o.sigma, .bias = o.bias, .substep = o.substep, .max_iterations = o.max_iterations});
  const std::filesystem::path inputs[] = {o.telemetry};
  write_text_file(o.out, fit::fit_json(result), inputs, "the fit's result");
  if (o.out != "-") {
    // The gist for whoever ran it; the numbers are in the file.
    const Vec3& I = result.principal_moments.value;
    std::string line = fmt::format("{}: {} ({} samples, residual RMS {:.3g} sigma)", o.out,
                                   result.determined ? "determined" : "not determined", result.samples,
                                   result.rms_sigma);
    if (result.determined) {
      line += fmt::format("; principal moments {:.6g}, {:.6g}, {:.6g} {}", I[0], I[1], I[2],
                          result.absolute ? "kg m^2" : "(trace 1)");
    } else {
      line += ": " + result.reason;
    }
    std::fputs((line + "\n").c_str(), stdout);
  }
  return result.determined ? 0 : kExitNotDetermined;
}

}  // namespace

Runner add_fit_command(CLI::App& app) {
  auto o = std::make_shared<FitCommandOptions>();
  CLI::App* cmd = app.add_subcommand(
      "fit",
      "Identify a rigid body's inertia from its gyro telemetry: the inertia tensor J in the sensor's axes, "
      "the angular velocity at the first sample and (--bias) a constant gyro bias, fitted by least squares "
      "to Euler's equation J dw/dt = (J w + h) x w + tau - dh/dt. Without a known torque or wheel "
      "momentum J's scale does not show in the motion: J is reported divided by its trace (ratios); with "
      "one, in kg m^2. Prints JSON: the estimate, its standard deviations and covariance, the residuals, "
      "and a verdict: 'determined', or 'not determined' with the reason (e.g. a spin about one principal "
      "axis says nothing of the moments). docs/fit.md explains each part.\n\n"
      "TELEMETRY is a CSV file: a header line naming the columns (any order), then one sample per line:\n"
      "  t               time (s), strictly increasing\n"
      "  wx, wy, wz      the gyro's angular velocity (rad/s), sensor axes\n"
      "  tau_x, tau_y, tau_z   optional: a known applied torque (N m), sensor axes\n"
      "  h_x, h_y, h_z   optional: a known wheel angular momentum (N m s), sensor axes\n"
      "Blank lines and lines starting with # are skipped.\n\n"
      "Example:\n"
      "  t,wx,wy,wz\n"
      "  0.0,0.0123,-0.0456,0.0789\n"
      "  0.1,0.0125,-0.0451,0.0790\n"
      "  ...\n"
      "  tumble fit gyro.csv --sigma 1e-4 --bias --out fit.json\n\n"
      "Exit status: 0 determined, 3 not determined (the JSON says why), 1 an input that cannot be used, "
      "2 a command line that cannot be parsed.");
  cmd->add_option("telemetry", o->telemetry, "the telemetry CSV file (columns above)")->required();
  cmd->add_option("--sigma", o->sigma,
                  "the gyro's noise: the standard deviation of each component of a sample (rad/s), from its "
                  "data sheet (angle random walk / sqrt(sample interval)) or from a record at rest")
      ->required();
  cmd->add_flag("--bias", o->bias, "also estimate a constant gyro bias (3 more unknowns)");
  cmd->add_option("--substep", o->substep,
                  "the longest RK4 step between samples (s); default: chosen so that the integration error "
                  "stays below 0.1 sigma / sqrt(3 samples), by step halving");
  cmd->add_option("-o,--out", o->out,
                  "write the JSON here instead of standard output (never over the input)");
  cmd->add_option("--max-iterations", o->max_iterations,
                  "Levenberg-Marquardt iterations per start (default 100)");
  return [o]() -> int { return run_fit(*o); };
}

}  // namespace tumble::cli
