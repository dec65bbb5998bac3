// `tumble run`: simulate a scene file and write its trajectory (CSV or HDF5) and diagnostics.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <optional>

#include "commands.hpp"
#include "interrupt.hpp"
#include "plural.hpp"
#include "progress.hpp"
#include "run_plan_report.hpp"
#include "scene_summary.hpp"
#include "tumble/integrate/integrator.hpp"
#include "tumble/io/scene.hpp"
#include "tumble/io/trajectory_writer.hpp"

namespace tumble::cli {
namespace {

/// Exit status of `tumble run --strict` when a conserved quantity drifted past the threshold.
constexpr int kExitDrift = 3;

struct RunOptions {
  std::string scene;
  std::string output;
  std::string format;
  std::string diagnostics;
  std::optional<std::string> integrator;
  std::optional<std::string> formulation;
  std::optional<double> timestep;
  std::optional<double> duration;
  std::optional<double> output_interval;
  std::optional<double> rtol;
  std::optional<int> threads;
  std::vector<std::string> fields;
  std::optional<double> atol;
  std::optional<double> drift_threshold;
  bool quiet = false;
  bool progress = false;
  bool strict = false;
  bool force = false;
};

bool is_hdf5_name(const std::filesystem::path& p) {
  const std::string ext = p.extension().string();
  return ext == ".h5" || ext == ".hdf5" || ext == ".hdf";
}

/// The file's settings with the command line's on top.
RunSettings settings_for(const Scene& scene, const RunOptions& o) {
  RunSettings s = scene.settings;
  if (o.integrator) s.integrator = *o.integrator;
  if (o.formulation) s.formulation = parse_formulation(*o.formulation);
  if (o.timestep) s.timestep = *o.timestep;
  if (o.duration) s.duration = *o.duration;
  if (o.output_interval) s.output_interval = *o.output_interval;
  if (o.rtol) s.tolerances.relative = *o.rtol;
  if (o.atol) s.tolerances.absolute = *o.atol;
  if (o.threads) s.threads = *o.threads;
  validate(s);  // names the bad value and how to fix it
  return s;
}

/// Largest |drift| seen per quantity, for the closing line.
struct DriftExtremes {
  std::optional<double> energy, angular_momentum;
  void add(const DriftSample& d) {
    auto keep = [](std::optional<double>& m, const std::optional<double>& x) {
      if (x) m = std::max(m.value_or(0.0), std::abs(*x));
    };
    keep(energy, d.energy_drift);
    keep(angular_momentum, d.angular_momentum_drift);
  }
};

int run(const RunOptions& o) {
  body_fields(o.fields);  // an unknown field is named before the scene is read
  Scene scene = load_scene(o.scene);
  const RunSettings settings = settings_for(scene, o);
  const double threshold = o.drift_threshold.value_or(scene.drift_threshold);
  if (!(std::isfinite(threshold) && threshold >= 0)) {
    throw InvalidArgument(
        fmt::format("--drift-threshold {} is invalid: give a number >= 0 (0 turns the "
                    "warning off)",
                    threshold));
  }
  print_scene_warnings(scene);

  const bool hdf5 = o.format.empty() ? is_hdf5_name(o.output) : o.format == "hdf5";
  // Runs of a day or 100 GB are refused before anything is written; timing a few steps costs little
  // beside a run of 10⁹ body-steps, and is skipped for shorter ones.
  const RunPlan plan = plan_of(scene, settings, o.fields);
  const double rows = static_cast<double>(scene.model.bodies.size() + scene.model.particles.size());
  const std::optional<double> seconds =
      plan.steps && *plan.steps * rows > 1e9 ? estimate_seconds(scene, settings, plan) : std::nullopt;
  if (const auto warning = enforce(plan, seconds, hdf5, o.force))
    fmt::print(stderr, "tumble: warning: {}\n", *warning);
  std::filesystem::path out = o.output;
  if (out.empty()) {
    out = std::filesystem::path(o.scene).stem();
    out += hdf5 ? ".h5" : ".csv";
  }
  if (std::filesystem::is_directory(out)) {
    throw InvalidArgument(
        fmt::format("-o {} is a directory: give a file name, e.g. {}", out.string(),
                    (out / std::filesystem::path(o.scene).stem()).string() + (hdf5 ? ".h5" : ".csv")));
  }
  if (hdf5 && !o.diagnostics.empty()) {
    throw InvalidArgument(
        "--diagnostics names a CSV file; HDF5 output keeps the diagnostics in its "
        "'diagnostics' group: drop --diagnostics or use --format csv");
  }
  // The writer keeps the scene's text (HDF5 stores it); the run needs it no more, so it is not copied.
  const TrajectoryInfo info{std::move(scene.text), o.scene, TUMBLE_VERSION, settings,
                            o.fields.empty() ? scene.output_fields : o.fields};
  const std::unique_ptr<TrajectoryWriter> writer =
      hdf5 ? make_hdf5_writer(out, scene.model, info)
           : make_csv_writer(
                 out, o.diagnostics.empty() ? diagnostics_path(out) : std::filesystem::path(o.diagnostics),
                 scene.model, info);

  DriftMonitor monitor(scene.model, scene.initial, scene.conserved, threshold, settings);
  DriftExtremes extremes;
  Progress progress(o.quiet      ? ProgressMode::never
                    : o.progress ? ProgressMode::always
                                 : ProgressMode::automatic,
                    scene.initial.t, scene.initial.t + settings.duration);
  const InterruptGuard interrupt;
  bool interrupted = false;
  double t_reached = scene.initial.t;
  simulate(
      scene.model, scene.initial, settings,
      [&](const SystemState& state) {
        const DriftSample d = monitor.observe(state);
        writer->write(scene.model, state, d);
        extremes.add(d);
        t_reached = state.t;
        if (auto warning = monitor.take_warning()) progress.message("tumble: warning: " + *warning);
        progress.update(state.t);
        interrupted = interrupt.requested();
        return !interrupted;  // stop at this sample: everything written so far stays valid
      },
      nullptr, [&] { return interrupt.requested(); });  // asked every step: Ctrl-C needs no wait for a sample
  progress.finish();
  writer->commit(!interrupted);

  const auto files = writer->outputs();
  if (interrupted) {
    fmt::print(stderr, "tumble: interrupted at t = {:g} s of {:g} s; {} holds the {} samples up to then\n",
               t_reached, scene.initial.t + settings.duration, files.front().string(), writer->samples());
    return 130;  // 128 + SIGINT, as shells report an interrupted command
  }
  if (!o.quiet) {
    std::string what = count(scene.model.bodies.size(), "body", "bodies");
    if (!scene.model.particles.empty())
      what += " and " + count(scene.model.particles.size(), "particle", "particles");
    fmt::print("ran {} for {:g} s ({}, {} formulation): {} samples of {}\n", o.scene, settings.duration,
               settings.integrator, formulation_name(settings.formulation), writer->samples(), what);
    std::vector<std::string> drift;
    if (scene.conserved.energy && extremes.energy)
      drift.push_back(fmt::format("energy {:.2g}", *extremes.energy));
    if (scene.conserved.angular_momentum && extremes.angular_momentum) {
      drift.push_back(fmt::format("angular momentum {:.2g}", *extremes.angular_momentum));
    }
    if (!drift.empty())
      fmt::print("largest relative drift of conserved quantities: {}\n", fmt::join(drift, ", "));
    if (hdf5) {
      fmt::print("trajectory and diagnostics: {}\n", files.front().string());
    } else {
      fmt::print("trajectory:  {}\ndiagnostics: {}\n", files[0].string(), files[1].string());
    }
  }
  if (monitor.warning()) {
    // Said again at the end, where it is not lost in the progress output: the files are complete, but
    // their numbers carry more integration error than the scene's threshold allows.
    std::fflush(stdout);
    fmt::print(stderr,
               "tumble: warning: the results carry integration error past the drift threshold ({}){}\n",
               *monitor.warning(), o.strict ? "; failing because of --strict" : "");
    if (o.strict) return kExitDrift;
  }
  return 0;
}

}  // namespace

Runner add_run_command(CLI::App& app) {
  auto o = std::make_shared<RunOptions>();
  CLI::App* cmd = app.add_subcommand(
      "run",
      "Simulate a scene file and write the trajectory: one row per body per output sample with the pose "
      "of its reference frame (position, quaternion w,x,y,z), the velocity of its origin and the angular "
      "velocity, all in world axes; plus the energy, momenta and their drift from t = 0. Options given "
      "here override the scene's [simulation] values. Ctrl-C stops within a few steps (at most 16), writes "
      "the "
      "state reached as a last sample and keeps what was written.\n\nExamples:\n"
      "  tumble run examples/t_handle.toml -o out/t_handle.csv\n"
      "  tumble run examples/satellite.toml -o out/satellite.h5 --integrator dopri45 --rtol 1e-10\n"
      "  tumble run examples/t_handle.toml --timestep 1e-4 --duration 5 --quiet");
  cmd->add_option("scene", o->scene, "scene file (TOML; see docs/scene-format.md)")->required();
  cmd->add_option("-o,--output", o->output,
                  "trajectory file; .h5/.hdf5 means HDF5 unless --format says otherwise (default: the "
                  "scene's name with .csv or .h5, in the current directory); directories are created");
  cmd->add_option("--format", o->format, "csv (two files: trajectory and diagnostics) or hdf5 (one file)")
      ->check(CLI::IsMember({"csv", "hdf5"}));
  cmd->add_option("--diagnostics", o->diagnostics,
                  "CSV file for energy, momenta and drifts (default: OUTPUT with .diagnostics.csv)");
  cmd->add_option("--integrator", o->integrator,
                  fmt::format("time integrator, one of: {}", fmt::join(integrator_names(), ", ")));
  cmd->add_option("--formulation", o->formulation,
                  "frame of the integrated velocities: world, mixed or body");
  cmd->add_option("--timestep", o->timestep, "step h (s); for adaptive integrators the first trial step");
  cmd->add_option("--duration", o->duration, "simulated time (s)");
  cmd->add_option("--output-interval", o->output_interval, "time between samples (s); 0 = every step");
  cmd->add_option("--rtol", o->rtol, "relative tolerance of adaptive integrators");
  cmd->add_option("--atol", o->atol, "absolute tolerance of adaptive integrators");
  cmd->add_option("--threads", o->threads,
                  "threads for fixed-step integrators (default 1; 0 = one per core); worth it from a few "
                  "thousand bodies; results are bit-identical for any count");
  std::string fields_help =
      "per-body output fields, comma-separated, in the order wanted (default: the scene's [output] "
      "fields, else position,orientation,velocity,angular_velocity). Each field is a group of CSV columns "
      "and one HDF5 dataset:";
  for (const BodyField& f : body_fields()) {
    fields_help += fmt::format("\n  {} ({}; {}, {}): {}", f.name,
                               fmt::join(f.columns.begin(), f.columns.begin() + f.width, ","), f.unit,
                               f.frame, f.meaning);
  }
  cmd->add_option("--fields,--columns", o->fields, fields_help)->delimiter(',');
  cmd->add_option("--drift-threshold", o->drift_threshold,
                  "warn when a conserved energy or angular momentum drifts by more than this, relative "
                  "to t = 0 (0 = never)");
  cmd->add_flag("--strict", o->strict,
                "exit with status 3 (after writing every file) if a conserved quantity drifted past the "
                "drift threshold; without it such a run warns and exits 0");
  cmd->add_flag("--force", o->force,
                "run even if it would take more than a day or write more than 100 GB (`tumble check` "
                "prints the steps, samples, output size and time a run would take)");
  auto* quiet =
      cmd->add_flag("--quiet,-q", o->quiet, "no progress bar and no summary; errors and warnings only");
  cmd->add_flag("--progress", o->progress,
                "show the progress bar even when stderr is not a terminal or the run is short")
      ->excludes(quiet);
  return [o] { return run(*o); };
}

}  // namespace tumble::cli
