#pragma once
// Reading an input file (a mesh, a scene) whole, safely: only a regular file is read (a FIFO, a
// device such as /dev/zero, a socket or a directory is refused before a byte is read, and opening
// never blocks on a FIFO), and never more than a limit, so that no input can make tumble read
// forever or exhaust memory. The limit is kDefaultMaxInputBytes unless the environment variable
// TUMBLE_MAX_INPUT_BYTES gives another. It lives in `mass`, the first layer that reads files; `io`
// reads scene files through it.
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>

namespace tumble {

/// 1 GiB: about 20 million triangles of binary STL, 4 million of ASCII STL.
constexpr std::uint64_t kDefaultMaxInputBytes = std::uint64_t{1} << 30;

/// The environment variable that sets the limit: a whole number of bytes, optionally followed by k, M,
/// G or T (powers of 1024), e.g. TUMBLE_MAX_INPUT_BYTES=8G.
constexpr const char* kMaxInputBytesVariable = "TUMBLE_MAX_INPUT_BYTES";

/// The largest input file tumble reads: TUMBLE_MAX_INPUT_BYTES if set, else kDefaultMaxInputBytes.
/// Throws InvalidArgument when the variable is not a byte count.
std::uint64_t max_input_bytes();

/// The byte count the environment variable `name` gives (a whole number, optionally followed by k, M, G
/// or T, powers of 1024), or `fallback` when it is unset or empty. Throws InvalidArgument when it is not
/// a positive byte count.
std::uint64_t byte_count_from_environment(const char* name, std::uint64_t fallback);

/// The size of the regular file `path`, checked: FileError when it does not exist, is not a regular
/// file (the message names what it is), or is larger than max_input_bytes() (the message names the
/// limit and how to raise it). `what` names the file in messages ("mesh file", "scene file").
std::uint64_t checked_input_size(const std::filesystem::path& path, std::string_view what);

/// The bytes of the regular file `path`, with the checks of checked_input_size() made on the open
/// file itself (so the file cannot be swapped for a FIFO between the check and the read).
std::string read_input_file(const std::filesystem::path& path, std::string_view what);

/// An input file read in pieces, for files too large to hold whole (a body table of 10⁶ rows): opened
/// and checked as read_input_file() does, then read a buffer at a time. Exactly size() bytes are read;
/// a file that ends sooner (it was truncated meanwhile) is a FileError.
class InputFile {
 public:
  InputFile(const std::filesystem::path& path, std::string_view what);
  ~InputFile();
  InputFile(const InputFile&) = delete;
  InputFile& operator=(const InputFile&) = delete;

  /// The size the file had when it was opened: what is read.
  std::uint64_t size() const { return size_; }
  /// Reads up to `capacity` bytes into `buffer`: how many, 0 once size() bytes have been read.
  std::size_t read(char* buffer, std::size_t capacity);

 private:
  std::filesystem::path path_;
  std::string what_;
  int fd_;
  std::uint64_t size_ = 0, done_ = 0;
};

}  // namespace tumble
