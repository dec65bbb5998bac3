// `tumble run`: simulate a scene file and write its trajectory (CSV or HDF5) and diagnostics.
#include <fmt/format.h>

#include <unistd.h>

#include <chrono>
#include <cstdio>

#include <algorithm>
#include <cmath>
#include <optional>
#include <thread>

#include "commands.hpp"
#include "interrupt.hpp"
#include "output_format.hpp"
#include "plural.hpp"
#include "progress.hpp"
#include "run_plan_report.hpp"
#include "scene_summary.hpp"
#include "setting_options.hpp"
#include "tumble/integrate/integrator.hpp"
#include "tumble/io/checkpoint.hpp"
#include "tumble/io/geometry.hpp"
#include "tumble/io/report.hpp"
#include "tumble/io/scene.hpp"
#include "tumble/io/trajectory_writer.hpp"
#include "tumble/sim/run.hpp"

namespace tumble::cli {
namespace {

/// Exit status of `tumble run --strict` when a conserved quantity drifted past the threshold.
constexpr int kExitDrift = 3;
/// Rows per sample from which a CSV trajectory is written on a thread of its own: a row is ~0.6 µs of
/// formatting, the hand-over to the thread ~10 µs a sample.
constexpr size_t kRowsWrittenInBackground = 1000;

struct RunOptions {
  std::string scene;
  std::string output;
  std::string format;
  std::string diagnostics;
  SettingOptions settings;  // --timestep, --integrator, … (sim/run_settings.hpp)
  std::vector<std::string> fields;
  bool quiet = false;
  bool progress = false;
  bool strict = false;
  bool force = false;
  std::string checkpoint;
  double checkpoint_every = 60.0;
  std::string report;
  bool sensitivities = false;
  std::string sensitivity_parameters = "inertia";
  bool unwrap_angles = false;  // --unwrap-angles
  std::string epoch;           // --epoch: the UTC date of t = 0 in an attitude message (empty: J2000's)
  std::string aem_frame;       // --aem-frame: its REF_FRAME_A (empty: EME2000)
};

/// What `tumble resume` takes.
struct ResumeOptions {
  std::string checkpoint;
  std::optional<double> checkpoint_every;
  std::optional<int> threads;
  bool quiet = false;
  bool progress = false;
  bool writer_gone = false;  // the writer ran on another host and is gone (recover_outputs)
};

/// Everything a run needs after its options are checked: from the command line (`run`) or from a
/// checkpoint (`resume`).
struct Job {
  Scene scene;
  std::string scene_arg;  // the scene as named on the command line
  RunSettings settings;
  bool hdf5 = false;
  std::optional<AemHeader> aem;  // an attitude message (.aem) instead of CSV or HDF5
  std::filesystem::path out, diagnostics;
  std::filesystem::path report;  // --report: the HTML report to write after the run (empty: none)
  std::vector<std::string> fields;
  bool unwrap_angles = false;  // Euler angles continuous from sample to sample
  bool quiet = false, progress = false, strict = false;
  std::filesystem::path checkpoint;  // empty: none
  double checkpoint_every = 60.0;
  std::optional<Checkpoint> resumed;                   // the checkpoint this run continues
  std::optional<SensitivityParameters> sensitivities;  // --sensitivities: with respect to these
};

/// An output file and how the command line named it, for messages.
struct NamedOutput {
  std::string label;  // "-o x.csv"
  std::filesystem::path path;
  std::string fix;  // "give another output name, e.g. -o s.csv"
};

/// Refuses an output that is one of the run's inputs (the scene file, a mesh it reads), compared by
/// file identity (device and inode: hard links and any spelling of the path count).
void refuse_inputs_as_outputs(const std::vector<NamedOutput>& outputs, const Scene& scene) {
  for (const NamedOutput& out : outputs) {
    if (out.path == "-") continue;
    for (size_t i = 0; i < scene.input_files.size(); ++i) {
      const std::filesystem::path& in = scene.input_files[i];
      if (!same_file(out.path, in)) continue;
      throw InvalidArgument(fmt::format("{} is {} {}{}: writing it would destroy the run's input; {}",
                                        out.label, i == 0 ? "the scene file" : "the file", in.string(),
                                        i == 0 ? "" : " that the scene reads (a mesh or a body table)",
                                        out.fix));
    }
  }
}

/// The file's settings with the command line's on top.
RunSettings settings_for(const Scene& scene, const RunOptions& o) {
  RunSettings s = scene.settings;
  o.settings.apply(s);
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

/// Writes every sample and crossing to the trajectory files.
class TrajectoryObserver final : public RunObserver {
 public:
  TrajectoryObserver(TrajectoryWriter& writer, const Scene& scene) : writer_(writer), scene_(scene) {}
  void on_sample(const SystemState& state, const DriftSample& d) override {
    writer_.write(scene_.model, state, d);
  }
  void on_event(const EventHit& hit) override {
    writer_.event(hit.name, scene_.events[hit.index].row, hit.state.t);
  }
  void on_sensitivities(const Sensitivities& s) override { writer_.sensitivities(s); }

 private:
  TrajectoryWriter& writer_;
  const Scene& scene_;
};

/// Keeps the report's samples (every stride-th) and its crossings.
class ReportObserver final : public RunObserver {
 public:
  ReportObserver(Report& report, ReportRecorder& recorder, const Scene& scene)
      : report_(report), recorder_(recorder), scene_(scene) {}
  void on_sample(const SystemState& state, const DriftSample& d) override {
    recorder_.sample(scene_.model, state, d);
  }
  void on_event(const EventHit& hit) override {
    report_.events.push_back({hit.name, hit.state.t, static_cast<long>(scene_.events[hit.index].row)});
  }

 private:
  Report& report_;
  ReportRecorder& recorder_;
  const Scene& scene_;
};

/// The terminal's view of a run: the progress bar, the drift warning when it comes, and what the
/// closing summary says (the largest drifts, the time reached, each event's crossings).
class ConsoleObserver final : public RunObserver {
 public:
  /// `crossings`: per event, those before a resumed run's checkpoint (empty: none, or not recorded).
  ConsoleObserver(DriftMonitor& monitor, Progress& progress, DriftExtremes& extremes, size_t events, double t,
                  const std::vector<std::pair<long, double>>& crossings)
      : monitor_(monitor),
        progress_(progress),
        extremes_(extremes),
        crossings_(crossings.size() == events ? crossings
                                              : std::vector<std::pair<long, double>>(events, {0, 0.0})),
        t_(t) {}
  void on_sample(const SystemState& state, const DriftSample& d) override {
    extremes_.add(d);
    t_ = state.t;
    if (auto warning = monitor_.take_warning()) progress_.message("tumble: warning: " + *warning);
    progress_.update(state.t);
  }
  void on_event(const EventHit& hit) override {
    auto& [n, first] = crossings_[hit.index];
    if (n++ == 0) first = hit.state.t;
  }
  double t_reached() const { return t_; }
  /// Per event: the number of crossings and the time of the first.
  const std::vector<std::pair<long, double>>& crossings() const { return crossings_; }

 private:
  DriftMonitor& monitor_;
  Progress& progress_;
  DriftExtremes& extremes_;
  std::vector<std::pair<long, double>> crossings_;
  double t_;
};

/// Writes a checkpoint at a run point every `every` seconds of wall-clock time, with what the drift
/// report said there; save() writes one at once (an interrupted run's last).
class CheckpointObserver final : public RunObserver {
 public:
  using Clock = std::chrono::steady_clock;
  CheckpointObserver(std::filesystem::path file, const Checkpoint& base, double every,
                     TrajectoryWriter& writer, const DriftMonitor& monitor, const DriftExtremes& extremes,
                     const ConsoleObserver& console)
      : file_(std::move(file)),
        base_(base),
        every_(every),
        writer_(writer),
        monitor_(monitor),
        extremes_(extremes),
        console_(console),
        next_(Clock::now() + interval()) {}
  void on_run_point(const RunPoint& p) override {
    extremes_at_point_ = extremes_;
    warning_at_point_ = monitor_.warning();
    crossings_at_point_ = console_.crossings();  // the console saw this point's events already
    if (Clock::now() < next_) return;
    writer_.sync();  // the rows the checkpoint counts are in the file before it names them
    save(p);
    next_ = Clock::now() + interval();
  }
  void save(const RunPoint& p) const {
    Checkpoint c = base_;
    c.largest_energy_drift = extremes_at_point_.energy;
    c.largest_angular_momentum_drift = extremes_at_point_.angular_momentum;
    c.drift_warning = warning_at_point_.value_or("");
    c.crossings = crossings_at_point_;
    c.point = p;
    stamp_output(c);  // the rows it counts: synced to the file before the observer saves
    write_checkpoint(file_, c);
  }

 private:
  Clock::duration interval() const {
    return std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(every_));
  }
  std::filesystem::path file_;
  const Checkpoint& base_;
  double every_;
  TrajectoryWriter& writer_;
  const DriftMonitor& monitor_;
  const DriftExtremes& extremes_;
  const ConsoleObserver& console_;
  DriftExtremes extremes_at_point_;
  std::optional<std::string> warning_at_point_;
  std::vector<std::pair<long, double>> crossings_at_point_;
  Clock::time_point next_;
};

/// Runs a job: writes the outputs (continuing them for a resumed run) and, with a checkpoint file, a
/// checkpoint every checkpoint_every seconds of wall-clock time and when interrupted.
int execute(Job& j) {
  Scene& scene = j.scene;
  const RunSettings& settings = j.settings;
  const std::filesystem::path& out = j.out;
  const std::filesystem::path& diagnostics = j.diagnostics;
  const bool hdf5 = j.hdf5;
  // Human messages go to stderr when the trajectory takes standard output.
  std::FILE* const human = out == "-" || diagnostics == "-" ? stderr : stdout;
  // The writer keeps the scene's text (HDF5 stores it); the run needs it no more, so it is not copied.
  // What a checkpoint holds besides the run point (checkpoint.hpp).
  Checkpoint base;
  if (!j.checkpoint.empty()) {
    base.tumble_version = TUMBLE_VERSION;
    base.scene_path = j.scene_arg;
    base.scene_absolute = std::filesystem::absolute(scene.path).lexically_normal().string();
    base.scene_text = scene.text;
    for (size_t i = 1; i < scene.input_files.size(); ++i) {
      base.inputs.push_back(j.resumed ? j.resumed->inputs.at(i - 1) : stamp_file(scene.input_files[i]));
    }
    base.settings = settings;
    base.output = std::filesystem::absolute(out).lexically_normal().string();
    base.diagnostics = diagnostics.empty()
                           ? std::string()
                           : std::filesystem::absolute(diagnostics).lexically_normal().string();
    base.fields = j.fields;
    base.strict = j.strict;
    set_writer(base);
  }
  auto geometry = std::make_shared<const SceneGeometry>(scene_geometry(scene));
  // A report (--report) keeps every stride-th sample as the run goes, and the run's facts.
  std::optional<Report> report;
  std::optional<ReportRecorder> recorder;
  if (!j.report.empty()) {
    report.emplace();
    report->tumble_version = TUMBLE_VERSION;
    report->scene_path = j.scene_arg;
    report->scene_text = scene.text;
    report->integrator = settings.integrator;
    report->formulation = formulation_name(settings.formulation);
    report->timestep = settings.timestep;
    report->duration = settings.duration;
    report->names = row_names(scene.model);
    report->geometry = *geometry;
    recorder.emplace(*report,
                     plan_run(settings, scene.model.bodies.size(), scene.model.particles.size()).samples);
  }
  // The writer keeps the scene's text (HDF5 stores it); the run needs it no more, so it is not copied.
  TrajectoryInfo info{std::move(scene.text), j.scene_arg, TUMBLE_VERSION, settings, j.fields,
                      !scene.events.empty(), geometry,    j.unwrap_angles};
  const auto started = std::chrono::steady_clock::now();
  std::optional<CsvContinuation> continuation;
  if (j.resumed) continuation = CsvContinuation{j.resumed->point.samples, j.resumed->point.t_last_sample};
  std::unique_ptr<TrajectoryWriter> writer =
      j.aem  ? make_aem_writer(out, scene.model, info, *j.aem)
      : hdf5 ? make_hdf5_writer(out, scene.model, info)
             : make_csv_writer(out, diagnostics, scene.model, std::move(info), continuation);
  // A CSV sample of thousands of rows takes milliseconds to format: a second core does it while the
  // run steps on (HDF5 writes binary, and its library must stay on one thread).
  if (!hdf5 && !j.aem && std::thread::hardware_concurrency() > 1 &&
      scene.model.bodies.size() + scene.model.particles.size() >= kRowsWrittenInBackground) {
    writer = write_in_background(std::move(writer));
  }

  const double t0 = scene.initial.t;
  Run run(scene.model, std::move(scene.initial), settings, scene.conserved);  // 112 bytes a body: not copied
  DriftMonitor& monitor = run.monitor();
  DriftExtremes extremes;
  if (j.resumed) {
    extremes.energy = j.resumed->largest_energy_drift;
    extremes.angular_momentum = j.resumed->largest_angular_momentum_drift;
    if (!j.resumed->drift_warning.empty()) monitor.restore_warning(j.resumed->drift_warning);
  }
  Progress progress(j.quiet      ? ProgressMode::never
                    : j.progress ? ProgressMode::always
                                 : ProgressMode::automatic,
                    t0, t0 + settings.duration);
  const InterruptGuard interrupt;
  // What watches the run, in the order it is told: the files, the report, the terminal.
  TrajectoryObserver trajectory(*writer, scene);
  std::optional<ReportObserver> reporting;
  if (report) reporting.emplace(*report, *recorder, scene);
  ConsoleObserver console(monitor, progress, extremes, scene.events.size(),
                          j.resumed ? j.resumed->point.t_last_sample : t0,
                          j.resumed ? j.resumed->crossings : std::vector<std::pair<long, double>>{});
  run.watch(make_events(scene.model, scene.events)).attach(trajectory);
  if (reporting) run.attach(*reporting);
  run.attach(console).stop_when([&] { return interrupt.requested(); });  // asked every step and sample
  // Checkpoints: the run point (the last sample on the grid) with what the drift report said there.
  RunPoint point;
  std::optional<CheckpointObserver> checkpoints;
  if (!j.checkpoint.empty()) {
    checkpoints.emplace(j.checkpoint, base, j.checkpoint_every, *writer, monitor, extremes, console);
    run.keep_run_points(point).attach(*checkpoints);
  }
  if (j.resumed) run.resume_from(j.resumed->point);
  if (j.sensitivities) run.carry_sensitivities(*j.sensitivities);
  run.run();
  const bool interrupted = run.stopped();
  const double t_reached = console.t_reached();
  const auto& crossings = console.crossings();
  progress.finish();
  const double wall_time_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  std::vector<std::string> warnings = scene.warnings;
  if (monitor.warning()) warnings.push_back(*monitor.warning());
  writer->outcome(wall_time_s, warnings);
  {
    // A second Ctrl-C now waits until both files are in place (interrupt.hpp).
    const InterruptGuard::Deferral deferral;
    writer->commit(!interrupted);
  }
  bool checkpointed = false;
  if (!j.checkpoint.empty()) {
    if (interrupted && point.samples > 0) {
      checkpoints->save(
          point);  // the outputs are under their final names now, cut back to point.samples on resume
      checkpointed = true;
    } else if (!interrupted) {
      std::error_code ec;
      std::filesystem::remove(j.checkpoint, ec);  // the run is complete: nothing to resume
    }
  }

  if (report) {
    recorder->finish(scene.model);
    report->wall_time_s = wall_time_s;
    report->warnings = warnings;
    write_report(j.report, *report);
  }

  const auto files = writer->outputs();
  if (interrupted) {
    std::fputs(
        fmt::format("tumble: interrupted at t = {:g} s of {:g} s; {} holds the {} samples up to then\n",
                    t_reached, t0 + settings.duration,
                    files.front() == "-" ? "standard output" : files.front().string(), writer->samples())
            .c_str(),
        stderr);
    if (checkpointed) {
      std::fputs(fmt::format("tumble: checkpoint {} holds the run at t = {:g} s; continue it with: tumble "
                             "resume {}\n",
                             j.checkpoint.string(), point.t_last_sample, j.checkpoint.string())
                     .c_str(),
                 stderr);
    }
    return 128 + interrupt.signal();  // 130 for SIGINT, as shells report an interrupted command
  }
  if (!j.quiet) {
    std::string what = count(scene.model.bodies.size(), "body", "bodies");
    if (!scene.model.particles.empty())
      what += " and " + count(scene.model.particles.size(), "particle", "particles");
    fmt::print(human, "{} {} for {:g} s ({}, {} formulation): {} samples of {}\n",
               j.resumed ? "resumed and ran" : "ran", j.scene_arg, settings.duration, settings.integrator,
               formulation_name(settings.formulation), writer->samples(), what);
    std::vector<std::string> drift;
    if (scene.conserved.energy && extremes.energy)
      drift.push_back(fmt::format("energy {:.2g}", *extremes.energy));
    if (scene.conserved.angular_momentum && extremes.angular_momentum) {
      drift.push_back(fmt::format("angular momentum {:.2g}", *extremes.angular_momentum));
    }
    if (!drift.empty())
      fmt::print(human, "largest relative drift of conserved quantities: {}\n", fmt::join(drift, ", "));
    const std::vector<std::string> rows = row_names(scene.model);
    for (size_t e = 0; e < scene.events.size(); ++e) {
      const auto [n, first] = crossings[e];
      fmt::print(human, "event {} ({}): {}{}\n", scene.events[e].name, rows[scene.events[e].row],
                 count(static_cast<size_t>(n), "crossing", "crossings"),
                 n > 0 ? fmt::format(", the first at t = {:.9g} s", first) : std::string());
    }
    auto where = [](const std::filesystem::path& p) { return p == "-" ? "standard output" : p.string(); };
    if (j.aem) {
      fmt::print(human, "attitude message (CCSDS AEM, one segment per body): {}\n", where(files.front()));
    } else if (hdf5) {
      fmt::print(human, "trajectory and diagnostics: {}\n", files.front().string());
      if (j.sensitivities) {
        fmt::print(human, "sensitivities (stm, parameter_sensitivity with respect to {}): {}\n",
                   sensitivity_parameters_name(*j.sensitivities), files.front().string());
      }
    } else {
      fmt::print(human, "trajectory:  {}\n", where(files[0]));
      if (diagnostics.empty()) {
        fmt::print(human, "diagnostics: none (give --diagnostics FILE)\n");
      } else {
        fmt::print(human, "diagnostics: {}\n", where(diagnostics));
      }
      for (const auto& f : files) {
        if (f == events_path(out)) fmt::print(human, "events:      {}\n", f.string());
        if (f == run_facts_path(out)) fmt::print(human, "run facts:   {} (for tumble report)\n", f.string());
      }
    }
    if (report) fmt::print(human, "report:      {}\n", where(j.report));
  }
  if (monitor.warning()) {
    // Said again at the end, where it is not lost in the progress output: the files are complete, but
    // their numbers carry more integration error than the scene's threshold allows.
    std::fflush(human);
    fmt::print(stderr,
               "tumble: warning: the results carry integration error past the drift threshold ({}){}\n",
               *monitor.warning(), j.strict ? "; failing because of --strict" : "");
    if (j.strict) return kExitDrift;
  }
  return 0;
}

int run(const RunOptions& o) {
  Job j;
  body_fields(o.fields);  // an unknown field is named before the scene is read
  Scene scene = load_scene(o.scene);
  const RunSettings settings = settings_for(scene, o);
  print_scene_warnings(scene, o.strict);
  if (!o.quiet && scene.text.find("[ensemble") != std::string::npos) {
    fmt::print(stderr,
               "tumble: note: {} describes an ensemble; tumble run runs its base scene once (the "
               "study: tumble ensemble {})\n",
               o.scene, o.scene);
  }

  const bool hdf5 = hdf5_output(o.output, o.format);
  const bool aem = aem_output(o.output, o.format);
  const char* const extension = hdf5 ? ".h5" : aem ? ".aem" : ".csv";
  if (aem && !o.fields.empty()) {
    throw InvalidArgument(
        "an attitude message (.aem) holds each body's quaternion and body rates, whatever the fields: drop "
        "--fields, or write CSV or HDF5");
  }
  if (!aem && (!o.epoch.empty() || !o.aem_frame.empty())) {
    throw InvalidArgument(fmt::format(
        "{} dates and frames an attitude message: give an .aem output (-o {}.aem)",
        o.epoch.empty() ? "--aem-frame" : "--epoch", std::filesystem::path(o.scene).stem().string()));
  }
  // Runs of a day or 100 GB are refused before anything is written; timing a few steps costs little
  // beside a run of 10⁹ body-steps, and is skipped for shorter ones.
  const RunPlan plan = plan_of(scene, settings, o.fields);
  const double rows = static_cast<double>(scene.model.bodies.size() + scene.model.particles.size());
  const std::optional<double> seconds =
      plan.steps && *plan.steps * rows > 1e9 ? estimate_seconds(scene, settings, plan) : std::nullopt;
  if (const auto warning = enforce(plan, seconds, hdf5, o.force))
    fmt::print(stderr, "tumble: warning: {}\n", *warning);
  const std::string stem = std::filesystem::path(o.scene).stem().string();
  std::filesystem::path out = o.output;
  if (out.empty()) out = stem + extension;
  if (out != "-" && std::filesystem::is_directory(out)) {
    throw InvalidArgument(fmt::format("-o {} is a directory: give a file name, e.g. {}", out.string(),
                                      (out / std::filesystem::path(o.scene).stem()).string() + extension));
  }
  if (hdf5 && !o.diagnostics.empty()) {
    throw InvalidArgument(
        "--diagnostics names a CSV file; HDF5 output keeps the diagnostics in its "
        "'diagnostics' group: drop --diagnostics or use --format csv");
  }
  if (aem && !o.diagnostics.empty()) {
    throw InvalidArgument(
        "--diagnostics goes with a CSV trajectory; an attitude message holds the attitude alone: drop "
        "--diagnostics, or write CSV or HDF5");
  }
  // With -o - (standard output), a device such as /dev/null, or a FIFO, the trajectory is written
  // through, and diagnostics only where --diagnostics says (never a file beside a device).
  std::error_code no_status;
  const bool written_through = out == "-" || (std::filesystem::exists(out, no_status) &&
                                              !std::filesystem::is_regular_file(out, no_status));
  const std::filesystem::path diagnostics = hdf5 || aem              ? std::filesystem::path()
                                            : !o.diagnostics.empty() ? std::filesystem::path(o.diagnostics)
                                            : written_through        ? std::filesystem::path()
                                                                     : diagnostics_path(out);
  std::vector<NamedOutput> outputs{
      {o.output.empty() ? fmt::format("the output {} (the scene's name)", out.string())
                        : fmt::format("-o {}", out.string()),
       out, fmt::format("give another output name, e.g. -o {}{}", stem, extension)}};
  if (!diagnostics.empty()) {
    if (o.diagnostics.empty()) {
      outputs.push_back(
          {fmt::format("the diagnostics file {} (named after the output)", diagnostics.string()), diagnostics,
           "give another output name with -o, or a diagnostics file with --diagnostics"});
    } else {
      outputs.push_back({fmt::format("--diagnostics {}", diagnostics.string()), diagnostics,
                         fmt::format("give another file, e.g. --diagnostics {}.diagnostics.csv", stem)});
    }
  }
  if (!hdf5 && !aem && !written_through && !scene.events.empty()) {
    outputs.push_back({fmt::format("the events file {} (named after the output)", events_path(out).string()),
                       events_path(out), "give another output name with -o"});
  }
  if (!hdf5 && !aem && !written_through) {
    outputs.push_back({fmt::format("the run file {} (named after the output)", run_facts_path(out).string()),
                       run_facts_path(out), "give another output name with -o"});
  }
  if (!o.report.empty()) {
    for (const NamedOutput& other : outputs) {
      if (same_file(other.path, o.report)) {
        throw InvalidArgument(fmt::format("--report {} is {}: give another file, e.g. --report {}.html",
                                          o.report, other.label, stem));
      }
    }
    if (report_template().empty()) report_html(Report{});  // says how to get the viewer, before the run
    outputs.push_back({fmt::format("--report {}", o.report), o.report,
                       fmt::format("give another file, e.g. --report {}.html", stem)});
  }
  refuse_inputs_as_outputs(outputs, scene);
  require_known_extension(out, o.format, /*aem_allowed=*/true);
  if (o.sensitivities) {
    if (!hdf5) {
      throw InvalidArgument(fmt::format(
          "--sensitivities writes matrices (datasets stm and parameter_sensitivity) that CSV cannot hold: "
          "give an HDF5 output, e.g. -o {}.h5",
          stem));
    }
    if (!o.checkpoint.empty() || !scene.events.empty()) {
      throw InvalidArgument(fmt::format("--sensitivities runs its own loop, which {} yet: {}",
                                        scene.events.empty() ? "writes no checkpoints" : "watches no events",
                                        scene.events.empty() ? "drop --checkpoint"
                                                             : "remove the scene's [[events]] for this run"));
    }
    j.sensitivities = parse_sensitivity_parameters(o.sensitivity_parameters);
  }
  const bool unwrap_angles = o.unwrap_angles || scene.unwrap_angles;
  if (unwrap_angles && aem) {
    throw InvalidArgument(
        "--unwrap-angles makes Euler angles continuous, and an attitude message holds quaternions: drop it");
  }
  if (unwrap_angles && !o.checkpoint.empty()) {
    throw InvalidArgument(fmt::format(
        "{} and --checkpoint: a resumed run would not continue the unwrapped angles (not supported yet): "
        "drop one of them",
        o.unwrap_angles ? "--unwrap-angles" : "the scene's [output] unwrap_angles"));
  }
  if (!o.checkpoint.empty()) {
    if (hdf5 || aem) {
      throw InvalidArgument(fmt::format(
          "--checkpoint needs CSV output: continuing {} is not supported; use --format csv (or a .csv output "
          "name)",
          hdf5 ? "an HDF5 file" : "an attitude message"));
    }
    if (written_through) {
      throw InvalidArgument(fmt::format(
          "--checkpoint needs the trajectory in a file that a resumed run can continue, not {}; give a file "
          "name with -o",
          out == "-" ? "standard output" : out.string()));
    }
    if (!(std::isfinite(o.checkpoint_every) && o.checkpoint_every >= 0)) {
      throw InvalidArgument(
          fmt::format("--checkpoint-every {} is invalid: give the seconds of wall-clock time between "
                      "checkpoints, e.g. 60",
                      o.checkpoint_every));
    }
    refuse_inputs_as_outputs({{fmt::format("--checkpoint {}", o.checkpoint), o.checkpoint,
                               fmt::format("give another file, e.g. --checkpoint {}.checkpoint", stem)}},
                             scene);
    for (const NamedOutput& other : outputs) {
      if (same_file(other.path, o.checkpoint)) {
        throw InvalidArgument(
            fmt::format("--checkpoint {} is {}: give another file", o.checkpoint, other.label));
      }
    }
    check_checkpoint_path(o.checkpoint);
  }
  j.scene_arg = o.scene;
  j.settings = settings;
  j.hdf5 = hdf5;
  if (aem) {
    j.aem = AemHeader{};
    if (!o.epoch.empty()) j.aem->epoch = o.epoch;
    if (!o.aem_frame.empty()) j.aem->ref_frame = o.aem_frame;
  }
  j.out = out;
  j.diagnostics = diagnostics;
  j.fields = o.fields.empty() ? scene.output_fields : o.fields;
  j.unwrap_angles = unwrap_angles;
  j.quiet = o.quiet;
  j.progress = o.progress;
  j.strict = o.strict;
  j.checkpoint = o.checkpoint;
  j.checkpoint_every = o.checkpoint_every;
  j.report = o.report;
  j.scene = std::move(scene);
  return execute(j);
}

/// `tumble resume CHECKPOINT`: the run rebuilt from the checkpoint's scene text and settings, its outputs
/// cut back to the checkpoint's samples and continued.
int resume(const ResumeOptions& o) {
  Job j;
  Checkpoint c = read_checkpoint(o.checkpoint);
  check_inputs_unchanged(c.inputs);  // a changed mesh would build another model
  if (c.tumble_version != TUMBLE_VERSION) {
    std::fputs(
        fmt::format("tumble: warning: checkpoint {} was written by tumble {}, and this is tumble {}: the "
                    "run goes on, but the files are byte for byte those of an uninterrupted run only "
                    "when one version writes them all\n",
                    o.checkpoint, c.tumble_version, TUMBLE_VERSION)
            .c_str(),
        stderr);
  }
  j.scene = parse_scene(c.scene_text, c.scene_absolute);
  {
    std::vector<std::string> now;
    for (size_t i = 1; i < j.scene.input_files.size(); ++i)
      now.push_back(std::filesystem::absolute(j.scene.input_files[i]).lexically_normal().string());
    std::vector<std::string> then;
    for (const FileStamp& s : c.inputs) then.push_back(s.path);
    if (now != then) {
      throw InvalidArgument(fmt::format(
          "the scene of checkpoint {} now reads other files than when the run began ({}); the run cannot "
          "be resumed exactly",
          o.checkpoint, fmt::join(now, ", ")));
    }
  }
  j.scene_arg = c.scene_path;
  j.settings = c.settings;
  if (o.threads) j.settings.threads = *o.threads;  // results do not depend on it, bit for bit
  validate(j.settings);
  j.out = c.output;
  j.diagnostics = c.diagnostics;
  j.fields = c.fields;
  j.strict = c.strict;
  j.quiet = o.quiet;
  j.progress = o.progress;
  j.checkpoint = o.checkpoint;
  j.checkpoint_every = o.checkpoint_every.value_or(60.0);
  if (!(std::isfinite(j.checkpoint_every) && j.checkpoint_every >= 0)) {
    throw InvalidArgument(fmt::format(
        "--checkpoint-every {} is invalid: give the seconds of wall-clock time between checkpoints, e.g. 60",
        j.checkpoint_every));
  }
  std::vector<NamedOutput> outputs{{fmt::format("the trajectory {}", c.output), c.output, "start a new run"}};
  if (!c.diagnostics.empty())
    outputs.push_back({fmt::format("the diagnostics {}", c.diagnostics), c.diagnostics, "start a new run"});
  if (!j.scene.events.empty()) {
    outputs.push_back({fmt::format("the events file {}", events_path(c.output).string()),
                       events_path(c.output), "start a new run"});
  }
  outputs.push_back({fmt::format("the run file {}", run_facts_path(c.output).string()),
                     run_facts_path(c.output), "start a new run"});
  refuse_inputs_as_outputs(outputs, j.scene);
  print_scene_warnings(j.scene);
  // A killed run's files, still under their temporary names; the trajectory must be the checkpoint's.
  recover_outputs(c, o.checkpoint, o.writer_gone);
  j.resumed = std::move(c);
  return execute(j);
}

}  // namespace

Runner add_resume_command(CLI::App& app) {
  auto o = std::make_shared<ResumeOptions>();
  CLI::App* cmd = app.add_subcommand(
      "resume",
      "Continue a run from the checkpoint that `tumble run --checkpoint FILE` wrote (every "
      "--checkpoint-every seconds, and when the run was interrupted by Ctrl-C, SIGTERM or SIGHUP). The "
      "scene is rebuilt from the text stored in the checkpoint (a mesh or body table that changed since is "
      "refused), the same settings and outputs are used, the CSV files are cut back to the checkpoint's "
      "last sample and continued: the trajectory and diagnostics end up byte for byte those of a run that "
      "was never stopped, for every integrator. The checkpoint is updated as the run goes on and removed "
      "when it completes.\n\nExample:\n"
      "  tumble run examples/t_handle.toml -o out/t.csv --checkpoint out/t.ckpt --checkpoint-every 30\n"
      "  (Ctrl-C)\n"
      "  tumble resume out/t.ckpt");
  cmd->add_option("checkpoint", o->checkpoint, "checkpoint file written by tumble run --checkpoint")
      ->required();
  cmd->add_option("--checkpoint-every", o->checkpoint_every,
                  "seconds of wall-clock time between checkpoints (default 60; 0 = at every sample)");
  cmd->add_option("--threads", o->threads, "threads (results are bit-identical for any count)");
  cmd->add_flag("--writer-gone", o->writer_gone,
                "the run that wrote the checkpoint ran on another host and no longer runs: take over the "
                "files it left under temporary names (tumble cannot ask another host)");
  auto* quiet = cmd->add_flag("--quiet,-q", o->quiet, "no progress bar and no summary");
  cmd->add_flag("--progress", o->progress, "show the progress bar even when stderr is not a terminal")
      ->excludes(quiet);
  return [o] { return resume(*o); };
}

Runner add_run_command(CLI::App& app) {
  auto o = std::make_shared<RunOptions>();
  CLI::App* cmd = app.add_subcommand(
      "run",
      "Simulate a scene file and write the trajectory: one row per body per output sample with the pose "
      "of its reference frame (position, quaternion w,x,y,z), the velocity of its origin and the angular "
      "velocity, all in world axes; plus the energy, momenta and their drift from t = 0. Options given "
      "here override the scene's [simulation] values. Ctrl-C (or SIGTERM, SIGHUP) stops within a few steps "
      "(at most 16), writes the state reached as a last sample and keeps what was written (exit status "
      "128 + the signal).\n\nFiles are written under a temporary name and renamed when complete (the "
      "trajectory and its diagnostics together); after an error nothing appears under their names. An "
      "output that is the scene file or a mesh it reads (under any name) is refused. -o - writes CSV to "
      "standard output (messages to stderr); a symlink is followed, a device (-o /dev/null) or FIFO is "
      "written through, never replaced.\n\nExamples:\n"
      "  tumble run examples/t_handle.toml -o out/t_handle.csv\n"
      "  tumble run examples/satellite.toml -o out/satellite.h5 --integrator dopri45 --rtol 1e-10\n"
      "  tumble run examples/t_handle.toml --timestep 1e-4 --duration 5 --quiet\n"
      "  tumble run examples/t_handle.toml -o out/t.csv --checkpoint out/t.ckpt   (then: tumble resume "
      "out/t.ckpt)\n"
      "  tumble run examples/satellite.toml -o out/satellite.h5 --sensitivities   (state transition matrix, "
      "docs/sensitivities.md)");
  cmd->add_option("scene", o->scene, "scene file (TOML; see docs/scene-format.md)")->required();
  cmd->add_option(
      "-o,--output", o->output,
      "trajectory file; .h5/.hdf5 (any case) means HDF5, .aem a CCSDS attitude message and .csv CSV "
      "unless --format says otherwise; another extension needs --format (default: the "
      "scene's name with .csv, .h5 or .aem, in the current directory); directories are created. "
      "- is standard output (CSV); a symlink's target is replaced, the link kept; a device or "
      "FIFO is written through (CSV). Never one of the run's inputs");
  cmd->add_option("--format", o->format,
                  "csv (two files: trajectory and diagnostics), hdf5 (one file) or aem (a CCSDS Attitude "
                  "Ephemeris Message, version 2.0, KVN: each body's quaternion and body rates, one segment a "
                  "body, for Orekit and other flight-dynamics tools)")
      ->check(CLI::IsMember({"csv", "hdf5", "aem"}));
  cmd->add_flag(
      "--unwrap-angles", o->unwrap_angles,
      "Euler angles (euler_zyx, euler_zxz, euler_zyx_lvlh) continuous from sample to sample: each "
      "moved by the multiple of 2 pi nearest the previous sample's, so a spinning body's roll is not "
      "a sawtooth (true where an angle changes by less than pi between samples; the scene's [output] "
      "unwrap_angles = true says the same)");
  cmd->add_option("--epoch", o->epoch,
                  "attitude messages: the UTC date of t = 0, YYYY-MM-DDThh:mm:ss[.fff] (default "
                  "2000-01-01T12:00:00.000, J2000's; a sample at t is dated epoch + t, days of 86400 s)");
  cmd->add_option("--aem-frame", o->aem_frame,
                  "attitude messages: REF_FRAME_A, the inertial frame tumble's world axes stand for (default "
                  "EME2000; ICRF, GCRF, ... as CCSDS names them)");
  cmd->add_option("--diagnostics", o->diagnostics,
                  "CSV file for energy, momenta and drifts (default: OUTPUT with .diagnostics.csv; none "
                  "when OUTPUT is -, a device or a FIFO)");
  o->settings.add_to(*cmd);
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
  cmd->add_flag("--strict", o->strict,
                "warnings are errors: a scene with warnings (a density or a mesh size that looks like "
                "another unit, angles that look like degrees, ...) is refused before the run (status 1), "
                "and a run whose conserved quantity drifted past the drift threshold exits with status 3 "
                "after writing every file; without it both warn and the run exits 0");
  cmd->add_flag("--force", o->force,
                "run even if it would take more than a day or write more than 100 GB (`tumble check` "
                "prints the steps, samples, output size and time a run would take)");
  cmd->add_option("--report", o->report,
                  "also write an interactive 3D report of the run: ONE self-contained HTML file (opens from "
                  "disk, no network) with the bodies tumbling, ω and L, playback, energy, momentum and ω "
                  "plots and the events; long runs are down-sampled for display (docs/report.md)");
  cmd->add_option("--checkpoint", o->checkpoint,
                  "write a checkpoint to this file every --checkpoint-every seconds and when interrupted "
                  "(Ctrl-C, SIGTERM, SIGHUP); `tumble resume FILE` continues the run, and its CSV files end "
                  "up byte for byte those of an uninterrupted run. Removed when the run completes. CSV "
                  "output to a file only (not HDF5, -, a device or a FIFO)");
  cmd->add_option("--checkpoint-every", o->checkpoint_every,
                  "seconds of wall-clock time between checkpoints (default 60; 0 = at every sample)");
  cmd->add_flag(
      "--sensitivities", o->sensitivities,
      fmt::format("also write the run's sensitivities to the HDF5 output: stm = d x(t_k)/d x(0) and "
                  "parameter_sensitivity = d x(t_k)/d(I1, I2, I3) of each body (or d/d mass, or d/d the "
                  "force models' parameters: --sensitivity-parameters), by forward-mode differentiation of "
                  "the integrator's own steps ({}; docs/sensitivities.md). HDF5 only; no events or "
                  "checkpoints",
                  fmt::join(differentiating_integrators(), ", ")));
  cmd->add_option("--sensitivity-parameters", o->sensitivity_parameters,
                  "what parameter_sensitivity differentiates with respect to: inertia (each body's "
                  "principal moments, 3 columns a body; default), mass (1 a body), or forces (every force "
                  "model's parameters - g, drag and damping coefficients, a point force or torque, a "
                  "spring's stiffness, rest length and damping, mu - columns every body shares, named in "
                  "the dataset's attribute parameter_names)")
      ->check(CLI::IsMember({"inertia", "mass", "forces"}));
  auto* quiet =
      cmd->add_flag("--quiet,-q", o->quiet, "no progress bar and no summary; errors and warnings only");
  cmd->add_flag("--progress", o->progress,
                "show the progress bar even when stderr is not a terminal or the run is short")
      ->excludes(quiet);
  return [o] { return run(*o); };
}

}  // namespace tumble::cli
