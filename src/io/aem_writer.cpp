// CCSDS Attitude Ephemeris Messages (trajectory_writer.hpp, make_aem_writer). The format, as the
// standard (CCSDS 504.0-B-2, ADM version 2.0) and Orekit's parser read it: docs/research/ccsds-aem.md.
// Version 2 has no ATTITUDE_DIR and no QUATERNION_TYPE: the quaternion is always frame A → frame B,
// scalar last, and rates are in deg/s; ANGVEL_FRAME is SC_BODY_1, the body's own axes.
//
// The samples of each body are kept in an anonymous temporary file until commit, when the message is
// written under a staged name (staged_file.hpp) and moved into place: a segment's START_TIME and
// STOP_TIME come before its data, and a run may stop anywhere.
#include <fmt/format.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <numbers>
#include <vector>

#include "staged_file.hpp"
#include "tumble/error.hpp"
#include "tumble/io/trajectory_writer.hpp"
#include "utc_time.hpp"

namespace tumble {
namespace {

/// The names REF_FRAME_A may take here: an inertial frame's name in the standard's form (upper-case
/// letters, digits, '_'; EME2000, ICRF, GCRF, ...), not a spacecraft frame (that is frame B).
void check_reference_frame(const std::string& name) {
  const bool form = !name.empty() && std::all_of(name.begin(), name.end(), [](char c) {
    return (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_';
  });
  if (!form || name.starts_with("SC_BODY")) {
    throw InvalidArgument(fmt::format(
        "--aem-frame {}: give the inertial frame tumble's world axes stand for, as CCSDS names it (EME2000, "
        "ICRF, GCRF, ...: upper-case letters, digits and '_'); the body's own frame is SC_BODY_1",
        name));
  }
}

/// The creation date: now, or SOURCE_DATE_EPOCH's (reproducible files, as build tools honour it).
std::string creation_date() {
  using namespace std::chrono;
  std::int64_t seconds = duration_cast<std::chrono::seconds>(system_clock::now().time_since_epoch()).count();
  if (const char* fixed = std::getenv("SOURCE_DATE_EPOCH")) {
    char* end = nullptr;
    const long long v = std::strtoll(fixed, &end, 10);
    if (end != fixed && *end == '\0') seconds = v;
  }
  const io::CalendarTime unix_epoch{0, 0};
  return io::format_calendar_time(unix_epoch, static_cast<double>(seconds));
}

class Segment {
 public:
  Segment() : file_(std::tmpfile()) {
    if (!file_)
      throw FileError(fmt::format("cannot create a temporary file for the AEM: {}", std::strerror(errno)));
  }
  ~Segment() {
    if (file_) std::fclose(file_);
  }
  Segment(const Segment&) = delete;
  Segment& operator=(const Segment&) = delete;

  std::FILE* file() const { return file_; }
  std::string first, last;  ///< the dates of the first and last lines

 private:
  std::FILE* file_;
};

class AemWriter final : public TrajectoryWriter {
 public:
  AemWriter(const std::filesystem::path& path, const Model& model, const TrajectoryInfo& info,
            const AemHeader& header)
      : staged_(path),
        epoch_(io::parse_calendar_time(header.epoch, "--epoch")),
        ref_frame_(header.ref_frame),
        run_(fmt::format("tumble {}: {}, {} with steps of {} s; time 0 s is {} (days of 86400 s, no leap "
                         "second)",
                         info.tumble_version, info.scene_path, info.settings.integrator,
                         info.settings.timestep, header.epoch)) {
    check_reference_frame(ref_frame_);
    if (model.bodies.empty()) {
      throw InvalidArgument(
          "an attitude message (.aem) holds the attitude of bodies, and the system has only particles: write "
          "CSV or HDF5");
    }
    for (const RigidBody& b : model.bodies) {
      names_.push_back(b.name());
      segments_.push_back(std::make_unique<Segment>());
    }
  }

  void write(const Model& model, const SystemState& state, const DriftSample&) override {
    const std::string date = io::format_calendar_time(epoch_, state.t);
    if (samples_ > 0 && date == segments_[0]->last) return;  // the same instant to the nanosecond
    constexpr double deg = 180.0 / std::numbers::pi;
    for (size_t b = 0; b < model.bodies.size(); ++b) {
      const ReferenceFrameState r = reference_state(model.bodies[b], state.bodies[b]);
      const Quat& q = r.orientation;
      const Vec3 w = deg * rotate_inverse<double>(q, r.omega_w);  // R_refᵀ ω: the body's own axes
      // 16 significant digits: the standard's limit, and enough to carry a double's value to 1 ulp.
      const std::string line = fmt::format("{} {:.15e} {:.15e} {:.15e} {:.15e} {:.15e} {:.15e} {:.15e}\n",
                                           date, q.x(), q.y(), q.z(), q.w(), w.x(), w.y(), w.z());
      Segment& s = *segments_[b];
      if (std::fputs(line.c_str(), s.file()) == EOF) fail(errno);
      if (s.first.empty()) s.first = date;
      s.last = date;
    }
    last_t_ = state.t;
    ++samples_;
  }
  void event(std::string_view, size_t, double) override {}
  void outcome(double, const std::vector<std::string>&) override {}
  long samples() const override { return samples_; }
  std::vector<std::filesystem::path> outputs() const override { return {staged_.final_path()}; }

  void commit(bool complete) override {
    std::FILE* out = staged_.kind() == io::OutputKind::standard_output
                         ? stdout
                         : std::fopen(staged_.temporary().c_str(), "wb");
    if (!out) fail(errno);
    std::string head = fmt::format("CCSDS_AEM_VERS = 2.0\nCOMMENT {}\n", run_);
    if (!complete) head += fmt::format("COMMENT incomplete: the run stopped at time {} s\n", last_t_);
    head += fmt::format("CREATION_DATE = {}\nORIGINATOR = TUMBLE\n", creation_date());
    bool ok = std::fputs(head.c_str(), out) != EOF;
    for (size_t b = 0; b < segments_.size() && ok && samples_ > 0; ++b) {
      Segment& s = *segments_[b];
      const std::string& name = names_[b];
      ok = std::fputs(fmt::format("\nMETA_START\n"
                                  "OBJECT_NAME = {}\n"
                                  "OBJECT_ID = {}\n"
                                  "REF_FRAME_A = {}\n"
                                  "REF_FRAME_B = SC_BODY_1\n"
                                  "TIME_SYSTEM = UTC\n"
                                  "START_TIME = {}\n"
                                  "STOP_TIME = {}\n"
                                  "ATTITUDE_TYPE = QUATERNION/ANGVEL\n"
                                  "ANGVEL_FRAME = SC_BODY_1\n"
                                  "INTERPOLATION_METHOD = HERMITE\n"
                                  "INTERPOLATION_DEGREE = 1\n"
                                  "META_STOP\n\nDATA_START\n",
                                  name, name, ref_frame_, s.first, s.last)
                          .c_str(),
                      out) != EOF;
      std::rewind(s.file());
      char buffer[1 << 16];
      size_t n = 0;
      while (ok && (n = std::fread(buffer, 1, sizeof buffer, s.file())) > 0)
        ok = std::fwrite(buffer, 1, n, out) == n;
      ok = ok && !std::ferror(s.file()) && std::fputs("DATA_STOP\n", out) != EOF;
    }
    int error = ok && std::fflush(out) == 0 && !std::ferror(out) ? 0 : (errno != 0 ? errno : EIO);
    if (out != stdout && std::fclose(out) != 0 && error == 0) error = errno != 0 ? errno : EIO;
    if (error != 0) fail(error);
    staged_.commit();
  }

 private:
  [[noreturn]] void fail(int error) {
    staged_.abandon();
    throw FileError(
        fmt::format("writing the attitude message {} failed: {}; nothing was kept under that name",
                    staged_.final_path().string(), std::strerror(error != 0 ? error : EIO)));
  }

  io::StagedFile staged_;
  io::CalendarTime epoch_;
  std::string ref_frame_;
  std::string run_;                 ///< the header's COMMENT: what made the file
  std::vector<std::string> names_;  ///< OBJECT_NAME and OBJECT_ID of each segment: the bodies' names
  std::vector<std::unique_ptr<Segment>> segments_;
  long samples_ = 0;
  double last_t_ = 0.0;
};

}  // namespace

std::unique_ptr<TrajectoryWriter> make_aem_writer(const std::filesystem::path& path, const Model& model,
                                                  const TrajectoryInfo& info, const AemHeader& header) {
  return std::make_unique<AemWriter>(path, model, info, header);
}

}  // namespace tumble
