// CSV trajectories. Two files:
//   trajectory:  t,body, then the columns of each chosen output field (output_fields.hpp; by default
//                px,py,pz,qw,qx,qy,qz,vx,vy,vz,wx,wy,wz: the pose of the body's reference frame in world,
//                the velocity of its origin and ω, world) — one row per body and particle per sample.
//                numbers in their shortest round-trip text (number_text.hpp): every double reads
//                back bit for bit.
//   diagnostics: t and the columns of every SystemField (kinetic_energy, …, angular_momentum_drift),
//                then with rotors rotor_speed_<name> for each and rotor_torque_<name> for each — one
//                row per sample. A field is empty where the quantity is undefined (no potential,
//                or zero at t = 0), never "nan".
// and, when the trajectory is a regular file:
//   events:      t,event,body — one row per crossing, in time order (when the run watches events);
//   run facts:   OUT.run.json — the scene, settings, wall time, warnings and geometry (run_facts.hpp),
//                written at commit (when TrajectoryInfo::geometry is set).
#include <fmt/format.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <optional>

#include "number_text.hpp"
#include "run_facts.hpp"
#include "staged_file.hpp"
#include "tumble/error.hpp"
#include "tumble/forces/rotors.hpp"
#include "tumble/io/report.hpp"
#include "tumble/io/trajectory_writer.hpp"

#include <unistd.h>

namespace tumble {
namespace {

/// A sample's rows go to the file in pieces of about this size.
constexpr size_t kFlushBytes = 1 << 20;

/// What a continued file keeps of the file now under its final name (CsvContinuation).
struct Kept {
  long samples;
  size_t lines_per_sample;  ///< 0: rows by time (events), every row at t ≤ last_t kept
  double last_t;
};

/// A CSV file being written: a staged temporary (or a device, a FIFO, standard output: staged_file.hpp)
/// and its stdio stream. The first failed write throws: a full disk stops the run at once.
class CsvFile {
 public:
  CsvFile(const std::filesystem::path& path, const std::string& header, std::string_view what,
          const std::optional<Kept>& kept = {})
      : staged_(path), what_(what) {
    if (kept && staged_.kind() != io::OutputKind::staged) {
      throw InvalidArgument(
          fmt::format("the {} {} is not a regular file: it cannot be continued", what_, path.string()));
    }
    if (staged_.kind() == io::OutputKind::standard_output) {
      file_ = stdout;
    } else {
      file_ = std::fopen(staged_.temporary().c_str(), "wb");
      if (!file_) {
        throw FileError(
            fmt::format("cannot create {}: {}", staged_.temporary().string(), std::strerror(errno)));
      }
    }
    if (kept) {
      copy_kept(header, *kept);
    } else if (!header.empty()) {  // a file that is not a table (run.json) writes its own first line
      write(header + "\n");
    }
  }
  ~CsvFile() {
    if (file_ && file_ != stdout) std::fclose(file_);
  }
  CsvFile(const CsvFile&) = delete;
  CsvFile& operator=(const CsvFile&) = delete;

  void write(std::string_view text) {
    if (std::fwrite(text.data(), 1, text.size(), file_) != text.size()) fail(errno);
  }
  /// Flushes and closes (standard output: flushes); throws FileError (and deletes a temporary) if
  /// anything was lost.
  void close() {
    errno = 0;
    int error = std::fflush(file_) == 0 && !std::ferror(file_) ? 0 : (errno != 0 ? errno : EIO);
    if (file_ != stdout) {
      errno = 0;
      if (std::fclose(file_) != 0 && error == 0) error = errno != 0 ? errno : EIO;
    }
    file_ = nullptr;
    if (error != 0) fail(error);
  }
  /// Flushed to the file and fsync'ed.
  void sync() {
    if (std::fflush(file_) != 0 ||
        (file_ != stdout && staged_.kind() == io::OutputKind::staged && ::fsync(fileno(file_)) != 0)) {
      fail(errno);
    }
  }
  io::StagedFile& staged() { return staged_; }
  const std::filesystem::path& path() const { return staged_.final_path(); }

