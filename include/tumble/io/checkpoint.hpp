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
// Format (version 2; docs/ARCHITECTURE.md): "TUMBLECK", a uint32 version, a uint32 byte-order mark
// 0x01020304, then the fields in a fixed order — integers as uint64, doubles as their 8 bytes
// (exact), strings and arrays as a uint64 length and their bytes; the run settings as every row of the
// settings table (sim/run_settings.hpp): its key, then 0 and a double or 1 and a name — and last the
// FNV-1a 64 hash of all bytes before it. Version 1 stored the settings field by field. Native byte order: a checkpoint moves between machines of the same byte order only.
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
  std::optional<double> largest_energy_drift, largest_angular_momentum_drift;
  std::string drift_warning;  ///< the drift monitor's warning so far; empty: none
  RunPoint point;             ///< point.samples: the samples the outputs hold at the checkpoint
};

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

/// Before continuing the outputs of a checkpointed run: if the run was killed before it committed them
/// (SIGKILL, power loss), they are still under its temporary names FINAL.tmp-PID; these are moved to the
/// final names (where an interrupted run would have put them), so the files to continue are always
/// under the final names. Throws InvalidArgument if that process is still running.
void recover_outputs(const Checkpoint& c);

/// Throws InvalidArgument naming the first input file that is missing or differs from its stamp.
void check_inputs_unchanged(const std::vector<FileStamp>& inputs);

}  // namespace tumble
