#pragma once
// The plan of a run (sim/run_plan.hpp) as people read it: `tumble check` prints it, `tumble run`
// refuses a run that would take more than a day or write more than 100 GB unless --force, and warns
// before an output of more than 1 GB.
#include <optional>
#include <string>

#include "tumble/io/scene.hpp"
#include "tumble/sim/run_plan.hpp"

namespace tumble::cli {

/// Beyond these `tumble run` refuses without --force; past kWarnBytes it warns.
inline constexpr double kMaxSeconds = 24 * 3600.0;
inline constexpr double kMaxBytes = 100e9;
inline constexpr double kWarnBytes = 1e9;

/// The plan of running `scene` with `settings` and `fields` (empty: the scene's or the defaults).
RunPlan plan_of(const Scene& scene, const RunSettings& settings, const std::vector<std::string>& fields);

/// The wall time the run would take on this machine, from timing its first few steps (at most 16,
/// and about 10⁶ body-steps); nullopt for adaptive integrators (their step count is not known).
std::optional<double> estimate_seconds(const Scene& scene, const RunSettings& settings, const RunPlan& plan);

/// "5000 steps, 501 samples of 1 body; output up to 150 kB (CSV) or about 40 kB (HDF5); about 0.02 s".
std::string describe(const RunPlan& plan, std::optional<double> seconds, std::size_t rows_per_sample);

/// Throws InvalidArgument (with the figures and how to shrink the run, or --force) when the run is
/// beyond kMaxSeconds or its output beyond kMaxBytes; returns a warning when the output passes
/// kWarnBytes.
std::optional<std::string> enforce(const RunPlan& plan, std::optional<double> seconds, bool hdf5, bool force);

}  // namespace tumble::cli
