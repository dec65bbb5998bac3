#pragma once
// Ensembles: one scene run many times with uncertain values (docs/ensembles.md). A scene's [ensemble]
// table says how many runs, a base seed, and a distribution for any numeric value of the scene by its
// path ("bodies.handle.angular_velocity[1]"); [ensemble.outputs] what each run reports. Run i is the
// scene with the values drawn for i, read by the scene reader itself (every check and message is the
// file's), simulated (study/runs.hpp: alone, or with the runs that share its structure as one batch),
// and summarised into one row of a table.
//
// The draws of run i depend only on (seed, i, the variation's index): Philox4x64 (Random123, a
// counter-based generator: Salmon et al., SC'11) keyed by the seed and counting (i, variation, draw),
// so a table never depends on the order the runs are done in, on threads or on MPI ranks, and run i
// can be redone alone (a resumed study, the trajectory of a chosen run).
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "tumble/io/scene.hpp"

namespace tumble {

/// One uncertain value of a scene and how it is drawn.
struct Variation {
  enum class Kind { uniform, normal, lognormal, truncated_normal, rotation, direction, list, grid };
  std::string path;  ///< e.g. "bodies.handle.angular_velocity[1]", "bodies.handle.orientation"
  Kind kind = Kind::uniform;
  double low = 0, high = 1;        ///< uniform; truncated_normal's bounds
  double mean = 0, std = 1;        ///< normal, truncated_normal
  double mu = 0, sigma = 1;        ///< lognormal: exp(N(mu, sigma²))
  double magnitude = 1;            ///< direction: the length of the vector drawn
  std::vector<double> values;      ///< list (run i takes values[i mod n]), grid (a full-factorial axis)
  int width = 1;                   ///< values per draw: 1; 3 for direction, 4 for rotation (w, x, y, z)
  std::vector<std::string> names;  ///< column names of the drawn values (path, or path[k])
};

/// What each run reports.
struct EnsembleOutputs {
  std::vector<std::string> final_fields;  ///< output fields of every body at the final time
  std::vector<std::string> extrema;       ///< columns (e.g. "w2", "com_z"): min and max over the samples
  bool events = true;                     ///< per [[events]] event: count, first time, mean interval
  bool drift = true;                      ///< largest |relative drift| of energy and angular momentum
  long every = 0;                         ///< full trajectories of runs 0, every, 2·every, … (0: none)
  long worst = 0;                         ///< and of the `worst` runs with the largest `worst_by`
  std::string worst_by;                   ///< a column of the table
};

/// One run's row: its index, the drawn values, the outputs (NaN where undefined, e.g. no crossing).
struct EnsembleRow {
  long run = 0;
  std::vector<double> values;
};

class EnsembleStudy {
 public:
  /// Reads a scene file with an [ensemble] table. SceneError (file:line:column) for anything wrong.
  static EnsembleStudy load(const std::filesystem::path& scene);
  /// The same from text; `path` names it and anchors mesh paths.
  static EnsembleStudy parse(const std::string& text, const std::filesystem::path& path);
  EnsembleStudy(EnsembleStudy&&) noexcept;
  EnsembleStudy& operator=(EnsembleStudy&&) noexcept;
  ~EnsembleStudy();

  long runs() const;
  std::uint64_t seed() const;
  const std::vector<Variation>& variations() const;
  const EnsembleOutputs& outputs() const;
  /// The scene without variations (the file as written), for summaries and run plans.
  const Scene& base() const;
  /// A fingerprint of everything a row depends on (the scene text and the tumble version): a resumed
  /// study refuses rows computed for another.
  std::uint64_t fingerprint() const;

  /// The table's columns: "run", the drawn values, then the outputs.
  const std::vector<std::string>& columns() const;
  /// The drawn values of run i (one per column after "run", up to the outputs).
  std::vector<double> draws(long i) const;
  /// "run 17 (bodies.racket.mass = 0.31)": run i with its drawn values, as messages about it name it.
  std::string run_label(long i) const;
  /// The scene of run i: the file with run i's values, read by the scene reader. SceneError names the
  /// run and the values when they make the scene invalid (e.g. a negative mass).
  Scene scene_of_run(long i) const;
  /// The scenes of runs, whose drawn values are `draws` (draws(i) of each): as scene_of_run gives them,
  /// with the scene file's tree copied once and each run's values written into it in place (every run
  /// sets the same paths), not copied per run.
  std::vector<Scene> scenes_of_runs(std::span<const long> runs,
                                    std::span<const std::vector<double>> draws) const;
  /// The draw columns (indices after "run") of variations that change a run's structure: anything but
  /// the values of a body or of an event. Runs with equal such draws share settings, forces and bodies'
  /// count (study/runs.hpp steps them together).
  const std::vector<size_t>& structural_columns() const;

