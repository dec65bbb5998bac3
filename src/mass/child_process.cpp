// A forked child for untrusted work (child_process.hpp). POSIX and Linux calls only: fork, pipe2, poll,
// waitpid, kill, setrlimit, prctl(PR_SET_PDEATHSIG).
#include "child_process.hpp"

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fcntl.h>
#include <fmt/format.h>
#include <new>
#include <poll.h>
#include <sys/prctl.h>
#include <sys/resource.h>
#include <sys/syscall.h>
#include <sys/wait.h>
#include <unistd.h>
#include <vector>

#include "tumble/error.hpp"

namespace tumble::child_process {
namespace {

using Clock = std::chrono::steady_clock;

constexpr int kWorkThrewExitStatus = 1;
constexpr int kWriteFailedExitStatus = 112;
constexpr int kParentGoneExitStatus = 114;
constexpr std::size_t kDiagnosticsKept = 4096;

/// The child's address-space limit in bytes (0: none); set in the child only.
std::uint64_t g_address_space_limit = 0;

/// The new-handler in the child: an allocation failed (the memory limit): end, saying so.
void on_out_of_memory() { ::_exit(kOutOfMemoryExitStatus); }

/// The address space of this process in bytes (/proc/self/statm), 0 if unknown.
std::uint64_t address_space_now() {
  std::FILE* f = std::fopen("/proc/self/statm", "re");
  if (f == nullptr) return 0;
  unsigned long long pages = 0;
  const int got = std::fscanf(f, "%llu", &pages);
  std::fclose(f);
  const long page = ::sysconf(_SC_PAGESIZE);
  return got == 1 && page > 0 ? pages * static_cast<std::uint64_t>(page) : 0;
}

/// Both ends of a pipe, closed with the object unless released.
struct Pipe {
  int read = -1, write = -1;
  Pipe() {
    int fds[2];
    if (::pipe2(fds, O_CLOEXEC) != 0) {
      throw FileError(fmt::format("cannot start the mesh loader process: pipe: {}", std::strerror(errno)));
    }
    read = fds[0], write = fds[1];
  }
  ~Pipe() {
    close_read();
    close_write();
  }
  void close_read() {
    if (read >= 0) ::close(read);
    read = -1;
  }
  void close_write() {
    if (write >= 0) ::close(write);
    write = -1;
  }
  Pipe(const Pipe&) = delete;
  Pipe& operator=(const Pipe&) = delete;
};

/// In the child: from fork to the work. System calls only (async-signal-safe), then the work, then
/// _exit: never a return into the caller, never the parent's atexit handlers or stdio buffers.
[[noreturn]] void child_main(const std::function<void(int)>& work, pid_t parent, Pipe& answer,
                             Pipe& diagnostics, std::uint64_t address_space_limit) {
  // Die with the parent (a killed tumble leaves no parser running), also if it died before this line.
  ::prctl(PR_SET_PDEATHSIG, SIGKILL);
  if (::getppid() != parent) ::_exit(kParentGoneExitStatus);
  // Ctrl-C, SIGTERM and SIGHUP end the child at once (the parent may handle them by setting a flag);
  // a parent that stopped reading ends it by SIGPIPE.
  struct sigaction action = {};
  action.sa_handler = SIG_DFL;
  sigemptyset(&action.sa_mask);
  for (int s : {SIGINT, SIGTERM, SIGHUP, SIGPIPE}) ::sigaction(s, &action, nullptr);
  sigset_t none;
  sigemptyset(&none);
  ::sigprocmask(SIG_SETMASK, &none, nullptr);

  ::close(answer.read);
  ::close(diagnostics.read);
  // A parent without standard output or error may have got descriptor 1 or 2 for the answer: move it.
  int answer_fd = answer.write;
  if (answer_fd <= STDERR_FILENO) answer_fd = ::fcntl(answer_fd, F_DUPFD, STDERR_FILENO + 1);
  // Whatever the parser prints (assertions) goes to the parent, not to the user's terminal.
  ::dup2(diagnostics.write, STDOUT_FILENO);
  ::dup2(diagnostics.write, STDERR_FILENO);
  if (diagnostics.write > STDERR_FILENO) ::close(diagnostics.write);

  if (address_space_limit != 0) {
    const struct rlimit limit = {address_space_limit, address_space_limit};
    ::setrlimit(RLIMIT_AS, &limit);
    g_address_space_limit = address_space_limit;
  }
  std::set_new_handler(on_out_of_memory);
  try {
    work(answer_fd);
  } catch (const std::bad_alloc&) {  // a replaced operator new may throw without the new-handler
    ::_exit(kOutOfMemoryExitStatus);
  } catch (...) {
    ::_exit(kWorkThrewExitStatus);
  }
  ::_exit(0);
}

/// Reads what is there (the descriptor is non-blocking); false at end of file or on an error.
bool drain(int fd, std::string& into, std::size_t keep_last = 0) {
  char buffer[65536];
  for (;;) {
    const ssize_t n = ::read(fd, buffer, sizeof buffer);
    if (n > 0) {
      into.append(buffer, static_cast<std::size_t>(n));
      if (keep_last != 0 && into.size() > 2 * keep_last) into.erase(0, into.size() - keep_last);
      continue;
    }
    if (n < 0 && errno == EINTR) continue;
    if (n < 0 && (errno == EAGAIN || errno == EWOULDBLOCK)) return true;
    return false;  // end of file, or an error: nothing more will come
  }
}

/// Kills and reaps the child on every way out of run(), exceptions included.
struct Reaper {
  explicit Reaper(pid_t child) : pid(child) {}
  pid_t pid;
  int pidfd =
      static_cast<int>(::syscall(SYS_pidfd_open, pid, 0));  // readable once the child exits; -1: old kernel
  bool reaped = false;
  int status = 0;
  bool known = false;  // status is the child's (waitpid succeeded)

