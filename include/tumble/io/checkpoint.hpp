#pragma once
// Checkpoints of `tumble run --checkpoint FILE`, continued by `tumble resume FILE` so that the resumed
// run, and its CSV files, are byte for byte those of a run that was never stopped.
//
// A checkpoint holds everything the continuation needs: the scene's text and path (the Model is built
// again from that text, exactly as the run built it) with a stamp (size and FNV-1a 64 hash) of every
// other file the scene read (meshes, body tables: a changed one is refused), the run settings as run
// (after command-line overrides), the output options, the RunPoint (the formulation's variables, the
// time loop's counters, the integrator's own state, event values) as raw doubles, how many samples the
// outputs hold at that point, what the drift monitor reported so far and the PID of the process that
// wrote the outputs (its staged FINAL.tmp-PID holds them until they are committed).
//
// Format (version 4; docs/ARCHITECTURE.md): "TUMBLECK", a uint32 version, a uint32 byte-order mark
// 0x01020304, then the fields in a fixed order — integers as uint64, doubles as their 8 bytes
// (exact), strings and arrays as a uint64 length and their bytes; the run settings as every row of the
// settings table (sim/run_settings.hpp): its key, then 0 and a double or 1 and a name — and last the
// FNV-1a 64 hash of all bytes before it. Version 1 stored the settings field by field; version 3 added
// the writer's host and boot and the trajectory's stamp, version 4 each event's crossings so far
// (versions 2 and 3 are still read, without them). Native byte order: a checkpoint moves between machines of the same byte order only.
// Written atomically: CHECKPOINT.tmp-PID, fsync, rename.
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "tumble/sim/simulate.hpp"

namespace tumble {

/// FNV-1a, 64 bits.
std::uint64_t fnv1a64(std::string_view bytes, std::uint64_t hash = 0xcbf29ce484222325ULL);

/// A file a run read, as it was then.
struct FileStamp {
  std::string path;  ///< absolute
  std::uint64_t size = 0;
  std::uint64_t hash = 0;  ///< FNV-1a 64 of the contents
};
/// The stamp of a file now; throws FileError if it cannot be read.
FileStamp stamp_file(const std::filesystem::path& path);

struct Checkpoint {
  std::string tumble_version;
  std::string scene_path;      ///< as given on the command line (messages)
  std::string scene_absolute;  ///< absolute: anchors mesh paths when the scene is parsed again
  std::string scene_text;
  std::vector<FileStamp> inputs;  ///< every file the scene read but the scene file itself
  RunSettings settings;           ///< as run
  std::string output;             ///< trajectory, absolute
  std::string diagnostics;        ///< absolute; empty: none
  std::vector<std::string> fields;
  bool strict = false;
  long writer_pid = 0;  ///< the process whose staged temporaries hold the outputs until committed
  /// Where that process ran: its host name and that machine's boot (kernel boot_id), so that the PID
  /// is asked about only on the machine and boot it belongs to (empty: unknown, format version 2).
  std::string writer_host, writer_boot_id;
  /// The trajectory as it was at the checkpoint: its size and the FNV-1a 64 of its last
  /// kOutputTailBytes bytes (0 and 0: not stamped, format version 2). A trajectory that is shorter or
  /// differs there was written by another run since (a complete rerun to the same -o), and resuming
  /// would cut it back: refused (recover_outputs).
  std::uint64_t output_bytes = 0, output_tail_hash = 0;
  std::optional<double> largest_energy_drift, largest_angular_momentum_drift;
  std::string drift_warning;  ///< the drift monitor's warning so far; empty: none
  /// Per event of the scene, in its order: the crossings so far and the first one's time (unused at 0),
  /// so that a resumed run's summary counts them all. Empty: not recorded (format versions 2 and 3).
  std::vector<std::pair<long, double>> crossings;
  RunPoint point;  ///< point.samples: the samples the outputs hold at the checkpoint
};

/// How much of the trajectory's end its stamp covers: its last samples' rows.
inline constexpr std::uint64_t kOutputTailBytes = 4096;

/// This process as a checkpoint's writer: writer_pid, writer_host and writer_boot_id of `c`.
void set_writer(Checkpoint& c);
/// Stamps c.output (output_bytes, output_tail_hash) as it is now: under the writer's temporary name
/// while the run writes it, under its final name once committed. Call after the writer's sync().
/// Throws FileError if it cannot be read.
void stamp_output(Checkpoint& c);
/// Writes `c` to `path` atomically (a temporary beside it, fsync, rename). Throws FileError.
void write_checkpoint(const std::filesystem::path& path, const Checkpoint& c);
/// Before a run that will checkpoint to `path`: creates its directory and writes and removes the
/// temporary write_checkpoint will use, so that a path that cannot be written is refused now, not at
/// the first checkpoint hours into the run. Throws FileError (InvalidArgument for a path that is not a
/// regular file) naming the path.
void check_checkpoint_path(const std::filesystem::path& path);
/// Reads a checkpoint; throws InvalidArgument with one line naming the file and what is wrong (not a
/// checkpoint, another format version, truncated or corrupt), FileError if it cannot be read.
Checkpoint read_checkpoint(const std::filesystem::path& path);

/// Before continuing the outputs of a checkpointed run (`checkpoint`, the file `c` was read from): if the
/// run was killed before it committed them (SIGKILL, power loss), they are still under its temporary
/// names FINAL.tmp-PID; these are moved to the final names (where an interrupted run would have put
/// them) and the trajectory is cut back to the stamped bytes, so the files to continue are always
/// under the final names. Throws InvalidArgument, moving nothing,
///  - if that process is still running: asked of the PID on the writer's machine and boot only (a PID
///    of another boot, or of a process that is not tumble, is not the writer); a writer on another
///    host cannot be asked, and is refused unless `writer_gone` (the user says it no longer runs);
///  - if the trajectory is not the one the checkpoint stamped (a stale checkpoint: another run wrote
///    the file since), or a killed run's files would replace final ones written after the checkpoint.
void recover_outputs(const Checkpoint& c, const std::filesystem::path& checkpoint, bool writer_gone = false);

/// Throws InvalidArgument naming the first input file that is missing or differs from its stamp.
void check_inputs_unchanged(const std::vector<FileStamp>& inputs);

}  // namespace tumble
