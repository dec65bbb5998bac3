// Checkpoint files (format in include/tumble/io/checkpoint.hpp).
#include "tumble/io/checkpoint.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>

#include <csignal>

#include "staged_file.hpp"
#include "tumble/error.hpp"
#include "tumble/io/trajectory_writer.hpp"
#include "tumble/mass/input_file.hpp"
#include "tumble/sim/run_settings.hpp"

namespace tumble {
namespace {

constexpr char kMagic[8] = {'T', 'U', 'M', 'B', 'L', 'E', 'C', 'K'};
// 2: the run settings by the settings table, key by key; 3: the writer's host and boot, the output's
// stamp. Version 2 is read too.
constexpr std::uint32_t kVersion = 4;
constexpr std::uint32_t kByteOrder = 0x01020304;

class Out {
 public:
  void raw(const void* p, size_t n) {
    if (n > 0) bytes.append(static_cast<const char*>(p), n);  // p may be null (an empty vector's data)
  }
  void u64(std::uint64_t v) { raw(&v, sizeof v); }
  void i64(long v) { u64(static_cast<std::uint64_t>(v)); }
  void f64(double v) { raw(&v, sizeof v); }
  void str(std::string_view s) {
    u64(s.size());
    raw(s.data(), s.size());
  }
  void f64s(const std::vector<double>& v) {
    u64(v.size());
    raw(v.data(), v.size() * sizeof(double));
  }
  void opt(const std::optional<double>& v) {
    u64(v ? 1 : 0);
    f64(v.value_or(0.0));
  }
  std::string bytes;
};

/// Reads what Out wrote; anything out of bounds or out of range is a corrupt file.
class In {
 public:
  In(std::string_view bytes, const std::filesystem::path& path) : bytes_(bytes), path_(path) {}
  void raw(void* p, size_t n) {
    if (n > bytes_.size() - pos_) corrupt();
    if (n == 0) return;  // p may be null (an empty vector's data)
    std::memcpy(p, bytes_.data() + pos_, n);
    pos_ += n;
  }
  std::uint64_t u64() {
    std::uint64_t v;
    raw(&v, sizeof v);
    return v;
  }
  /// A count of items of `item` bytes each that must fit in what is left.
  size_t count(size_t item) {
    const std::uint64_t n = u64();
    if (n > (bytes_.size() - pos_) / std::max<size_t>(item, 1)) corrupt();
    return static_cast<size_t>(n);
  }
  long i64(long lo, long hi) {
    const auto v = static_cast<long>(u64());
    if (v < lo || v > hi) corrupt();
    return v;
  }
  bool flag() { return i64(0, 1) == 1; }
  double f64() {
    double v;
    raw(&v, sizeof v);
    return v;
  }
  std::string str() {
    std::string s(count(1), '\0');
    raw(s.data(), s.size());
    return s;
  }
  std::vector<double> f64s() {
    std::vector<double> v(count(sizeof(double)));
    raw(v.data(), v.size() * sizeof(double));
    return v;
  }
  std::optional<double> opt() {
    const bool has = flag();
    const double v = f64();
    return has ? std::optional<double>(v) : std::nullopt;
  }
  bool at_end() const { return pos_ == bytes_.size(); }
  [[noreturn]] void corrupt() const {
    throw InvalidArgument(fmt::format(
        "checkpoint {} is corrupt: its fields do not fit its length; it cannot be resumed", path_.string()));
  }