  /// Reaps the child if it has ended; with `block`, waits for it.
  bool try_reap(bool block) {
    if (reaped) return true;
    for (;;) {
      const pid_t r = ::waitpid(pid, &status, block ? 0 : WNOHANG);
      if (r == pid) return reaped = known = true;
      if (r == 0) return false;
      if (errno == EINTR) continue;
      return reaped = true;  // ECHILD: SIGCHLD ignored, the kernel reaped it; the status is lost
    }
  }
  void kill_and_reap() {
    if (reaped) return;
    ::kill(pid, SIGKILL);
    try_reap(true);
  }
  ~Reaper() {
    kill_and_reap();
    if (pidfd >= 0) ::close(pidfd);
  }
  Reaper(const Reaper&) = delete;
  Reaper& operator=(const Reaper&) = delete;
};

}  // namespace

void write_all(int fd, const void* data, std::size_t size) {
  const char* p = static_cast<const char*>(data);
  while (size > 0) {
    const ssize_t n = ::write(fd, p, std::min<std::size_t>(size, std::size_t{1} << 20));
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) ::_exit(kWriteFailedExitStatus);
    p += n;
    size -= static_cast<std::size_t>(n);
  }
}

void exit_out_of_memory() { ::_exit(kOutOfMemoryExitStatus); }

bool near_memory_limit() {
  if (g_address_space_limit == 0) return false;
  std::FILE* f = std::fopen("/proc/self/status", "re");
  if (f == nullptr) return false;
  char line[256];
  unsigned long long peak_kib = 0;
  while (std::fgets(line, sizeof line, f) != nullptr) {
    if (std::sscanf(line, "VmPeak: %llu kB", &peak_kib) == 1) break;
  }
  std::fclose(f);
  return peak_kib * 1024 + (std::uint64_t{16} << 20) >= g_address_space_limit;
}

