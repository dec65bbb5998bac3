// Input files: regular files only, of bounded size (input_file.hpp). POSIX open/fstat/read, so that
// the checks apply to the file actually read and a FIFO is never waited on.
#include "tumble/mass/input_file.hpp"

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cstdlib>
#include <cstring>
#include <fcntl.h>
#include <fmt/format.h>
#include <sys/stat.h>
#include <unistd.h>

#include "tumble/error.hpp"
#include "tumble/math/huge_pages.hpp"

namespace tumble {
namespace {

/// What a file that is not regular is, for messages.
std::string kind_of(mode_t mode) {
  if (S_ISDIR(mode)) return "a directory";
  if (S_ISFIFO(mode)) return "a FIFO (named pipe), which may never end";
  if (S_ISCHR(mode)) return "a character device (such as /dev/zero), which may never end";
  if (S_ISBLK(mode)) return "a block device";
  if (S_ISSOCK(mode)) return "a socket";
  return "not a regular file";
}

/// "300 bytes", or "1610612736 bytes (1.5 GiB)": the exact count, and at a glance.
std::string readable(std::uint64_t bytes) {
  const char* units[] = {"KiB", "MiB", "GiB", "TiB", "PiB", "EiB"};
  if (bytes < 1024) return fmt::format("{} bytes", bytes);
  double v = static_cast<double>(bytes) / 1024.0;
  int u = 0;
  while (v >= 1024.0 && u < 5) v /= 1024.0, ++u;
  return fmt::format("{} bytes ({:.3g} {})", bytes, v, units[u]);
}

[[noreturn]] void throw_open_error(const std::filesystem::path& path, std::string_view what, int error) {
  if (error == ENOENT || error == ENOTDIR) {
    throw FileError(fmt::format("{}: no such file; check the path and the working directory", path.string()));
  }
  throw FileError(fmt::format("{}: cannot open the {}: {}", path.string(), what, std::strerror(error)));
}

/// Checks the open file's type and size; returns the size.
std::uint64_t checked_size(const std::filesystem::path& path, std::string_view what, const struct stat& st) {
  if (!S_ISREG(st.st_mode)) {
    throw FileError(
        fmt::format("{}: {}, not a regular file; give a {} (tumble reads input from regular "
                    "files only: save a stream to a file first)",
                    path.string(), kind_of(st.st_mode), what));
  }
  const auto size = static_cast<std::uint64_t>(st.st_size);
  const std::uint64_t limit = max_input_bytes();
  if (size > limit) {
    // Suggest a limit in whole GiB above the size.
    const std::uint64_t gib = (size >> 30) + 1;
    throw FileError(
        fmt::format("{}: the {} is {}, more than tumble reads from one input file ({}); to "
                    "read it, raise the limit with the environment variable {}, e.g. {}={}G",
                    path.string(), what, readable(size), readable(limit), kMaxInputBytesVariable,
                    kMaxInputBytesVariable, gib));
  }
  return size;
}

}  // namespace

std::uint64_t byte_count_from_environment(const char* name, std::uint64_t fallback) {
  const char* text = std::getenv(name);
  if (text == nullptr || *text == '\0') return fallback;
  const std::string_view s(text);
  std::uint64_t value = 0;
  const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), value);
  const std::string_view suffix(end, static_cast<std::size_t>(s.data() + s.size() - end));
  int shift = -1;
  if (suffix.empty()) shift = 0;
  if (suffix == "k" || suffix == "K") shift = 10;
  if (suffix == "M") shift = 20;
  if (suffix == "G") shift = 30;
  if (suffix == "T") shift = 40;
  if (ec != std::errc{} || end == s.data() || shift < 0 || value == 0 || (value >> (63 - shift)) != 0) {
    throw InvalidArgument(
        fmt::format("{}='{}' is not a byte count: give a positive whole number of bytes, "
                    "optionally followed by k, M, G or T (powers of 1024), e.g. {}=8G",
                    name, s.substr(0, 40), name));
  }
  return value << shift;
}

std::uint64_t max_input_bytes() {
  return byte_count_from_environment(kMaxInputBytesVariable, kDefaultMaxInputBytes);
}

std::uint64_t checked_input_size(const std::filesystem::path& path, std::string_view what) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) throw_open_error(path, what, errno);
  return checked_size(path, what, st);
}

InputFile::InputFile(const std::filesystem::path& path, std::string_view what)
    : path_(path),
      what_(what),
      // O_NONBLOCK: opening a FIFO without a writer would otherwise wait for one, forever.
      fd_(::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC)) {
  if (fd_ < 0) throw_open_error(path, what, errno);
  try {
    struct stat st {};
    if (::fstat(fd_, &st) != 0) throw_open_error(path, what, errno);
    size_ = checked_size(path, what, st);
  } catch (...) {
    ::close(fd_);  // the destructor of an object never made does not run
    throw;
  }
}

InputFile::~InputFile() { ::close(fd_); }

std::size_t InputFile::read(char* buffer, std::size_t capacity) {
  const auto wanted = static_cast<std::size_t>(std::min<std::uint64_t>(capacity, size_ - done_));
  std::size_t got = 0;
  while (got < wanted) {
    const ssize_t n = ::read(fd_, buffer + got, wanted - got);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) {
      throw FileError(fmt::format("{}: cannot read the {}: {}", path_.string(), what_, std::strerror(errno)));
    }
    if (n == 0) {
      throw FileError(
          fmt::format("{}: the {} became shorter while it was read ({} of {} bytes); read it "
                      "again when nothing writes to it",
                      path_.string(), what_, done_ + got, size_));
    }
    got += static_cast<std::size_t>(n);
  }
  done_ += got;
  return got;
}

std::string read_input_file(const std::filesystem::path& path, std::string_view what) {
  InputFile file(path, what);
  std::string bytes;
  bytes.reserve(static_cast<std::size_t>(file.size()));
  prefer_huge_pages(bytes.data(), bytes.capacity());  // a 10⁵-body scene is 48 MB of text
  bytes.resize(static_cast<std::size_t>(file.size()));
  for (std::size_t done = 0; done < bytes.size();)
    done += file.read(bytes.data() + done, bytes.size() - done);
  return bytes;
}

}  // namespace tumble
