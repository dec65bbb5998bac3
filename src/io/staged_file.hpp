#pragma once
// Where an output file's bytes go, decided once when the writer is made:
//  - staged (a new or a regular file, or a symlink to one): written under a temporary name next to the
//    file (FINAL.tmp-PID) and renamed onto it only when complete (rename is atomic within a file
//    system), or deleted if abandoned. A symlink is followed: its target is replaced, the link stays.
//  - direct (a character device such as /dev/null, or a FIFO): written straight through, since such a
//    file cannot be replaced and has no partial state to protect.
//  - standard output ("-"): written to stdout.
// Anything else (a directory, a block device, a socket) is refused. Making a staged file removes the
// stale temporaries that killed runs left beside the same final name (FINAL.tmp-PID and FINAL.old-PID
// of a PID that is no longer alive, regular files only).
#include <filesystem>
#include <span>

namespace tumble::io {

enum class OutputKind { staged, direct, standard_output };

class StagedFile {
 public:
  /// Resolves the final path and creates its directory if needed. `direct_allowed` false (HDF5, which
  /// seeks) refuses a device, a FIFO and "-". `what` names the file in messages (e.g. "the trajectory").
  /// Throws InvalidArgument for a file that cannot be an output, FileError if the directory cannot be
  /// created.
  explicit StagedFile(std::filesystem::path final_path, bool direct_allowed = true);
  ~StagedFile();  // removes the temporary unless committed
  StagedFile(const StagedFile&) = delete;
  StagedFile& operator=(const StagedFile&) = delete;

  OutputKind kind() const { return kind_; }
  /// The file to open for writing: the temporary (staged), or the device or FIFO itself (direct).
  const std::filesystem::path& temporary() const { return temporary_; }
  /// As given.
  const std::filesystem::path& final_path() const { return final_; }
  /// The file that will hold the output: the final path with symlinks followed.
  const std::filesystem::path& target() const { return target_; }
  /// Staged: renames the temporary onto the target (replacing an older file), with SIGINT, SIGTERM
  /// and SIGHUP blocked in this thread. Direct and standard output: nothing to do. Throws FileError.
  void commit();
  /// Deletes the temporary now (staged only).
  void abandon();

 private:
  std::filesystem::path final_;
  std::filesystem::path target_;
  std::filesystem::path temporary_;
  OutputKind kind_ = OutputKind::staged;
  bool done_ = false;
};

/// Moves two staged files into place together (a trajectory and its diagnostics): both or neither.
/// SIGINT, SIGTERM and SIGHUP are blocked in this thread meanwhile; if the second rename fails, the
/// first is undone (the older file under the first name is put back, or the new one removed) and
/// FileError says so. Files written directly are not affected (there is nothing to undo).
void commit_together(StagedFile& first, StagedFile& second);
/// The same for any number of files (a trajectory, its diagnostics and its events): all or none, an
/// earlier one undone if a later one cannot be moved.
void commit_together(std::span<StagedFile* const> files);

/// The file that holds `final_path`'s output: the path with symlinks followed.
std::filesystem::path output_target(const std::filesystem::path& final_path);

/// FINAL.tmp-PID: where process `pid` stages `final_path` (symlinks followed, as StagedFile does).
std::filesystem::path temporary_path(const std::filesystem::path& final_path, long pid);

/// Removes FINAL.tmp-PID and FINAL.old-PID beside `final_path` whose PID is not a live process
/// (kill(PID, 0) fails with ESRCH). Only regular files whose names match exactly; best effort.
void remove_stale_temporaries(const std::filesystem::path& final_path);

}  // namespace tumble::io
