#pragma once
// A file written under a temporary name in its final directory and renamed into place when complete
// (rename is atomic within a file system), or deleted if abandoned.
#include <filesystem>

namespace tumble::io {

class StagedFile {
 public:
  /// Creates the final directory if needed; the temporary is FINAL.tmp-PID (two runs writing the same
  /// output do not share a temporary). Throws FileError if the directory cannot be created.
  explicit StagedFile(std::filesystem::path final_path);
  ~StagedFile();  // removes the temporary unless committed
  StagedFile(const StagedFile&) = delete;
  StagedFile& operator=(const StagedFile&) = delete;

  const std::filesystem::path& temporary() const { return temporary_; }
  const std::filesystem::path& final_path() const { return final_; }
  /// Renames the temporary to the final name (replacing an older file). Throws FileError.
  void commit();
  /// Deletes the temporary now.
  void abandon();

 private:
  std::filesystem::path final_;
  std::filesystem::path temporary_;
  bool done_ = false;
};

}  // namespace tumble::io