 private:
  /// Copies the header and the first kept.samples samples of the file under the final name.
  void copy_kept(const std::string& header, const Kept& kept) {
    const std::filesystem::path source = staged_.target();
    if (kept.lines_per_sample == 0) {
      copy_until(header, kept.last_t);
      return;
    }
    std::ifstream in(source, std::ios::binary);
    if (!in) {
      throw InvalidArgument(
          fmt::format("the {} {} that the checkpoint continues is missing: the run cannot "
                      "be resumed; start a new run",
                      what_, source.string()));
    }
    const size_t wanted = 1 + static_cast<size_t>(kept.samples) * kept.lines_per_sample;
    std::string line, last;
    size_t lines = 0;
    while (lines < wanted && std::getline(in, line)) {
      if (in.eof()) break;  // a last line without its newline: cut off, not a whole row
      if (lines == 0 && line != header) {
        throw InvalidArgument(fmt::format(
            "the {} {} does not have this run's header: it is not the file the checkpointed run wrote; the "
            "run cannot be resumed",
            what_, source.string()));
      }
      write(line);
      write("\n");
      ++lines;
      if (lines == wanted) last = line;
    }
    if (lines < wanted) {
      throw InvalidArgument(fmt::format(
          "the {} {} holds {} of the {} lines the checkpoint needs ({} samples): it is not the file the "
          "checkpointed run wrote, or it was cut; the run cannot be resumed",
          what_, source.string(), lines, wanted, kept.samples));
    }
    const std::string t = std::string(io::NumberText(kept.last_t)) + ",";
    if (last.compare(0, t.size(), t) != 0) {
      throw InvalidArgument(fmt::format(
          "the {} {} has another time at its sample {} than the checkpoint ({} s): it is not the file the "
          "checkpointed run wrote; the run cannot be resumed",
          what_, source.string(), kept.samples, kept.last_t));
    }
  }

  /// Copies the header and the rows at t ≤ last_t (crossings after it are found again by the resumed run,
  /// which repeats the steps from there bit for bit). A file that is missing or foreign is an error, as
  /// for the other files.
  void copy_until(const std::string& header, double last_t) {
    const std::filesystem::path source = staged_.target();
    std::ifstream in(source, std::ios::binary);
    std::string line;
    if (!in || !std::getline(in, line) || line != header) {
      throw InvalidArgument(fmt::format(
          "the {} {} that the checkpoint continues is missing or does not have this run's header; the run "
          "cannot be resumed; start a new run",
          what_, source.string()));
    }
    write(line + "\n");
    while (std::getline(in, line) && !in.eof()) {
      char* end = nullptr;
      const double t = std::strtod(line.c_str(), &end);
      if (end == line.c_str() || *end != ',' || !(t <= last_t)) break;
      write(line + "\n");
    }
  }

  [[noreturn]] void fail(int error) {
    staged_.abandon();
    const std::string reason = std::strerror(error != 0 ? error : EIO);
    switch (staged_.kind()) {
      case io::OutputKind::standard_output:
        throw FileError(fmt::format("writing the {} to standard output failed: {}", what_, reason));
      case io::OutputKind::direct:
        throw FileError(fmt::format("writing the {} to {} failed: {}", what_, path().string(), reason));
      case io::OutputKind::staged:
        break;
    }
    throw FileError(fmt::format(
        "writing the {} to {} failed: {}; nothing was kept under that name: free some space or write "
        "elsewhere",
        what_, path().string(), reason));
  }

