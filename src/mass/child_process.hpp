#pragma once
// Running untrusted work (a third-party parser given a hostile file) in a forked child process, so that
// its segfault, abort, endless loop or runaway allocation ends the child, not tumble. The child gets a
// pipe for its answer; its standard output and error go to a second pipe (the parent keeps their last
// bytes: an assertion's text). The parent reads both until the child is gone, waits at most a timeout
// (then kills it), and reaps it on every path (no zombie, no orphan: the child dies with its parent).
//
// fork() in a process that may have threads (OpenMP's): the child has only the forking thread, and
// locks other threads held stay held. glibc makes malloc usable after fork; the work must avoid what
// other threads may lock (stdio of the parent's streams, OpenMP). The child never returns into the
// caller's code: it ends with _exit (no atexit handlers, no flush of the parent's stdio buffers).
#include <cstdint>
#include <functional>
#include <string>
#include <string_view>

namespace tumble::child_process {

struct Limits {
  double timeout_seconds = 30.0;   ///< wall time the child may take, then it is killed (SIGKILL)
  std::uint64_t memory_bytes = 0;  ///< address space the child may add to what it inherits (0: no limit)
};

/// How the child ended.
enum class End {
  finished,       ///< exited with status 0 after the work returned
  crashed,        ///< killed by a signal it raised (SIGSEGV, SIGABRT, ...) or exited with another status
  interrupted,    ///< killed by SIGINT, SIGTERM, SIGHUP or SIGKILL from outside (Ctrl-C)
  timed_out,      ///< still running at the timeout: killed
  out_of_memory,  ///< an allocation failed within the memory limit
  unknown,        ///< reaped by someone else (SIGCHLD ignored): only the answer tells
};

struct Outcome {
  End end = End::unknown;
  int signal = 0;           ///< End::crashed or interrupted by a signal: its number
  int exit_status = 0;      ///< End::crashed by exiting: the status
  std::string answer;       ///< every byte the work wrote to its descriptor
  std::string diagnostics;  ///< the last 4 KiB the child wrote to standard output and error
};

/// The child's exit status for End::out_of_memory (a failed `new`, or exit_out_of_memory()).
constexpr int kOutOfMemoryExitStatus = 113;

/// Runs `work(fd)` in a child process, `fd` the write end of the answer pipe; `work` writes its answer
/// there (write_all) and returns. An exception out of `work` ends the child with status 1. Throws
/// FileError only when no child can be started (fork or pipe failing); whatever the child does is in
/// the Outcome.
Outcome run(const std::function<void(int fd)>& work, const Limits& limits);

/// Writes all `size` bytes (retrying after EINTR and short writes); in the child, a failure (the parent
/// gone) ends it.
void write_all(int fd, const void* data, std::size_t size);

/// In the child: whether the peak address space came within a few MiB of the memory limit (so that a
/// failure the work saw was probably an allocation failing: parsers that use malloc report it as
/// their own error, or not at all).
bool near_memory_limit();

/// In the child: ends it as End::out_of_memory.
[[noreturn]] void exit_out_of_memory();

/// "segmentation fault", "abort", ... for messages.
std::string signal_name(int signal);

/// The line of `diagnostics` that best says what went wrong (an assertion, a sanitizer's report, else
/// the last line), control characters removed, at most 200 characters; empty if nothing was written.
std::string telling_line(const std::string& diagnostics);

}  // namespace tumble::child_process