 private:
  std::string_view bytes_;
  const std::filesystem::path& path_;
  size_t pos_ = 0;
};

constexpr long kMaxLong = 1L << 53;

void put_point(Out& o, const RunPoint& p) {
  o.f64(p.t0);
  o.f64(p.x.t);
  const size_t n = p.x.bodies.size();
  o.u64(n);
  for (size_t k = 0; k < BodyColumns::kCount; ++k) o.raw(p.x.bodies[k], n * sizeof(double));
  o.u64(p.x.particles.size());
  for (const ParticleState& s : p.x.particles) {
    o.raw(s.x.data(), 3 * sizeof(double));
    o.raw(s.v.data(), 3 * sizeof(double));
  }
  o.i64(p.next_sample);
  o.f64(p.t_last_sample);
  o.i64(p.steps_since_sample);
  o.i64(p.samples);
  o.u64(p.finished ? 1 : 0);
  o.i64(p.stats.steps);
  o.i64(p.stats.rejected);
  o.i64(p.stats.evaluations);
  o.f64s(p.event_values);
  o.f64s(p.integrator);
}

RunPoint get_point(In& in) {
  RunPoint p;
  p.t0 = in.f64();
  p.x.t = in.f64();
  const size_t n = in.count(BodyColumns::kCount * sizeof(double));
  p.x.bodies.resize(n);
  for (size_t k = 0; k < BodyColumns::kCount; ++k) in.raw(p.x.bodies[k], n * sizeof(double));
  p.x.particles.resize(in.count(6 * sizeof(double)));
  for (ParticleState& s : p.x.particles) {
    in.raw(s.x.data(), 3 * sizeof(double));
    in.raw(s.v.data(), 3 * sizeof(double));
  }
  p.next_sample = in.i64(1, kMaxLong);
  p.t_last_sample = in.f64();
  p.steps_since_sample = in.i64(0, kMaxLong);
  p.samples = in.i64(1, kMaxLong);
  p.finished = in.flag();
  p.stats.steps = in.i64(0, kMaxLong);
  p.stats.rejected = in.i64(0, kMaxLong);
  p.stats.evaluations = in.i64(0, kMaxLong);
  p.event_values = in.f64s();
  p.integrator = in.f64s();
  return p;
}

}  // namespace

std::uint64_t fnv1a64(std::string_view bytes, std::uint64_t hash) {
  for (const unsigned char c : bytes) {
    hash ^= c;
    hash *= 0x100000001b3ULL;
  }
  return hash;
}

FileStamp stamp_file(const std::filesystem::path& path) {
  const std::string text = read_input_file(path, "input file");
  return {std::filesystem::absolute(path).lexically_normal().string(), text.size(), fnv1a64(text)};
}

void check_inputs_unchanged(const std::vector<FileStamp>& inputs) {
  for (const FileStamp& s : inputs) {
    std::error_code ec;
    if (!std::filesystem::exists(s.path, ec)) {
      throw InvalidArgument(fmt::format(
          "{}, which the scene reads, is gone since the checkpoint was written: the run cannot be resumed "
          "exactly; put the file back or start a new run",
          s.path));
    }
    const FileStamp now = stamp_file(s.path);
    if (now.size != s.size || now.hash != s.hash) {
      throw InvalidArgument(fmt::format(
          "{}, which the scene reads, changed since the checkpoint was written ({} bytes then, {} now{}): "
          "the run cannot be resumed exactly; restore the file or start a new run",
          s.path, s.size, now.size, now.size == s.size ? ", other contents" : ""));
    }
  }
}

namespace {

/// The first line of a small system file, empty if it cannot be read.
std::string first_line_of(const char* path) {
  std::string line;
  if (std::FILE* f = std::fopen(path, "re")) {
    char buffer[256];
    if (std::fgets(buffer, sizeof buffer, f)) line = buffer;
    std::fclose(f);
  }
  while (!line.empty() && (line.back() == '\n' || line.back() == '\r')) line.pop_back();
  return line;
}

std::string host_name() {
  char name[256] = {};
  return ::gethostname(name, sizeof name - 1) == 0 ? std::string(name) : std::string();
}

/// Whether process `pid` of this machine is running and is a tumble (its command name).
bool tumble_is_running(long pid) {
  if (pid == static_cast<long>(::getpid()) || ::kill(static_cast<pid_t>(pid), 0) != 0) return false;
  const std::string name = first_line_of(fmt::format("/proc/{}/comm", pid).c_str());
  return name.empty() || name.rfind("tumble", 0) == 0;  // unknown: assume it is
}

/// The FNV-1a 64 of bytes [size − kOutputTailBytes, size) of `path` (from 0 if shorter).
std::uint64_t tail_hash(const std::filesystem::path& path, std::uint64_t size) {
  const std::uint64_t from = size > kOutputTailBytes ? size - kOutputTailBytes : 0;
  std::string tail(size - from, '\0');
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  bool ok = fd >= 0;
  for (size_t done = 0; ok && done < tail.size();) {
    const ssize_t n = ::pread(fd, tail.data() + done, tail.size() - done, static_cast<off_t>(from + done));
    if (n < 0 && errno == EINTR) continue;
    ok = n > 0;
    done += ok ? static_cast<size_t>(n) : 0;
  }
  if (fd >= 0) ::close(fd);
  if (!ok)
    throw FileError(
        fmt::format("cannot read {}: {}", path.string(), std::strerror(errno != 0 ? errno : EIO)));
  return fnv1a64(tail);
}

}  // namespace

void set_writer(Checkpoint& c) {
  c.writer_pid = static_cast<long>(::getpid());
  c.writer_host = host_name();
  c.writer_boot_id = first_line_of("/proc/sys/kernel/random/boot_id");
}

void stamp_output(Checkpoint& c) {
  const std::filesystem::path temporary = io::temporary_path(c.output, c.writer_pid);
  std::error_code ec;
  const std::filesystem::path now =
      std::filesystem::is_regular_file(temporary, ec) ? temporary : io::output_target(c.output);
  const std::uint64_t size = std::filesystem::file_size(now, ec);
  if (ec) throw FileError(fmt::format("cannot stamp {} for the checkpoint: {}", now.string(), ec.message()));
  c.output_bytes = size;
  c.output_tail_hash = tail_hash(now, size);
}

namespace {

/// Throws unless the trajectory `file` is the one `c` stamped: exactly (`grown` false: the checkpoint's
/// run committed it when it was interrupted, or an earlier resume cut it back), or followed by the rows
/// a killed run wrote after the checkpoint (`grown` true: its temporary).
void check_stamp(const Checkpoint& c, const std::filesystem::path& checkpoint,
                 const std::filesystem::path& file, bool grown) {
  std::error_code ec;
  const std::uint64_t size = std::filesystem::file_size(file, ec);
  if (!ec && (grown ? size >= c.output_bytes : size == c.output_bytes) &&
      tail_hash(file, c.output_bytes) == c.output_tail_hash) {
    return;
  }
  const std::string why =
      ec ? "it is gone"
      : size != c.output_bytes && !(grown && size > c.output_bytes)
          ? fmt::format("{} bytes, where the checkpoint's run had written {}", size, c.output_bytes)
          : "its rows up to the checkpoint differ";
  throw InvalidArgument(fmt::format(
      "checkpoint {} is stale: {} is not the trajectory of its run ({}): another run has written it since, "
      "and resuming would cut it back to the checkpoint's {} samples; keep the file and start a new run with "
      "tumble run",
      checkpoint.string(), file.string(), why, c.point.samples));
}

}  // namespace

void recover_outputs(const Checkpoint& c, const std::filesystem::path& checkpoint, bool writer_gone) {
  if (c.output.empty()) return;
  const bool this_machine = c.writer_host.empty() || c.writer_host == host_name();
  const bool this_boot = c.writer_boot_id.empty() ||
                         c.writer_boot_id == first_line_of("/proc/sys/kernel/random/boot_id");
  // Everything is checked before anything moves.
  std::vector<std::pair<std::filesystem::path, std::filesystem::path>> moves;  // temporary → final
  for (const std::string& out : {c.output, c.diagnostics, events_path(c.output).string()}) {
    if (out.empty()) continue;
    const std::filesystem::path temporary = io::temporary_path(out, c.writer_pid);
    std::error_code ec;
    if (!std::filesystem::is_regular_file(std::filesystem::symlink_status(temporary, ec))) continue;
    if (!this_machine && !writer_gone) {
      throw InvalidArgument(fmt::format(
          "the run that wrote this checkpoint ran on host {} (process {}), and its {} is still there: if "
          "that "
          "run no longer runs, give --writer-gone to take its files over; if it does, stop it there first "
          "(Ctrl-C writes a last checkpoint)",
          c.writer_host, c.writer_pid, temporary.string()));
    }
    if (this_machine && this_boot && tumble_is_running(c.writer_pid)) {
      throw InvalidArgument(fmt::format(
          "the run that wrote this checkpoint (process {}) is still writing {}: stop it (Ctrl-C writes a "
          "last checkpoint) before resuming",
          c.writer_pid, temporary.string()));
    }
    moves.emplace_back(temporary, io::output_target(out));
  }
  const bool killed = !moves.empty() && moves.front().second == io::output_target(c.output);
  if (c.output_bytes != 0) {  // stamped (format version 3)
    check_stamp(c, checkpoint, killed ? moves.front().first : std::filesystem::path(c.output), killed);
    // A killed run's files replace the final ones; those must not be another run's, written since.
    std::error_code ec;
    const auto final_time = std::filesystem::last_write_time(io::output_target(c.output), ec);
    if (killed && !ec && final_time > std::filesystem::last_write_time(checkpoint)) {
      throw InvalidArgument(fmt::format(
          "checkpoint {} is stale: {} was written after it, by another run, and resuming would replace it "
          "with the checkpoint's run; keep it and start a new run with tumble run, or move it away and "
          "resume",
          checkpoint.string(), c.output));
    }
  }
  for (const auto& [temporary, target] : moves) {
    std::error_code ec;
    std::filesystem::rename(temporary, target, ec);
    if (ec) {
      throw FileError(fmt::format("cannot move the killed run's {} to {}: {}", temporary.string(),
                                  target.string(), ec.message()));
    }
  }
  // The rows after the checkpoint are the resume's to write again: cut now, so the trajectory is the
  // stamped one exactly, whatever becomes of this resume.
  if (killed && c.output_bytes != 0)
    std::filesystem::resize_file(io::output_target(c.output), c.output_bytes);
}

namespace {
/// Where write_checkpoint stages PATH: PATH.tmp-PID.
std::filesystem::path checkpoint_temporary(const std::filesystem::path& path) {
  std::filesystem::path temporary = path;
  temporary += fmt::format(".tmp-{}", static_cast<long>(::getpid()));
  return temporary;
}
}  // namespace

void check_checkpoint_path(const std::filesystem::path& path) {
  std::error_code ec;
  const auto status = std::filesystem::status(path, ec);
  if (std::filesystem::exists(status) && !std::filesystem::is_regular_file(status)) {
    throw InvalidArgument(
        fmt::format("--checkpoint {} is not a regular file: give a file name, e.g. "
                    "--checkpoint run.checkpoint",
                    path.string()));
  }
  if (const auto dir = path.parent_path(); !dir.empty()) {
    std::filesystem::create_directories(dir, ec);
    if (ec) {
      throw FileError(
          fmt::format("cannot create the checkpoint's directory {}: {}; give another --checkpoint",
                      dir.string(), ec.message()));
    }
  }
  const std::filesystem::path probe = checkpoint_temporary(path);
  const int fd = ::open(probe.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0) {
    throw FileError(fmt::format("cannot write the checkpoint {}: {}; give another --checkpoint",
                                path.string(), std::strerror(errno)));
  }
  ::close(fd);
  std::filesystem::remove(probe, ec);
}

void write_checkpoint(const std::filesystem::path& path, const Checkpoint& c) {
  Out o;
  o.raw(kMagic, sizeof kMagic);
  const std::uint32_t head[2] = {kVersion, kByteOrder};
  o.raw(head, sizeof head);
  o.str(c.tumble_version);
  o.str(c.scene_path);
  o.str(c.scene_absolute);
  o.str(c.scene_text);
  o.u64(c.inputs.size());
  for (const FileStamp& s : c.inputs) {
    o.str(s.path);
    o.u64(s.size);
    o.u64(s.hash);
  }
  // Every setting of the table (sim/run_settings.hpp) by its key: a setting added to the table is kept
  // without a line here.
  o.u64(run_settings().size());
  for (const RunSetting& s : run_settings()) {
    o.str(s.key);
    const SettingValue v = s.get(c.settings);
    o.u64(std::holds_alternative<std::string>(v) ? 1 : 0);
    if (const auto* name = std::get_if<std::string>(&v)) {
      o.str(*name);
    } else {
      o.f64(std::get<double>(v));
    }
  }
  o.str(c.output);
  o.str(c.diagnostics);
  o.u64(c.fields.size());
  for (const std::string& f : c.fields) o.str(f);
  o.u64(c.strict ? 1 : 0);
  o.i64(c.writer_pid);
  o.str(c.writer_host);
  o.str(c.writer_boot_id);
  o.opt(c.largest_energy_drift);
  o.opt(c.largest_angular_momentum_drift);
  o.str(c.drift_warning);
  o.u64(c.output_bytes);
  o.u64(c.output_tail_hash);
  o.u64(c.crossings.size());
  for (const auto& [count, first] : c.crossings) {
    o.i64(count);
    o.f64(first);
  }
  put_point(o, c.point);
  o.u64(fnv1a64(o.bytes));

  const std::filesystem::path temporary = checkpoint_temporary(path);
  auto fail = [&](int error) {
    std::error_code ec;
    std::filesystem::remove(temporary, ec);
    throw FileError(fmt::format("cannot write the checkpoint {}: {}", path.string(),
                                std::strerror(error != 0 ? error : EIO)));
  };
  const int fd = ::open(temporary.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0) fail(errno);
  size_t done = 0;
  while (done < o.bytes.size()) {
    const ssize_t n = ::write(fd, o.bytes.data() + done, o.bytes.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      const int error = errno;
      ::close(fd);
      fail(error);
    }
    done += static_cast<size_t>(n);
  }
  if (::fsync(fd) != 0) {
    const int error = errno;
    ::close(fd);
    fail(error);
  }
  if (::close(fd) != 0) fail(errno);
  if (std::rename(temporary.c_str(), path.c_str()) != 0) fail(errno);
}

Checkpoint read_checkpoint(const std::filesystem::path& path) {
  const std::string bytes = read_input_file(path, "checkpoint");
  const std::string name = path.string();
  if (bytes.size() < sizeof kMagic || std::memcmp(bytes.data(), kMagic, sizeof kMagic) != 0) {
    throw InvalidArgument(
        fmt::format("{} is not a tumble checkpoint (it does not begin with TUMBLECK)", name));
  }
  std::uint32_t head[2] = {0, 0};
  if (bytes.size() < sizeof kMagic + sizeof head + 8) {
    throw InvalidArgument(
        fmt::format("checkpoint {} is truncated ({} bytes); it cannot be resumed", name, bytes.size()));
  }
  std::memcpy(head, bytes.data() + sizeof kMagic, sizeof head);
  if (head[1] != kByteOrder) {
    throw InvalidArgument(fmt::format(
        "checkpoint {} was written on a machine of the other byte order; resume it on such a machine", name));
  }
  const std::uint32_t version = head[0];
  if (version < 2 || version > kVersion) {
    throw InvalidArgument(fmt::format(
        "checkpoint {} has format version {}; this tumble reads versions 2 to {}: resume it with the tumble "
        "that wrote it",
        name, version, kVersion));
  }
  std::uint64_t stored;
  std::memcpy(&stored, bytes.data() + bytes.size() - 8, 8);
  const std::string_view body(bytes.data(), bytes.size() - 8);
  if (fnv1a64(body) != stored) {
    throw InvalidArgument(fmt::format(
        "checkpoint {} is truncated or corrupt (its checksum does not match its contents); it cannot be "
        "resumed",
        name));
  }
  In in(body.substr(sizeof kMagic + sizeof head), path);
  Checkpoint c;
  c.tumble_version = in.str();
  c.scene_path = in.str();
  c.scene_absolute = in.str();
  c.scene_text = in.str();
  c.inputs.resize(in.count(24));
  for (FileStamp& s : c.inputs) {
    s.path = in.str();
    s.size = in.u64();
    s.hash = in.u64();
  }
  // The settings by key; one the table does not have is from another tumble (a setting this file lacks
  // keeps its default).
  const size_t settings = in.count(16);
  for (size_t k = 0; k < settings; ++k) {
    const std::string key = in.str();
    const bool is_name = in.flag();
    const SettingValue v = is_name ? SettingValue(in.str()) : SettingValue(in.f64());
    const RunSetting* s = find_run_setting(key);
    if (!s) {
      throw InvalidArgument(
          fmt::format("checkpoint {} holds the setting '{}', which this tumble does not know: "
                      "resume it with the tumble that wrote it ({})",
                      name, key, c.tumble_version));
    }
    try {
      set_run_setting(c.settings, *s, v, key);
    } catch (const InvalidArgument&) {
      in.corrupt();
    }
  }
  c.output = in.str();
  c.diagnostics = in.str();
  c.fields.resize(in.count(8));
  for (std::string& f : c.fields) f = in.str();
  c.strict = in.flag();
  c.writer_pid = in.i64(1, kMaxLong);
  if (version >= 3) {
    c.writer_host = in.str();
    c.writer_boot_id = in.str();
  }
  c.largest_energy_drift = in.opt();
  c.largest_angular_momentum_drift = in.opt();
  c.drift_warning = in.str();
  if (version >= 3) {
    c.output_bytes = in.u64();
    c.output_tail_hash = in.u64();
  }
  if (version >= 4) {
    c.crossings.resize(in.count(16));
    for (auto& [count, first] : c.crossings) {
      count = in.i64(0, kMaxLong);
      first = in.f64();
    }
  }
  c.point = get_point(in);
  if (!in.at_end()) in.corrupt();
  return c;
}

}  // namespace tumble