  io::StagedFile staged_;
  std::string_view what_;
  std::FILE* file_ = nullptr;
};

std::string header(const std::vector<std::string_view>& first, auto fields) {
  std::vector<std::string_view> names = first;
  for (const auto& f : fields) {
    const auto& field = *f;
    names.insert(names.end(), field.columns.begin(), field.columns.begin() + field.width);
  }
  return fmt::format("{}", fmt::join(names, ","));
}

/// ",rotor_speed_<name>,…,rotor_torque_<name>,…" for the model's rotors (scene order), or "".
std::string rotor_columns(const Model& model) {
  std::string out;
  if (const Rotors* rotors = rotors_of(model)) {
    for (const char* what : {"rotor_speed_", "rotor_torque_"})
      for (const Rotor& r : rotors->rotors()) out += fmt::format(",{}{}", what, r.name);
  }
  return out;
}

std::vector<const SystemField*> all_system_fields() {
  std::vector<const SystemField*> out;
  for (const SystemField& f : system_fields()) out.push_back(&f);
  return out;
}

size_t row_width(const std::vector<const BodyField*>& fields) {
  size_t w = 0;
  for (const BodyField* f : fields) w += static_cast<size_t>(f->width);
  return w;
}

class CsvWriter final : public TrajectoryWriter {
 public:
  CsvWriter(const std::filesystem::path& trajectory, const std::filesystem::path& diagnostics,
            const Model& model, TrajectoryInfo&& info, const std::optional<CsvContinuation>& continuation)
      : info_(std::move(info)),
        names_(row_names(model)),
        fields_(body_fields(info_.fields, model)),
        width_(row_width(fields_)),
        unwrap_(info_.unwrap_angles ? std::optional<AngleUnwrapper>(std::in_place, fields_, names_.size())
                                    : std::nullopt),
        trajectory_(trajectory, header({"t", "body"}, fields_), "trajectory",
                    kept(continuation, names_.size())),
        samples_(continuation ? continuation->samples : 0) {
    if (!diagnostics.empty())
      diagnostics_.emplace(diagnostics, header({"t"}, all_system_fields()) + rotor_columns(model),
                           "diagnostics", kept(continuation, 1));
    if (info_.events && trajectory_.staged().kind() == io::OutputKind::staged) {
      events_.emplace(events_path(trajectory), "t,event,body", "events", kept(continuation, 0));
    }
  }

  void event(std::string_view name, size_t row, double t) override {
    if (events_) events_->write(fmt::format("{},{},{}\n", io::NumberText(t).view(), name, names_[row]));
  }

  void sync() override {
    trajectory_.sync();
    if (diagnostics_) diagnostics_->sync();
    if (events_) events_->sync();
  }

  void write(const Model& model, const SystemState& state, const DriftSample& d) override {
    begin_facts();  // here, not at commit: a writer on a thread of its own writes it while the run steps
    buffer_.clear();
    row_.resize(width_);
    const io::NumberText t(state.t);
    for (size_t r = 0; r < names_.size(); ++r) {
      buffer_.append(t.view());
      buffer_.push_back(',');
      buffer_.append(names_[r]);
      fields_of_row(fields_, model, state, r, row_.data());
      if (unwrap_) unwrap_->row(r, row_.data());
      for (const double v : row_) {
        buffer_.push_back(',');
        io::append_number(buffer_, v);
      }
      buffer_.push_back('\n');
      if (buffer_.size() > kFlushBytes) {  // a sample of 10⁵ bodies would hold 25 MB at once
        trajectory_.write(std::string_view(buffer_.data(), buffer_.size()));
        buffer_.clear();
      }
    }
    trajectory_.write(std::string_view(buffer_.data(), buffer_.size()));

    if (!diagnostics_) {
      ++samples_;
      return;
    }
    double values[3];
    buffer_.clear();
    buffer_.append(t.view());
    for (const SystemField& f : system_fields()) {
      const bool defined = f.of_sample(d, values);
      for (int k = 0; k < f.width; ++k) {
        buffer_.push_back(',');
        if (defined) io::append_number(buffer_, values[k]);  // empty where undefined, never "nan"
      }
    }
    for (const auto* rotor_values : {&d.rotor_speed, &d.rotor_torque}) {
      for (const double v : *rotor_values) {
        buffer_.push_back(',');
        io::append_number(buffer_, v);
      }
    }
    buffer_.push_back('\n');
    diagnostics_->write(std::string_view(buffer_.data(), buffer_.size()));
    ++samples_;
  }

  void outcome(double, const std::vector<std::string>& warnings) override { warnings_ = warnings; }

