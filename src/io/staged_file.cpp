#include "staged_file.hpp"

#include <fmt/format.h>
#include <signal.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <string>
#include <thread>
#include <vector>

#include "tumble/error.hpp"

namespace tumble::io {
namespace {

/// SIGINT, SIGTERM and SIGHUP held back in this thread for the lifetime of the object: a Ctrl-C that
/// arrives between two renames is acted on after both.
class SignalBlock {
 public:
  SignalBlock() {
    sigset_t set;
    sigemptyset(&set);
    sigaddset(&set, SIGINT);
    sigaddset(&set, SIGTERM);
    sigaddset(&set, SIGHUP);
    blocked_ = pthread_sigmask(SIG_BLOCK, &set, &previous_) == 0;
  }
  ~SignalBlock() {
    if (blocked_) pthread_sigmask(SIG_SETMASK, &previous_, nullptr);
  }
  SignalBlock(const SignalBlock&) = delete;
  SignalBlock& operator=(const SignalBlock&) = delete;

 private:
  sigset_t previous_;
  bool blocked_ = false;
};

/// The final path with every symlink followed (a dangling link gives the file it would create).
std::filesystem::path follow_symlinks(const std::filesystem::path& path) {
  std::filesystem::path p = path;
  for (int hops = 0; hops < 40; ++hops) {
    std::error_code ec;
    if (!std::filesystem::is_symlink(std::filesystem::symlink_status(p, ec))) return p;
    const std::filesystem::path to = std::filesystem::read_symlink(p, ec);
    if (ec) throw FileError(fmt::format("cannot read the symbolic link {}: {}", p.string(), ec.message()));
    p = to.is_absolute() ? to : p.parent_path() / to;
  }
  throw InvalidArgument(
      fmt::format("{}: too many levels of symbolic links (a loop?): give a file name that is not a link loop",
                  path.string()));
}

std::string describe_type(std::filesystem::file_type type) {
  switch (type) {
    case std::filesystem::file_type::character:
      return "a character device";
    case std::filesystem::file_type::fifo:
      return "a FIFO";
    case std::filesystem::file_type::block:
      return "a block device";
    case std::filesystem::file_type::socket:
      return "a socket";
    default:
      return "not a regular file";
  }
}

/// PID-suffixed names of temporaries ("FINAL.tmp-PID") and backups ("FINAL.old-PID").
std::filesystem::path with_pid_suffix(const std::filesystem::path& p, const char* suffix) {
  std::filesystem::path out = p;
  out += fmt::format(".{}-{}", suffix, static_cast<long>(::getpid()));
  return out;
}

/// Test hook: the pause between the two renames of commit_together (milliseconds), so that a test
/// can deliver a signal right there. Unset in normal use.
void pause_between_renames() {
  const char* ms = std::getenv("TUMBLE_TEST_PAUSE_BETWEEN_RENAMES_MS");
  if (ms != nullptr) std::this_thread::sleep_for(std::chrono::milliseconds(std::atol(ms)));
}

}  // namespace

StagedFile::StagedFile(std::filesystem::path final_path, bool direct_allowed)
    : final_(std::move(final_path)) {
  if (final_ == "-") {
    if (!direct_allowed) {
      throw InvalidArgument(
          "HDF5 cannot be written to standard output (the library seeks in its file): give a file name, "
          "or write CSV");
    }
    kind_ = OutputKind::standard_output;
    target_ = temporary_ = final_;
    return;
  }
  target_ = follow_symlinks(final_);
  std::error_code ec;
  const std::filesystem::file_status st = std::filesystem::status(target_, ec);
  const auto type = st.type();
  if (type == std::filesystem::file_type::directory) {
    throw InvalidArgument(fmt::format("{} is a directory: give a file name", final_.string()));
  }
  if (type == std::filesystem::file_type::character || type == std::filesystem::file_type::fifo) {
    if (!direct_allowed) {
      throw InvalidArgument(fmt::format(
          "{} is {}: HDF5 needs a regular file (the library seeks in it): give a file name, or write CSV",
          final_.string(), describe_type(type)));
    }
    kind_ = OutputKind::direct;  // written through: a device or a FIFO is never replaced
    temporary_ = target_;
    return;
  }
  if (type != std::filesystem::file_type::regular && type != std::filesystem::file_type::not_found) {
    throw InvalidArgument(
        fmt::format("{} is {}: tumble writes to regular files, character devices (e.g. /dev/null), FIFOs or "
                    "standard output (-): give a file name",
                    final_.string(), describe_type(type)));
  }
  temporary_ = with_pid_suffix(target_, "tmp");
  const std::filesystem::path dir = target_.parent_path();
  std::error_code dir_ec;
  if (!dir.empty()) std::filesystem::create_directories(dir, dir_ec);
  if (dir_ec) {
    throw FileError(fmt::format("cannot create the output directory {}: {}", dir.string(), dir_ec.message()));
  }
  remove_stale_temporaries(target_);
}

StagedFile::~StagedFile() { abandon(); }

void StagedFile::commit() {
  if (kind_ != OutputKind::staged || done_) return;
  const SignalBlock block;
  std::error_code ec;
  std::filesystem::rename(temporary_, target_, ec);
  if (ec) {
    abandon();
    throw FileError(fmt::format("cannot move {} to {}: {}; nothing was kept under that name",
                                temporary_.string(), target_.string(), ec.message()));
  }
  done_ = true;
}

void StagedFile::abandon() {
  if (done_) return;
  done_ = true;
  if (kind_ != OutputKind::staged) return;
  std::error_code ec;  // best effort: there is nothing more to do if it fails
  std::filesystem::remove(temporary_, ec);
}

void commit_together(std::span<StagedFile* const> files) {
  const SignalBlock block;
  // Each older file, kept under a second name (a hard link: the final name is still replaced
  // atomically) until every later file is in place, to be put back if one cannot be.
  struct Done {
    StagedFile* file;
    std::filesystem::path backup;
    bool had_older;
  };
  std::vector<Done> done;
  std::error_code ec;
  auto undo = [&] {
    for (auto d = done.rbegin(); d != done.rend(); ++d) {
      if (d->file->kind() != OutputKind::staged) continue;  // written through: nothing to undo
      if (d->had_older) {
        std::filesystem::rename(d->backup, d->file->target(), ec);
      } else {
        std::filesystem::remove(d->file->target(), ec);
      }
    }
  };
  for (StagedFile* f : files) {
    const bool staged = f->kind() == OutputKind::staged;
    const std::filesystem::path backup = with_pid_suffix(f->target(), "old");
    const bool had_older =
        staged && std::filesystem::is_regular_file(std::filesystem::symlink_status(f->target(), ec)) &&
        ::link(f->target().c_str(), backup.c_str()) == 0;
    if (!done.empty()) pause_between_renames();
    try {
      f->commit();
    } catch (const FileError& e) {
      if (had_older) std::filesystem::remove(backup, ec);
      if (done.empty()) throw;
      undo();
      std::vector<std::string> names;
      for (const Done& d : done) names.push_back(d.file->final_path().string());
      throw FileError(fmt::format("{}; {} {} not replaced either", e.what(), fmt::join(names, " and "),
                                  names.size() == 1 ? "was" : "were"));
    }
    done.push_back({f, backup, had_older});
  }
  for (const Done& d : done) {
    if (d.had_older) std::filesystem::remove(d.backup, ec);
  }
}

void commit_together(StagedFile& first, StagedFile& second) {
  StagedFile* const files[] = {&first, &second};
  commit_together(files);
}

std::filesystem::path output_target(const std::filesystem::path& final_path) {
  return follow_symlinks(final_path);
}

std::filesystem::path temporary_path(const std::filesystem::path& final_path, long pid) {
  std::filesystem::path out = follow_symlinks(final_path);
  out += fmt::format(".tmp-{}", pid);
  return out;
}

void remove_stale_temporaries(const std::filesystem::path& final_path) {
  const std::string name = final_path.filename().string();
  if (name.empty()) return;
  const std::filesystem::path dir = final_path.parent_path().empty() ? "." : final_path.parent_path();
  std::error_code ec;
  std::filesystem::directory_iterator it(dir, ec);
  if (ec) return;
  const long self = static_cast<long>(::getpid());
  for (; it != std::filesystem::directory_iterator(); it.increment(ec)) {
    if (ec) return;
    const std::string entry = it->path().filename().string();
    if (entry.size() <= name.size() + 5 || entry.compare(0, name.size(), name) != 0) continue;
    const std::string suffix = entry.substr(name.size());
    if (suffix.compare(0, 5, ".tmp-") != 0 && suffix.compare(0, 5, ".old-") != 0) continue;
    const std::string digits = suffix.substr(5);
    if (digits.size() > 9 || digits.find_first_not_of("0123456789") != std::string::npos ||
        digits[0] == '0') {
      continue;  // not a PID this code writes
    }
    const long pid = std::stol(digits);
    if (pid == self) continue;
    if (::kill(static_cast<pid_t>(pid), 0) == 0 || errno != ESRCH) continue;  // alive, or not ours to ask
    std::error_code type_ec;
    if (!std::filesystem::is_regular_file(it->symlink_status(type_ec))) continue;
    std::error_code remove_ec;
    std::filesystem::remove(it->path(), remove_ec);
  }
}

}  // namespace tumble::io