Outcome run(const std::function<void(int fd)>& work, const Limits& limits) {
  Pipe answer, diagnostics;
  // The limit counts from what the child inherits (thread stacks, a sanitizer's shadow memory).
  std::uint64_t address_space_limit = 0;
  if (limits.memory_bytes != 0) {
    const std::uint64_t now = address_space_now();
    if (now != 0) address_space_limit = now + std::min(limits.memory_bytes, ~std::uint64_t{0} - now);
  }
  const pid_t parent = ::getpid();
  const auto start = Clock::now();
  const pid_t pid = ::fork();
  if (pid < 0) {
    throw FileError(fmt::format("cannot start the mesh loader process: fork: {}", std::strerror(errno)));
  }
  if (pid == 0) child_main(work, parent, answer, diagnostics, address_space_limit);

  Reaper child{pid};
  ::fcntl(answer.read, F_SETPIPE_SZ, 1 << 20);  // fewer wake-ups for a big mesh; the default if refused
  answer.close_write();
  diagnostics.close_write();
  for (int fd : {answer.read, diagnostics.read}) ::fcntl(fd, F_SETFL, ::fcntl(fd, F_GETFL) | O_NONBLOCK);

  Outcome out;
  const double seconds = std::clamp(limits.timeout_seconds, 0.0, 1e7);  // 1e7 s: 115 days, no overflow
  const auto deadline = start +
                        std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(seconds));
  bool timed_out = false;
  // Until the child is reaped (its exit seen through a pidfd, else polled every 100 ms), reading both
  // pipes; then what is left in them. Not until the pipes end: a copy of a write end may live on in a
  // process another thread forked meanwhile.
  for (;;) {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - Clock::now()).count();
    if (left <= 0) {
      timed_out = true;
      break;
    }
    struct pollfd fds[3];
    nfds_t n = 0;
    for (int fd : {answer.read, diagnostics.read, child.pidfd}) {
      if (fd >= 0) fds[n++] = {fd, POLLIN, 0};
    }
    const long long slice = child.pidfd >= 0 ? left : std::min<long long>(left, n == 0 ? 1 : 100);
    const int ready = ::poll(fds, n, static_cast<int>(std::min<long long>(slice, 1 << 30)));
    if (ready < 0 && errno != EINTR) {
      throw FileError(fmt::format("waiting for the mesh loader process: poll: {}", std::strerror(errno)));
    }
    bool exited = false;
    for (nfds_t i = 0; ready > 0 && i < n; ++i) {
      if (fds[i].revents == 0) continue;
      if (fds[i].fd == answer.read && !drain(answer.read, out.answer)) answer.close_read();
      if (fds[i].fd == diagnostics.read && !drain(diagnostics.read, out.diagnostics, kDiagnosticsKept)) {
        diagnostics.close_read();
      }
      if (fds[i].fd == child.pidfd) exited = true;
    }
    if ((exited || child.pidfd < 0) && child.try_reap(false)) {
      if (answer.read >= 0) drain(answer.read, out.answer);
      if (diagnostics.read >= 0) drain(diagnostics.read, out.diagnostics, kDiagnosticsKept);
      break;
    }
  }
  if (out.diagnostics.size() > kDiagnosticsKept) {
    out.diagnostics.erase(0, out.diagnostics.size() - kDiagnosticsKept);
  }
  if (timed_out) {
    child.kill_and_reap();
    out.end = End::timed_out;
    return out;
  }
  if (!child.known) {
    out.end = End::unknown;
  } else if (WIFSIGNALED(child.status)) {
    out.signal = WTERMSIG(child.status);
    const bool from_outside = out.signal == SIGINT || out.signal == SIGTERM || out.signal == SIGHUP ||
                              out.signal == SIGKILL || out.signal == SIGPIPE;
    out.end = from_outside ? End::interrupted : End::crashed;
  } else if (WIFEXITED(child.status) && WEXITSTATUS(child.status) == 0) {
    out.end = End::finished;
  } else if (WIFEXITED(child.status) && WEXITSTATUS(child.status) == kOutOfMemoryExitStatus) {
    out.end = End::out_of_memory;
  } else {
    out.end = End::crashed;
    out.exit_status = WIFEXITED(child.status) ? WEXITSTATUS(child.status) : -1;
  }
  return out;
}

std::string signal_name(int signal) {
  switch (signal) {
    case SIGSEGV:
      return "segmentation fault";
    case SIGABRT:
      return "abort";
    case SIGBUS:
      return "bus error";
    case SIGFPE:
      return "arithmetic exception";
    case SIGILL:
      return "illegal instruction";
    case SIGINT:
      return "interrupt";
    case SIGTERM:
      return "terminated";
    case SIGHUP:
      return "hangup";
    case SIGKILL:
      return "killed";
    case SIGPIPE:
      return "broken pipe";
    case SIGXCPU:
      return "CPU time limit";
    default:
      return fmt::format("{}", ::strsignal(signal));
  }
}

std::string telling_line(const std::string& diagnostics) {
  std::vector<std::string_view> lines;
  std::string_view rest(diagnostics);
  while (!rest.empty()) {
    const std::size_t end = rest.find('\n');
    std::string_view line = rest.substr(0, end);
    while (!line.empty() && (line.back() == '\r' || line.back() == ' ')) line.remove_suffix(1);
    if (!line.empty()) lines.push_back(line);
    if (end == std::string_view::npos) break;
    rest.remove_prefix(end + 1);
  }
  if (lines.empty()) return "";
  std::string_view chosen = lines.back();
  for (std::string_view line : lines) {
    if (line.find("ai_assert") != std::string_view::npos ||
        line.find("Assertion") != std::string_view::npos ||
        line.find("ERROR: AddressSanitizer") != std::string_view::npos ||
        line.find("runtime error:") != std::string_view::npos) {
      chosen = line;
      break;
    }
  }
  std::string out;
  for (char c : chosen.substr(0, 200)) out += static_cast<unsigned char>(c) < 0x20 || c == 0x7f ? ' ' : c;
  if (chosen.size() > 200) out += "...";
  return out;
}

}  // namespace tumble::child_process
