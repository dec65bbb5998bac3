// CSV trajectories. Two files:
//   trajectory:  t,body,px,py,pz,qw,qx,qy,qz,vx,vy,vz,wx,wy,wz — one row per body per sample; the pose
//                of the body's reference frame in world (position, unit quaternion w,x,y,z mapping the
//                reference frame to world), the velocity of its origin and the angular velocity, both
//                world. %.17g: every double reads back bit for bit.
//   diagnostics: t,kinetic_energy,potential_energy,total_energy,px,py,pz,Lx,Ly,Lz,energy_drift,
//                linear_momentum_drift,angular_momentum_drift — one row per sample; momenta in world,
//                L about the world origin; drifts relative to t = 0 (drift_monitor.hpp). A field is
//                empty where the quantity is undefined (no potential, or zero at t = 0), never "nan".
#include <fmt/format.h>

#include <cerrno>
#include <cstdio>
#include <cstring>

#include "sample_rows.hpp"
#include "staged_file.hpp"
#include "tumble/error.hpp"
#include "tumble/io/trajectory_writer.hpp"

namespace tumble {
namespace {

/// A CSV file being written: a staged temporary and its stdio stream.
class CsvFile {
 public:
  CsvFile(const std::filesystem::path& path, const std::string& header) : staged_(path) {
    file_ = std::fopen(staged_.temporary().c_str(), "wb");
    if (!file_) {
      throw FileError(
          fmt::format("cannot create {}: {}", staged_.temporary().string(), std::strerror(errno)));
    }
    write(header + "\n");
  }
  ~CsvFile() {
    if (file_) std::fclose(file_);
  }
  CsvFile(const CsvFile&) = delete;
  CsvFile& operator=(const CsvFile&) = delete;

  void write(std::string_view text) {
    if (std::fwrite(text.data(), 1, text.size(), file_) != text.size()) failed_ = true;
  }
  /// Flushes and closes the temporary; throws FileError (and deletes it) if anything was lost.
  void close() {
    const bool ok = !failed_ && std::fflush(file_) == 0 && !std::ferror(file_);
    const int closed = std::fclose(file_);
    file_ = nullptr;
    if (!ok || closed != 0) {
      staged_.abandon();
      throw FileError(fmt::format("writing {} failed (disk full?): nothing was kept under that name",
                                  staged_.final_path().string()));
    }
  }
  void rename() { staged_.commit(); }
  const std::filesystem::path& path() const { return staged_.final_path(); }

 private:
  io::StagedFile staged_;
  std::FILE* file_ = nullptr;
  bool failed_ = false;
};

void optional_field(fmt::memory_buffer& out, const std::optional<double>& x) {
  if (x) fmt::format_to(std::back_inserter(out), "{:.17g}", *x);
}

class CsvWriter final : public TrajectoryWriter {
 public:
  CsvWriter(const std::filesystem::path& trajectory, const std::filesystem::path& diagnostics,
            const Model& model)
      : names_(io::row_names(model)),
        trajectory_(trajectory, "t,body,px,py,pz,qw,qx,qy,qz,vx,vy,vz,wx,wy,wz"),
        diagnostics_(diagnostics,
                     "t,kinetic_energy,potential_energy,total_energy,px,py,pz,Lx,Ly,Lz,energy_drift,"
                     "linear_momentum_drift,angular_momentum_drift") {}

  void write(const Model& model, const SystemState& state, const DriftSample& d) override {
    io::sample_rows(model, state, rows_);
    buffer_.clear();
    auto out = std::back_inserter(buffer_);
    for (size_t i = 0; i < rows_.size(); ++i) {
      const ReferenceFrameState& r = rows_[i];
      const Quat& q = r.orientation;
      fmt::format_to(out,
                     "{:.17g},{},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g},"
                     "{:.17g},{:.17g},{:.17g},{:.17g}\n",
                     state.t, names_[i], r.position.x(), r.position.y(), r.position.z(), q.w(), q.x(), q.y(),
                     q.z(), r.velocity.x(), r.velocity.y(), r.velocity.z(), r.omega_w.x(), r.omega_w.y(),
                     r.omega_w.z());
    }
    trajectory_.write(std::string_view(buffer_.data(), buffer_.size()));

    buffer_.clear();
    const Invariants& inv = d.invariants;
    fmt::format_to(out, "{:.17g},{:.17g},", state.t, inv.kinetic_energy);
    optional_field(buffer_, inv.potential_energy);
    fmt::format_to(out, ",");
    optional_field(buffer_, inv.total_energy());
    const Vec3& p = inv.linear_momentum;
    const Vec3& L = inv.angular_momentum;
    fmt::format_to(out, ",{:.17g},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g},", p.x(), p.y(), p.z(), L.x(),
                   L.y(), L.z());
    optional_field(buffer_, d.energy_drift);
    fmt::format_to(out, ",");
    optional_field(buffer_, d.linear_momentum_drift);
    fmt::format_to(out, ",");
    optional_field(buffer_, d.angular_momentum_drift);
    fmt::format_to(out, "\n");
    diagnostics_.write(std::string_view(buffer_.data(), buffer_.size()));
    ++samples_;
  }

  void commit(bool) override {
    // Both files are complete before either gets its final name.
    trajectory_.close();
    diagnostics_.close();
    trajectory_.rename();
    diagnostics_.rename();
  }

  std::vector<std::filesystem::path> outputs() const override {
    return {trajectory_.path(), diagnostics_.path()};
  }
  long samples() const override { return samples_; }

 private:
  std::vector<std::string> names_;
  CsvFile trajectory_;
  CsvFile diagnostics_;
  std::vector<ReferenceFrameState> rows_;
  fmt::memory_buffer buffer_;
  long samples_ = 0;
};

}  // namespace

std::filesystem::path diagnostics_path(const std::filesystem::path& trajectory) {
  std::filesystem::path p = trajectory;
  p.replace_extension(".diagnostics.csv");
  return p;
}

std::unique_ptr<TrajectoryWriter> make_csv_writer(const std::filesystem::path& trajectory,
                                                  const std::filesystem::path& diagnostics,
                                                  const Model& model, const TrajectoryInfo&) {
  if (std::filesystem::absolute(trajectory) == std::filesystem::absolute(diagnostics)) {
    throw InvalidArgument(fmt::format(
        "the trajectory and the diagnostics would both be {}: give different files", trajectory.string()));
  }
  return std::make_unique<CsvWriter>(trajectory, diagnostics, model);
}

}  // namespace tumble
