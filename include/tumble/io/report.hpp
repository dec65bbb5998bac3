#pragma once
// The report of a run: ONE self-contained HTML file (viewer/ builds the page; docs/report.md) holding
// the run's samples, its geometry, its events and facts as JSON, so that it opens from disk with no
// network and no server. A Report is filled either while a run goes (`tumble run --report`, through
// ReportRecorder) or from a trajectory file that `tumble run` wrote (`tumble report`, read_report()).
// Long runs are down-sampled to at most `max_samples` for display; the true count is kept.
#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "tumble/io/geometry.hpp"
#include "tumble/sim/drift_monitor.hpp"

namespace tumble {

struct ReportEvent {
  std::string name;
  double t = 0.0;
  long row = -1;  ///< the body or particle it watches; −1 none
};

struct Report {
  // Facts.
  std::string tumble_version, scene_path, scene_text, integrator, formulation;
  double timestep = 0.0, duration = 0.0;
  std::optional<double> wall_time_s;
  std::vector<std::string> warnings;
  // What is drawn.
  std::vector<std::string> names;  ///< rows: bodies, then particles
  SceneGeometry geometry;          ///< bodies: geometry.bodies.size(); the rows after them are particles
  std::vector<ReportEvent> events;
  long samples_total = 0;  ///< samples of the run; those below are every stride-th of them (and the last)
  std::vector<double> t;
  std::vector<double> position, quaternion, omega_world, omega_principal;  ///< (T, N, 3 or 4), world
  std::vector<double> kinetic_energy, potential_energy, total_energy, energy_drift;  ///< (T), NaN undefined
  std::vector<double> angular_momentum, angular_momentum_drift;                      ///< (T, 3), (T)
};

/// The most samples a report shows of a run of N rows so that its data stays near `budget_bytes`
/// (float32 per-body series, float64 times and system series, base64): at least 2.
long report_sample_limit(std::size_t rows, double budget_bytes = 16e6);

/// Appends one sample (a state of `model` and its drift sample) to a report.
void add_report_sample(Report& report, const Model& model, const SystemState& state, const DriftSample& d);

/// Takes every stride-th of a run's samples, and its last one, into a report (`tumble run --report`):
/// the stride is fixed from the planned sample count so that at most report_sample_limit() are kept.
class ReportRecorder {
 public:
  ReportRecorder(Report& report, double planned_samples);
  void sample(const Model& model, const SystemState& state, const DriftSample& d);
  /// After the run: the last sample if the stride skipped it.
  void finish(const Model& model);

 private:
  Report* report_;
  long stride_ = 1;
  long seen_ = 0;
  std::optional<std::pair<SystemState, DriftSample>> last_;  ///< the latest sample not yet kept
};

/// A report from a trajectory that `tumble run` wrote: HDF5 (its geometry, events and diagnostics
/// groups) or CSV (with OUT.diagnostics.csv, OUT.events.csv and OUT.run.json beside it). Needs the
/// fields position, orientation and angular_velocity (the defaults). With `scene`, the names, geometry
/// and scene text come from it instead (files written before reports existed). Throws FileError or
/// InvalidArgument saying what is missing.
Report read_report(const std::filesystem::path& trajectory, const Scene* scene = nullptr);

/// The report as HTML: the embedded viewer page with the report's JSON in place of its data placeholder.
std::string report_html(const Report& report);

/// Writes report_html() to `path` safely (a temporary renamed into place; never an input, never a
/// non-regular file but a device or FIFO). Throws InvalidArgument when this tumble was built without the
/// viewer (node and npm missing at build time), FileError if writing fails.
void write_report(const std::filesystem::path& path, const Report& report);

/// The viewer page with its placeholder (build/…/report_template.cpp, from viewer/dist/report.html);
/// empty when it was not built.
std::string_view report_template();

/// OUT.run.json for OUT.csv: the run's facts and geometry beside a CSV trajectory.
std::filesystem::path run_facts_path(const std::filesystem::path& trajectory);

}  // namespace tumble
