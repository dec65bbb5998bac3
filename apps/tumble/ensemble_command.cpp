// `tumble ensemble SCENE -o results.csv|.h5`: a Monte Carlo study (io/ensemble.hpp, docs/ensembles.md) on
// every core, and across machines with `mpirun -np K tumble ensemble ...` (run i on rank i mod K; rows
// gathered to rank 0, which writes). An interrupted study resumes where it stopped: every finished row
// is kept in OUT.partial-RANK until the table is written.
#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <regex>
#include <set>

#include "commands.hpp"
#include "interrupt.hpp"
#include "mpi_ranks.hpp"
#include "output_format.hpp"
#include "progress.hpp"
#include "tumble/error.hpp"
#include "tumble/io/ensemble.hpp"
#include "tumble/io/trajectory_writer.hpp"
#include "tumble/sim/drift_monitor.hpp"
#include "tumble/study/runs.hpp"

namespace tumble::cli {
namespace {

struct EnsembleOptions {
  std::string scene;
  std::string output;
  std::string format;
  int threads = 0;
  bool quiet = false;
  bool progress = false;
  bool fresh = false;
};

/// Whether a study writing its table to `out` may write `file`: the table, its summary, a rank's partial
/// rows, or a chosen run's trajectory and the files beside it (which runs are chosen is known only
/// once the table is: `worst`).
bool written_by_study(const std::filesystem::path& file, const std::filesystem::path& out) {
  if (same_file(file, out)) return true;
  std::error_code ec;
  const auto dir_of = [](const std::filesystem::path& p) {
    return p.parent_path().empty() ? std::filesystem::path(".") : p.parent_path();
  };
  if (!std::filesystem::equivalent(dir_of(file), dir_of(out), ec)) return false;
  const std::string name = file.filename().string(), stem = out.stem().string();
  static const std::regex beside_table(
      R"(\.summary\.csv|\.run-[0-9]+(\.h5|\.csv|\.diagnostics\.csv|\.events\.csv|\.run\.json))");
  return (name.rfind(stem, 0) == 0 && std::regex_match(name.substr(stem.size()), beside_table)) ||
         name.rfind(out.filename().string() + ".partial-", 0) == 0;
}

/// Refuses an -o the study cannot write its files beside, or whose files would replace an input.
void check_output(const std::filesystem::path& out, bool named, const EnsembleStudy& study,
                  const std::string& example) {
  const std::string given = named ? fmt::format("-o {}", out.string())
                                  : fmt::format("the output {} (the scene's name)", out.string());
  if (out == "-") {
    throw InvalidArgument(
        fmt::format("-o -: a study writes a table and files beside it (OUT.summary.csv, OUT.run-I.csv, "
                    "OUT.partial-RANK), not a stream: give a file name, e.g. -o {}",
                    example));
  }
  std::error_code ec;
  const auto status = std::filesystem::status(out, ec);
  if (std::filesystem::is_directory(status)) {
    throw InvalidArgument(fmt::format("{} is a directory: give a file name, e.g. -o {}", given,
                                      (out / std::filesystem::path(example).filename()).string()));
  }
  if (std::filesystem::exists(status) && !std::filesystem::is_regular_file(status)) {
    throw InvalidArgument(fmt::format(
        "{} is not a regular file (a device, FIFO or socket): a study writes files beside its table, which "
        "must not go beside it; give a file name, e.g. -o {}",
        given, example));
  }
  for (const auto& input : study.base().input_files) {
    if (!written_by_study(input, out)) continue;
    throw InvalidArgument(fmt::format(
        "{} would overwrite the study's input {} (a study writes OUT, OUT.summary.csv, OUT.run-I.csv "
        "with their .diagnostics.csv, .events.csv and .run.json, and OUT.partial-RANK): give another "
        "output name, e.g. -o {}",
        given, input.string(), example));
  }
}

/// The runs whose full trajectories are written: every k-th, and the worst by a column.
std::vector<long> traced_runs(const EnsembleStudy& study, const std::vector<EnsembleRow>& rows) {
  std::set<long> chosen;
  const EnsembleOutputs& o = study.outputs();
  if (o.every > 0) {
    for (long i = 0; i < study.runs(); i += o.every) chosen.insert(i);
  }
  if (o.worst > 0) {
    const auto& c = study.columns();
    const size_t k = static_cast<size_t>(std::find(c.begin(), c.end(), o.worst_by) - c.begin());
    std::vector<std::pair<double, long>> ranked;
    for (const EnsembleRow& r : rows) {
      const double v = k == 0 ? static_cast<double>(r.run) : r.values[k - 1];
      if (std::isfinite(v)) ranked.emplace_back(v, r.run);
    }
    std::sort(ranked.begin(), ranked.end(), [](const auto& a, const auto& b) {
      return a.first != b.first ? a.first > b.first : a.second < b.second;
    });
    for (size_t j = 0; j < ranked.size() && j < static_cast<size_t>(o.worst); ++j)
      chosen.insert(ranked[j].second);
  }
  return {chosen.begin(), chosen.end()};
}

/// Run i again (bit for bit the run of the table) with its trajectory written to OUT.run-I.csv|h5.
std::filesystem::path write_trajectory(const EnsembleStudy& study, long i, const std::filesystem::path& out,
                                       bool hdf5) {
  std::filesystem::path file = out;
  file.replace_extension(fmt::format(".run-{}{}", i, hdf5 ? ".h5" : ".csv"));
  std::unique_ptr<TrajectoryWriter> writer;
  std::optional<DriftMonitor> monitor;
  RunTrajectory trajectory;
  trajectory.sample = [&](const Scene& s, const SystemState& state) {
    if (!writer) {  // the first sample comes before any crossing
      TrajectoryInfo info{s.text,
                          s.path.string(),
                          TUMBLE_VERSION,
                          s.settings,
                          s.output_fields,
                          !s.events.empty(),
                          std::make_shared<const SceneGeometry>(scene_geometry(s))};
      writer = hdf5 ? make_hdf5_writer(file, s.model, info)
                    : make_csv_writer(file, diagnostics_path(file), s.model, info);
      monitor.emplace(s.model, s.initial, s.conserved, 0.0, s.settings);
    }
    writer->write(s.model, state, monitor->observe(state));
  };
  trajectory.event = [&](const Scene& s, const EventHit& hit) {
    writer->event(hit.name, s.events[hit.index].row, hit.state.t);
  };
  run_alone(study, i, trajectory);
  writer->outcome(0.0, {});
  writer->commit(true);
  return file;
}

int ensemble(const EnsembleOptions& o, const Ranks& ranks) {
  const EnsembleStudy study = EnsembleStudy::load(o.scene);
  require_same_study(ranks, study);
  const bool hdf5 = hdf5_output(o.output, o.format);
  const std::string example = std::filesystem::path(o.scene).stem().string() +
                              (hdf5 ? "_ensemble.h5" : "_ensemble.csv");
  const std::filesystem::path out = o.output.empty() ? example : o.output;
  require_table_fits_in_memory(study);
  check_output(out, !o.output.empty(), study, example);
  require_known_extension(out, o.format, /*aem_allowed=*/false);
  const bool root = ranks.rank == 0;
  std::FILE* const human = stdout;

  // What is done already (an interrupted study), unless --fresh.
  if (o.fresh && root) PartialRows::remove_all(out);
  barrier(ranks);
  std::vector<EnsembleRow> done = o.fresh ? std::vector<EnsembleRow>{} : PartialRows::read_all(out, study);
  std::vector<bool> finished(static_cast<size_t>(study.runs()), false);
  for (const EnsembleRow& r : done) finished[static_cast<size_t>(r.run)] = true;
  std::vector<EnsembleRow> mine;  // this rank's rows: the done ones it owns, then those it computes
  std::vector<long> todo;
  for (long i = ranks.rank; i < study.runs(); i += ranks.size) {
    if (!finished[static_cast<size_t>(i)]) todo.push_back(i);
  }
  for (EnsembleRow& r : done) {
    if (r.run % ranks.size == ranks.rank) mine.push_back(std::move(r));
  }
  // A row computed twice (two partial files) is the same row: keep one.
  std::sort(mine.begin(), mine.end(), [](const auto& a, const auto& b) { return a.run < b.run; });
  mine.erase(std::unique(mine.begin(), mine.end(),
                         [](const auto& a, const auto& b) { return a.run == b.run; }),
             mine.end());
  if (root && !o.quiet) {
    const auto already = std::count(finished.begin(), finished.end(), true);
    fmt::print(human, "ensemble {}: {} runs, {} drawn values each, seed {}{}{}\n", o.scene, study.runs(),
               study.draws(0).size(), study.seed(),
               ranks.size > 1 ? fmt::format(", {} MPI ranks", ranks.size) : std::string(),
               already > 0 ? fmt::format("; resuming: {} runs already done", already) : std::string());
    std::fflush(human);
  }

  PartialRows partial(out, ranks.rank, study);
  Progress progress(o.quiet || !root ? ProgressMode::never
                    : o.progress     ? ProgressMode::always
                                     : ProgressMode::automatic,
                    0.0, static_cast<double>(todo.size()), "runs");
  const InterruptGuard interrupt;
  long count = 0;
  const auto started = std::chrono::steady_clock::now();
  std::vector<EnsembleRow> computed;
  try {
    computed = run_ensemble(
        study, todo, o.threads,
        [&](const EnsembleRow& row) {
          partial.add(row);
          progress.update(static_cast<double>(++count));
        },
        [&] { return interrupt.requested(); });
  } catch (...) {
    try {
      partial.flush();  // the rows done so far, for a rerun
    } catch (const FileError&) {
      // The run's own error says more; the rows kept before the flush still count.
    }
    throw;
  }
  partial.flush();
  progress.finish();
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  if (interrupt.requested()) {
    fmt::print(
        stderr,
        "tumble: interrupted after {} of {} runs; they are kept in {}.partial-*: run the same command again "
        "to finish the study\n",
        computed.size() + mine.size(), study.runs(), out.string());
    return 128 + interrupt.signal();
  }
  mine.insert(mine.end(), std::make_move_iterator(computed.begin()), std::make_move_iterator(computed.end()));
  const std::vector<EnsembleRow> rows = gather_rows(ranks, mine, study.columns().size() - 1);
  if (root) {
    if (static_cast<long>(rows.size()) != study.runs()) {
      throw Error(fmt::format("the ranks returned {} rows of {} runs", rows.size(), study.runs()));
    }
    write_ensemble_table(out, hdf5, study, rows, TUMBLE_VERSION);
    std::vector<std::filesystem::path> traced;
    for (long i : traced_runs(study, rows)) traced.push_back(write_trajectory(study, i, out, hdf5));
    if (!o.quiet) {
      fmt::print(human, "{} runs in {:.3g} s ({:.3g} runs/s{}{})\n", todo.size(), seconds,
                 seconds > 0 ? static_cast<double>(todo.size()) / seconds : 0.0,
                 ranks.size > 1 ? fmt::format(" on rank 0 of {}", ranks.size) : std::string(),
                 ", threads: " + (o.threads > 0 ? std::to_string(o.threads) : std::string("one per core")));
      std::filesystem::path summary = out;
      summary.replace_extension(".summary.csv");
      fmt::print(human, "table:   {}\n", out.string());
      if (!hdf5) fmt::print(human, "summary: {}\n", summary.string());
      for (const auto& t : traced) fmt::print(human, "trajectory of a chosen run: {}\n", t.string());
      // The summary of the outputs (not the draws) on the terminal.
      const auto stats = summarize(study.columns(), rows);
      const size_t first_output = study.draws(0).size();
      for (size_t c = first_output; c < stats.size(); ++c) {
        const ColumnSummary& s = stats[c];
        if (s.count == 0) continue;
        fmt::print(
            human,
            "  {:<28} mean {:<12.6g} std {:<10.3g} q05 {:<12.6g} q50 {:<12.6g} q95 {:<12.6g} ({} runs)\n",
            s.column, s.mean, s.std, s.q05, s.q50, s.q95, s.count);
      }
    }
  }
  barrier(ranks);
  if (root) PartialRows::remove_all(out);  // the table is written: nothing to resume
  return 0;
}

}  // namespace

Runner add_ensemble_command(CLI::App& app) {
  auto o = std::make_shared<EnsembleOptions>();
  CLI::App* cmd = app.add_subcommand(
      "ensemble",
      "Run a Monte Carlo study: the scene's [ensemble] table says how many runs, a seed, and a distribution "
      "for any number of the scene by its path (uniform, normal, lognormal, truncated_normal, rotation, "
      "direction, list, grid); [ensemble.outputs] what each run reports (event counts and times, extrema, "
      "final states, drifts, trajectories of chosen runs). Writes a table with a row per run and its "
      "summary (mean, std, quantiles, histogram per column). Run i's draws depend only on (seed, i): the "
      "table is the same bit for bit for any number of threads or MPI ranks. Runs on every core; across "
      "machines: mpirun -np K tumble ensemble ... (docs/ensembles.md). An interrupted study (Ctrl-C, a "
      "killed job) resumes when the same command is given again.\n\nExamples:\n"
      "  tumble ensemble examples/t_handle_ensemble.toml -o out/flips.csv\n"
      "  mpirun -np 4 tumble ensemble examples/t_handle_ensemble.toml -o out/flips.h5");
  cmd->add_option("scene", o->scene, "scene file with an [ensemble] table")->required();
  cmd->add_option("-o,--output", o->output,
                  "results: a table with a row per run; .h5/.hdf5 (any case) means HDF5 and .csv CSV unless "
                  "--format says otherwise; another extension needs --format (default: SCENE_ensemble.csv); "
                  "CSV adds OUTPUT.summary.csv. A regular file, never one of the study's inputs");
  cmd->add_option("--format", o->format, "csv or hdf5")->check(CLI::IsMember({"csv", "hdf5"}));
  cmd->add_option("--threads", o->threads, "threads per process (default 0: one per core)")
      ->check(CLI::NonNegativeNumber);
  cmd->add_flag("--fresh", o->fresh, "start again, ignoring the rows an interrupted run of this study kept");
  auto* quiet = cmd->add_flag("--quiet,-q", o->quiet, "no progress bar and no summary; errors only");
  cmd->add_flag("--progress", o->progress, "show the progress bar even when stderr is not a terminal")
      ->excludes(quiet);
  return [o] {
    const Ranks ranks = start_ranks();
    int status = 0;
    try {
      status = ensemble(*o, ranks);
    } catch (const std::exception& e) {
      if (ranks.size > 1) {
        std::fputs(fmt::format("tumble: error (rank {}): {}\n", ranks.rank, e.what()).c_str(), stderr);
        abort_ranks(ranks, 1);
      }
      finish_ranks(ranks);
      throw;
    }
    finish_ranks(ranks);
    return status;
  };
}

}  // namespace tumble::cli
