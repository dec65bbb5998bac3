// CSV trajectories. Two files:
//   trajectory:  t,body, then the columns of each chosen output field (output_fields.hpp; by default
//                px,py,pz,qw,qx,qy,qz,vx,vy,vz,wx,wy,wz: the pose of the body's reference frame in world,
//                the velocity of its origin and ω, world) — one row per body and particle per sample.
//                %.17g: every double reads back bit for bit.
//   diagnostics: t and the columns of every SystemField (kinetic_energy, …, angular_momentum_drift) —
//                one row per sample. A field is empty where the quantity is undefined (no potential,
//                or zero at t = 0), never "nan".
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

std::string header(const std::vector<std::string_view>& first, auto fields) {
  std::vector<std::string_view> names = first;
  for (const auto& f : fields) {
    const auto& field = *f;
    names.insert(names.end(), field.columns.begin(), field.columns.begin() + field.width);
  }
  return fmt::format("{}", fmt::join(names, ","));
}

std::vector<const SystemField*> all_system_fields() {
  std::vector<const SystemField*> out;
  for (const SystemField& f : system_fields()) out.push_back(&f);
  return out;
}

class CsvWriter final : public TrajectoryWriter {
 public:
  CsvWriter(const std::filesystem::path& trajectory, const std::filesystem::path& diagnostics,
            const Model& model, std::vector<const BodyField*> fields)
      : names_(io::row_names(model)),
        fields_(std::move(fields)),
        trajectory_(trajectory, header({"t", "body"}, fields_)),
        diagnostics_(diagnostics, header({"t"}, all_system_fields())) {}

  void write(const Model& model, const SystemState& state, const DriftSample& d) override {
    buffer_.clear();
    auto out = std::back_inserter(buffer_);
    double values[4];
    for (size_t r = 0; r < names_.size(); ++r) {
      fmt::format_to(out, "{:.17g},{}", state.t, names_[r]);
      for (const BodyField* f : fields_) {
        io::field_values(*f, model, state, r, values);
        for (int k = 0; k < f->width; ++k) fmt::format_to(out, ",{:.17g}", values[k]);
      }
      fmt::format_to(out, "\n");
    }
    trajectory_.write(std::string_view(buffer_.data(), buffer_.size()));

    buffer_.clear();
    fmt::format_to(out, "{:.17g}", state.t);
    for (const SystemField& f : system_fields()) {
      const bool defined = f.of_sample(d, values);
      for (int k = 0; k < f.width; ++k) {
        if (defined) {
          fmt::format_to(out, ",{:.17g}", values[k]);
        } else {
          fmt::format_to(out, ",");
        }
      }
    }
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
  std::vector<const BodyField*> fields_;
  CsvFile trajectory_;
  CsvFile diagnostics_;
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
                                                  const Model& model, const TrajectoryInfo& info) {
  if (std::filesystem::absolute(trajectory) == std::filesystem::absolute(diagnostics)) {
    throw InvalidArgument(fmt::format(
        "the trajectory and the diagnostics would both be {}: give different files", trajectory.string()));
  }
  return std::make_unique<CsvWriter>(trajectory, diagnostics, model, body_fields(info.fields));
}

}  // namespace tumble