  void commit(bool) override {
    begin_facts();
    if (facts_) io::run_facts_tail(warnings_, [this](std::string_view text) { facts_->write(text); });
    // Every file is complete before any gets its final name, and they get them together.
    std::vector<io::StagedFile*> staged;
    for (CsvFile* f : files()) {
      f->close();
      staged.push_back(&f->staged());
    }
    io::commit_together(staged);
  }

  std::vector<CsvFile*> files() {
    std::vector<CsvFile*> out{&trajectory_};
    if (diagnostics_) out.push_back(&*diagnostics_);
    if (events_) out.push_back(&*events_);
    if (facts_) out.push_back(&*facts_);
    return out;
  }

  /// OUT.run.json up to its warnings, once, beside a regular trajectory file when there is geometry.
  void begin_facts() {
    if (facts_ || !info_.geometry || trajectory_.staged().kind() != io::OutputKind::staged) return;
    facts_.emplace(run_facts_path(trajectory_.path()), std::string(), "run facts");
    io::run_facts_head(info_, names_, [this](std::string_view text) { facts_->write(text); });
  }

  static std::optional<Kept> kept(const std::optional<CsvContinuation>& c, size_t lines_per_sample) {
    if (!c) return std::nullopt;
    return Kept{c->samples, lines_per_sample, c->last_t};
  }

  std::vector<std::filesystem::path> outputs() const override {
    std::vector<std::filesystem::path> out{trajectory_.path()};
    if (diagnostics_) out.push_back(diagnostics_->path());
    if (events_) out.push_back(events_->path());
    if (facts_) out.push_back(facts_->path());
    return out;
  }
  long samples() const override { return samples_; }

 private:
  TrajectoryInfo info_;
  std::vector<std::string> names_;
  std::vector<const BodyField*> fields_;
  size_t width_ = 0;                      // the values of a row: Σ field widths
  std::optional<AngleUnwrapper> unwrap_;  // --unwrap-angles
  std::vector<double> row_;               // one row's values
  CsvFile trajectory_;
  long samples_ = 0;
  std::optional<CsvFile> diagnostics_;
  std::optional<CsvFile> events_;
  std::optional<CsvFile> facts_;
  std::vector<std::string> warnings_;
  fmt::memory_buffer buffer_;
};

}  // namespace

std::filesystem::path diagnostics_path(const std::filesystem::path& trajectory) {
  std::filesystem::path p = trajectory;
  p.replace_extension(".diagnostics.csv");
  return p;
}

std::filesystem::path events_path(const std::filesystem::path& trajectory) {
  std::filesystem::path p = trajectory;
  p.replace_extension(".events.csv");
  return p;
}

bool same_file(const std::filesystem::path& a, const std::filesystem::path& b) {
  if (a == "-" || b == "-") return a == b;
  std::error_code ec;
  if (std::filesystem::equivalent(a, b, ec)) return true;  // same device and inode (links, "x/../")
  // Not both existing yet: the same name once "." and ".." and symlinked directories are resolved.
  const auto canonical_a = std::filesystem::weakly_canonical(std::filesystem::absolute(a), ec);
  if (ec) return false;
  const auto canonical_b = std::filesystem::weakly_canonical(std::filesystem::absolute(b), ec);
  return !ec && canonical_a == canonical_b;
}

void TrajectoryWriter::sensitivities(const Sensitivities&) {
  throw InvalidArgument(
      "sensitivities are written to HDF5 only (datasets stm and parameter_sensitivity): give an .h5 "
      "output name or --format hdf5");
}

std::unique_ptr<TrajectoryWriter> make_csv_writer(const std::filesystem::path& trajectory,
                                                  const std::filesystem::path& diagnostics,
                                                  const Model& model, TrajectoryInfo info,
                                                  const std::optional<CsvContinuation>& continuation) {
  if (!diagnostics.empty() && same_file(trajectory, diagnostics)) {
    throw InvalidArgument(
        fmt::format("the trajectory {} and the diagnostics {} are the same file: give different files",
                    trajectory.string(), diagnostics.string()));
  }
  return std::make_unique<CsvWriter>(trajectory, diagnostics, model, std::move(info), continuation);
}

}  // namespace tumble
