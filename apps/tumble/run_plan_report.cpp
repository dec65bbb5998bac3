// The plan of a run, estimated, printed and enforced for `tumble check` and `tumble run`.
#include "run_plan_report.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>

#include "plural.hpp"
#include "tumble/integrate/integrator.hpp"
#include "tumble/sim/output_fields.hpp"

namespace tumble::cli {
namespace {

std::string bytes(double b) {
  if (b < 1e3) return fmt::format("{:.0f} B", b);
  if (b < 1e6) return fmt::format("{:.3g} kB", b / 1e3);
  if (b < 1e9) return fmt::format("{:.3g} MB", b / 1e6);
  if (b < 1e12) return fmt::format("{:.3g} GB", b / 1e9);
  return fmt::format("{:.3g} TB", b / 1e12);
}

std::string duration(double s) {
  if (s < 120) return fmt::format("{:.2g} s", s);
  if (s < 7200) return fmt::format("{:.2g} min", s / 60);
  if (s < 2 * 86400) return fmt::format("{:.2g} h", s / 3600);
  if (s < 2 * 365.25 * 86400) return fmt::format("{:.3g} days", s / 86400);
  return fmt::format("{:.3g} years", s / (365.25 * 86400));
}

/// Counts as integers while they are (up to 10¹⁵), then in exponent form.
std::string amount(double n) { return n < 1e15 ? fmt::format("{:.0f}", n) : fmt::format("{:.3g}", n); }

}  // namespace

RunPlan plan_of(const Scene& scene, const RunSettings& settings, const std::vector<std::string>& fields) {
  std::vector<int> widths;
  for (const BodyField* f : body_fields(fields.empty() ? scene.output_fields : fields))
    widths.push_back(f->width);
  return plan_run(settings, scene.model.bodies.size(), scene.model.particles.size(), widths);
}

std::optional<double> estimate_seconds(const Scene& scene, const RunSettings& settings, const RunPlan& plan) {
  if (!plan.steps || *plan.steps == 0) return plan.steps ? std::optional(0.0) : std::nullopt;
  // A few steps of the run itself, on this machine: at most 16, and about 10⁶ body-steps for large
  // scenes (one step at least). The first step's set-up makes small runs look slower: an upper estimate.
  const auto rows =
      static_cast<double>(std::max<std::size_t>(1, scene.model.bodies.size() + scene.model.particles.size()));
  const double trial = std::clamp(std::floor(1e6 / rows), 1.0, std::min(16.0, *plan.steps));
  RunSettings s = settings;
  s.duration = trial * settings.timestep;
  s.output_interval = 0;
  const auto t0 = std::chrono::steady_clock::now();
  simulate(scene.model, scene.initial, s);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return seconds / trial * *plan.steps;
}

std::string describe(const RunPlan& plan, std::optional<double> seconds, std::size_t rows_per_sample) {
  std::string text = plan.steps ? fmt::format("{} steps, ", amount(*plan.steps)) : "adaptive steps, ";
  text += fmt::format("{} samples of {}; output up to {} (CSV) or about {} (HDF5)", amount(plan.samples),
                      count(rows_per_sample, "row", "rows"), bytes(plan.csv_bytes), bytes(plan.hdf5_bytes));
  if (seconds) text += fmt::format("; about {} on this machine (one thread)", duration(*seconds));
  return text;
}

std::optional<std::string> enforce(const RunPlan& plan, std::optional<double> seconds, bool hdf5,
                                   bool force) {
  const double out = hdf5 ? plan.hdf5_bytes : plan.csv_bytes;
  const std::string what =
      fmt::format("{}{} samples", plan.steps ? amount(*plan.steps) + " steps, " : "", amount(plan.samples));
  if (!force && seconds && *seconds > kMaxSeconds) {
    throw InvalidArgument(fmt::format(
        "this run would take about {} ({}): shorten the duration or enlarge the timestep, or give --force "
        "to run it anyway",
        duration(*seconds), what));
  }
  if (!force && out > kMaxBytes) {
    throw InvalidArgument(
        fmt::format("this run would write up to {} ({}): enlarge --output-interval, choose "
                    "fewer --fields, or give --force to write it anyway",
                    bytes(out), what));
  }
  if (out > kWarnBytes) {
    return fmt::format("the output will take up to {} ({}); --output-interval thins it", bytes(out), what);
  }
  return std::nullopt;
}

}  // namespace tumble::cli