 private:
  struct Impl;
  explicit EnsembleStudy(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

/// Summary statistics of one column over the runs where it is defined.
struct ColumnSummary {
  std::string column;
  long count = 0;  ///< runs with a finite value
  double mean = 0, std = 0, min = 0, max = 0;
  double q05 = 0, q25 = 0, q50 = 0, q75 = 0, q95 = 0;  ///< quantiles (linear interpolation, type 7)
  std::vector<long> histogram;                         ///< 20 equal bins from min to max
};
/// The statistics of a ColumnSummary after its count, by name, in the order the tables write them: one
/// list for the CSV and HDF5 writers and the Python binding.
struct SummaryStatistic {
  const char* name;
  double ColumnSummary::*value;
};
inline constexpr SummaryStatistic kSummaryStatistics[] = {
    {"mean", &ColumnSummary::mean}, {"std", &ColumnSummary::std}, {"min", &ColumnSummary::min},
    {"q05", &ColumnSummary::q05},   {"q25", &ColumnSummary::q25}, {"q50", &ColumnSummary::q50},
    {"q75", &ColumnSummary::q75},   {"q95", &ColumnSummary::q95}, {"max", &ColumnSummary::max}};

std::vector<ColumnSummary> summarize(const std::vector<std::string>& columns,
                                     const std::vector<EnsembleRow>& rows);

/// 0, 1, …, runs − 1: every run of the study.
std::vector<long> every_run(const EnsembleStudy& study);

}  // namespace tumble

namespace tumble {

/// Writes an ensemble's table (a row per run, in run order) and its summary, safely (temporaries renamed
/// into place together): CSV `path` (the columns; %.17g; an undefined value empty) with
/// PATH.summary.csv (column,count,mean,std,min,q05,q25,q50,q75,q95,max,histogram), or HDF5 (`hdf5`):
/// group `runs` with a dataset (R) per column, `columns` (their order), group `summary` with one dataset
/// per statistic, and the
/// attributes scene (text), scene_file, seed, runs, tumble_version.
/// Bytes the study's table takes in memory, where its rows are gathered to be written: a row per run.
double ensemble_table_bytes(const EnsembleStudy& study);
/// Throws InvalidArgument, with the figures, when the table would not fit in this machine's memory:
/// better at the start (and in `tumble check`) than std::bad_alloc after hours of runs.
void require_table_fits_in_memory(const EnsembleStudy& study);

void write_ensemble_table(const std::filesystem::path& path, bool hdf5, const EnsembleStudy& study,
                          const std::vector<EnsembleRow>& rows, const std::string& tumble_version);

/// Rows of an interrupted study, kept as they are computed (PATH.partial-RANK, binary: a header with
/// the study's fingerprint and the row width, then (run, values) records), so that a rerun skips them.
class PartialRows {
 public:
  /// Opens PATH.partial-RANK for appending (a new file if none or a foreign one).
  PartialRows(const std::filesystem::path& path, int rank, const EnsembleStudy& study);
  ~PartialRows();
  PartialRows(const PartialRows&) = delete;
  PartialRows& operator=(const PartialRows&) = delete;
  /// Flushed to the file every half second, and by flush(). Both throw FileError if the file cannot
  /// take the rows (a full disk, a file size limit), saying that the rows before are kept.
  void add(const EnsembleRow& row);
  void flush();
  /// Every row that any rank's partial file beside PATH holds for this study (torn records ignored).
  static std::vector<EnsembleRow> read_all(const std::filesystem::path& path, const EnsembleStudy& study);
  /// Removes every PATH.partial-* (the study is complete).
  static void remove_all(const std::filesystem::path& path);

 private:
  std::FILE* file_ = nullptr;
  std::filesystem::path name_;
  size_t width_ = 0;
  std::chrono::steady_clock::time_point last_flush_;
  [[noreturn]] void fail(int error) const;
};

}  // namespace tumble
