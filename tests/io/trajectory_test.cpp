// The trajectory writers on their own: what is written reads back bit for bit (CSV from its text,
// HDF5 through the C API), the files appear under their final names only when committed, an abandoned
// run leaves nothing behind, and a writer on a thread of its own writes the same bytes.
#include <fmt/format.h>
#include <gtest/gtest.h>
#include <hdf5.h>

#include <algorithm>
#include <bit>
#include <cstdlib>

#include "../support/scene_files.hpp"
#include "tumble/dynamics/quantities.hpp"
#include "tumble/error.hpp"
#include "tumble/forces/forces.hpp"
#include "tumble/io/trajectory_writer.hpp"

namespace tumble {
namespace {

/// A body whose reference frame is not its principal frame (offset centre, products of inertia), and
/// a particle; states at a few times with arbitrary values.
struct Fixture {
  Model model;
  std::vector<SystemState> states;
  /// With `central_body`, a central gravity model too (torque only: the motion stays as given), for the
  /// fields relative to the orbit frame (LVLH), defined for the body and the particle.
  explicit Fixture(bool central_body = false) {
    Mat3 I;
    I << 0.3, -0.02, 0.01, -0.02, 0.4, 0.0, 0.01, 0.0, 0.5;
    model.add_body(RigidBody::from_inertia(2.0, I, Vec3(0.1, -0.2, 0.05), "wheel"));
    model.add_particle(Particle{"pebble", 0.1});
    if (central_body) model.add_force<GravityGradient>(3.986e14, Vec3(0.0, 0.0, -5.0), /*torque_only=*/true);
    for (int k = 0; k < 5; ++k) {
      const double t = 0.1 * k;
      BodyState b;
      b.o = Vec3(1.0 + t, 2.0 / 3.0, -t * t);
      b.q = Quat(Eigen::AngleAxisd(0.3 + t, Vec3(1, 2, 3).normalized()));
      b.v = Vec3(1.0 / 7.0, 0.0, -2 * t);
      b.omega_w = Vec3(0.5, -1.0 / 3.0, 10.0 + t);
      states.push_back(SystemState{t, {b}, {ParticleState{Vec3(t, 0.0, 1e-20), Vec3(-1.0, 0.0, 3.0)}}});
    }
  }
  DriftSample drift(const SystemState& s) const {
    DriftSample d;
    d.invariants = invariants(model, s);
    d.energy_drift = 1.0 / 3.0 * s.t;
    d.angular_momentum_drift = 0.0;  // defined; linear momentum drift left undefined
    return d;
  }
};

std::vector<std::string> split(const std::string& line, char sep) {
  std::vector<std::string> out(1);
  for (char c : line) {
    if (c == sep) {
      out.emplace_back();
    } else {
      out.back() += c;
    }
  }
  return out;
}

std::vector<std::string> lines(const std::string& text) {
  auto out = split(text, '\n');
  if (!out.empty() && out.back().empty()) out.pop_back();  // the last line ends with a newline
  return out;
}

bool has_temporaries(const std::filesystem::path& dir) {
  for (const auto& e : std::filesystem::directory_iterator(dir)) {
    if (e.path().string().find(".tmp-") != std::string::npos) return true;
  }
  return false;
}

TEST(CsvTrajectory, RowsReadBackBitForBit) {
  const Fixture f;
  test::TempDir dir("csv_writer");
  const auto path = dir / "sub/run.csv";  // the directory is created
  auto writer = make_csv_writer(path, diagnostics_path(path), f.model, {});
  for (const auto& s : f.states) writer->write(f.model, s, f.drift(s));
  EXPECT_FALSE(std::filesystem::exists(path)) << "only the temporary exists before commit";
  writer->commit(true);
  EXPECT_EQ(writer->outputs(), (std::vector<std::filesystem::path>{path, dir / "sub/run.diagnostics.csv"}));
  EXPECT_FALSE(has_temporaries(dir / "sub"));

  const auto rows = lines(test::read_text(path));
  ASSERT_EQ(rows.size(), 1 + 2 * f.states.size());
  EXPECT_EQ(rows[0], "t,body,px,py,pz,qw,qx,qy,qz,vx,vy,vz,wx,wy,wz");
  for (size_t k = 0; k < f.states.size(); ++k) {
    const auto body = split(rows[1 + 2 * k], ',');
    const auto particle = split(rows[2 + 2 * k], ',');
    ASSERT_EQ(body.size(), 15u);
    EXPECT_EQ(body[1], "wheel");
    EXPECT_EQ(particle[1], "pebble");
    auto num = [](const std::string& s) { return std::strtod(s.c_str(), nullptr); };
    // The reference frame's pose, not the principal frame's: compare with reference_state exactly
    // (17 significant digits round-trip every double).
    const ReferenceFrameState r = reference_state(f.model.bodies[0], f.states[k].bodies[0]);
    EXPECT_EQ(num(body[0]), f.states[k].t);
    EXPECT_EQ(Vec3(num(body[2]), num(body[3]), num(body[4])), r.position);
    EXPECT_EQ(Eigen::Vector4d(num(body[5]), num(body[6]), num(body[7]), num(body[8])),
              Eigen::Vector4d(r.orientation.w(), r.orientation.x(), r.orientation.y(), r.orientation.z()));
    EXPECT_EQ(Vec3(num(body[9]), num(body[10]), num(body[11])), r.velocity);
    EXPECT_EQ(Vec3(num(body[12]), num(body[13]), num(body[14])), r.omega_w);
    EXPECT_EQ(Vec3(num(particle[2]), num(particle[3]), num(particle[4])), f.states[k].particles[0].x);
    EXPECT_EQ(particle[5] + particle[6] + particle[7] + particle[8], "1000");  // identity orientation
  }

  const auto diag = lines(test::read_text(dir / "sub/run.diagnostics.csv"));
  ASSERT_EQ(diag.size(), 1 + f.states.size());
  EXPECT_EQ(diag[0],
            "t,kinetic_energy,potential_energy,total_energy,px,py,pz,Lx,Ly,Lz,energy_drift,"
            "linear_momentum_drift,angular_momentum_drift");
  const auto last = split(diag.back(), ',');
  ASSERT_EQ(last.size(), 13u);
  const DriftSample d = f.drift(f.states.back());
  EXPECT_EQ(std::strtod(last[1].c_str(), nullptr), d.invariants.kinetic_energy);
  EXPECT_EQ(last[2], "0");  // no force models: potential 0, total = kinetic
  EXPECT_EQ(std::strtod(last[10].c_str(), nullptr), *d.energy_drift);
  EXPECT_EQ(last[11], "") << "an undefined drift is an empty field, never nan";
  EXPECT_EQ(last[12], "0");
}

TEST(CsvTrajectory, AbandonedRunLeavesNothing) {
  const Fixture f;
  test::TempDir dir("csv_abandon");
  {
    auto writer = make_csv_writer(dir / "run.csv", dir / "run.diagnostics.csv", f.model, {});
    writer->write(f.model, f.states[0], f.drift(f.states[0]));
  }  // destroyed without commit: an error happened
  EXPECT_TRUE(std::filesystem::is_empty(dir.path()));
  EXPECT_THROW(make_csv_writer(dir / "same.csv", dir / "same.csv", f.model, {}), InvalidArgument);
}

TEST(BackgroundWriter, WritesTheSameBytesAsTheWriterItWraps) {
  // Samples, crossings between them and a sync (a checkpoint) in the order a run makes them; the
  // caller's state changes right after write() returns, as the run's does when it steps on.
  const Fixture f;
  test::TempDir dir("csv_background");
  TrajectoryInfo info;
  info.events = true;
  auto direct = make_csv_writer(dir / "direct.csv", dir / "direct.diagnostics.csv", f.model, info);
  auto background =
      write_in_background(make_csv_writer(dir / "thread.csv", dir / "thread.diagnostics.csv", f.model, info));
  for (size_t k = 0; k < f.states.size(); ++k) {
    for (TrajectoryWriter* w : {direct.get(), background.get()}) {
      SystemState sample = f.states[k];
      w->write(f.model, sample, f.drift(sample));
      sample.bodies[0].o.setConstant(std::nan(""));  // the writer holds its own copy
      if (k % 2 == 1) w->event("crossing", 1, sample.t + 0.05);
      if (k == 2) w->sync();
    }
  }
  EXPECT_EQ(background->samples(), static_cast<long>(f.states.size()));
  direct->commit(true);
  background->commit(true);
  EXPECT_EQ(background->outputs(),
            (std::vector<std::filesystem::path>{dir / "thread.csv", dir / "thread.diagnostics.csv",
                                                dir / "thread.events.csv"}));
  for (const char* file : {".csv", ".diagnostics.csv", ".events.csv"}) {
    const std::string a = test::read_text(dir / (std::string("direct") + file));
    EXPECT_GT(a.size(), 20u) << file;
    EXPECT_EQ(a, test::read_text(dir / (std::string("thread") + file))) << file;
  }
  EXPECT_FALSE(has_temporaries(dir.path()));
}

/// A writer that records the calls it gets, and fails the sample `fail_at` (0: never) as a full disk
/// would.
class RecordingWriter final : public TrajectoryWriter {
 public:
  RecordingWriter(std::vector<std::string>& calls, long fail_at) : calls_(calls), fail_at_(fail_at) {}
  void write(const Model&, const SystemState& s, const DriftSample&) override {
    calls_.push_back(fmt::format("write {}", s.t));
    if (++samples_ == fail_at_) throw FileError("disk full");
  }
  void event(std::string_view name, size_t, double t) override {
    calls_.push_back(fmt::format("{} {}", name, t));
  }
  void outcome(double, const std::vector<std::string>&) override { calls_.push_back("outcome"); }
  void commit(bool) override { calls_.push_back("commit"); }
  std::vector<std::filesystem::path> outputs() const override { return {}; }
  long samples() const override { return samples_; }
  void sync() override { calls_.push_back("sync"); }

 private:
  std::vector<std::string>& calls_;
  long fail_at_;
  long samples_ = 0;
};

TEST(BackgroundWriter, CallsArriveInOrderAndAFailedWriteStopsEverythingAfterIt) {
  const Fixture f;
  std::vector<std::string> calls;
  {
    auto w = write_in_background(std::make_unique<RecordingWriter>(calls, 0));
    w->write(f.model, f.states[0], {});
    w->event("a", 0, 0.05);
    w->write(f.model, f.states[1], {});
    w->sync();
    w->write(f.model, f.states[2], {});
    w->outcome(0.0, {});
    w->commit(true);
  }
  EXPECT_EQ(calls, (std::vector<std::string>{"write 0", "a 0.05", "write 0.1", "sync", "write 0.2", "outcome",
                                             "commit"}));

  // The second sample fails on the thread: the next call throws that error, and so does every call
  // after it; nothing more reaches the writer, which is destroyed uncommitted (its temporaries go).
  calls.clear();
  {
    auto w = write_in_background(std::make_unique<RecordingWriter>(calls, 2));
    w->write(f.model, f.states[0], {});
    w->write(f.model, f.states[1], {});
    EXPECT_THROW(w->write(f.model, f.states[2], {}), FileError);
    EXPECT_THROW(w->event("a", 0, 0.25), FileError);
    EXPECT_THROW(w->commit(true), FileError);
  }
  EXPECT_EQ(calls, (std::vector<std::string>{"write 0", "write 0.1"}));

  // Destroyed while a sample is in flight (an error elsewhere in the run): it waits for the sample and
  // ends its thread.
  calls.clear();
  {
    auto w = write_in_background(std::make_unique<RecordingWriter>(calls, 0));
    w->write(f.model, f.states[0], {});
  }
  EXPECT_EQ(calls, (std::vector<std::string>{"write 0"}));
}

/// Reads a whole double dataset and its dimensions.
std::vector<double> read_doubles(hid_t file, const char* name, std::vector<hsize_t>& dims) {
  const hid_t set = H5Dopen2(file, name, H5P_DEFAULT);
  EXPECT_GE(set, 0) << name;
  const hid_t space = H5Dget_space(set);
  dims.resize(static_cast<size_t>(H5Sget_simple_extent_ndims(space)));
  H5Sget_simple_extent_dims(space, dims.data(), nullptr);
  hsize_t n = 1;
  for (hsize_t d : dims) n *= d;
  std::vector<double> out(n);
  H5Dread(set, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, out.data());
  H5Sclose(space);
  H5Dclose(set);
  return out;
}

std::string read_string_attribute(hid_t file, const char* name) {
  const hid_t attr = H5Aopen(file, name, H5P_DEFAULT);
  const hid_t type = H5Aget_type(attr);
  char* value = nullptr;
  H5Aread(attr, type, &value);
  std::string s = value ? value : "";
  H5free_memory(value);
  H5Tclose(type);
  H5Aclose(attr);
  return s;
}

TEST(Hdf5Trajectory, ArraysAndAttributesReadBack) {
  const Fixture f;
  test::TempDir dir("hdf5_writer");
  TrajectoryInfo info{
      "[simulation]\nduration = 0.4\n# ünïcode\n", "scene.toml", "9.8.7", RunSettings{}, {}, false, nullptr};
  info.settings.integrator = "rk4";
  auto writer = make_hdf5_writer(dir / "run.h5", f.model, info);
  for (const auto& s : f.states) writer->write(f.model, s, f.drift(s));
  writer->commit(false);  // as after Ctrl-C
  EXPECT_FALSE(has_temporaries(dir.path()));

  const hid_t file = H5Fopen((dir / "run.h5").c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  ASSERT_GE(file, 0);
  std::vector<hsize_t> dims;
  const auto t = read_doubles(file, "t", dims);
  EXPECT_EQ(dims, (std::vector<hsize_t>{5}));
  EXPECT_EQ(t.back(), 0.4);
  const auto q = read_doubles(file, "orientation", dims);
  EXPECT_EQ(dims, (std::vector<hsize_t>{5, 2, 4}));
  const auto w = read_doubles(file, "angular_velocity", dims);
  EXPECT_EQ(dims, (std::vector<hsize_t>{5, 2, 3}));
  for (size_t k = 0; k < f.states.size(); ++k) {
    const ReferenceFrameState r = reference_state(f.model.bodies[0], f.states[k].bodies[0]);
    EXPECT_EQ(q[k * 8 + 0], r.orientation.w());
    EXPECT_EQ(q[k * 8 + 3], r.orientation.z());
    EXPECT_EQ(q[k * 8 + 4], 1.0);  // the particle
    EXPECT_EQ(Vec3(w[k * 6], w[k * 6 + 1], w[k * 6 + 2]), r.omega_w);
  }
  const auto E = read_doubles(file, "diagnostics/energy_drift", dims);
  EXPECT_EQ(E[4], *f.drift(f.states[4]).energy_drift);
  EXPECT_LT(H5Lexists(file, "diagnostics/linear_momentum_drift", H5P_DEFAULT), 1) << "undefined: not written";
  EXPECT_EQ(read_string_attribute(file, "scene"), info.scene_text);
  EXPECT_EQ(read_string_attribute(file, "tumble_version"), "9.8.7");
  int complete = -1;
  const hid_t attr = H5Aopen(file, "complete", H5P_DEFAULT);
  H5Aread(attr, H5T_NATIVE_INT, &complete);
  H5Aclose(attr);
  EXPECT_EQ(complete, 0);
  H5Fclose(file);
}

TEST(Hdf5Trajectory, ManySamplesAcrossBlocksAndAbandon) {
  // More samples than one block of the extendible datasets (65536 values / 3 per row for the
  // vectors, so 21845 rows): the appends must line up across block boundaries.
  Model model;
  model.add_particle(Particle{"p", 1.0});
  test::TempDir dir("hdf5_blocks");
  auto writer = make_hdf5_writer(dir / "long.h5", model, {});
  const int n = 50000;
  for (int k = 0; k < n; ++k) {
    const SystemState s{k * 1e-3, {}, {ParticleState{Vec3(k, -k, 0.5 * k), Vec3::Zero()}}};
    DriftSample d;
    d.invariants = invariants(model, s);
    writer->write(model, s, d);
  }
  writer->commit(true);
  const hid_t file = H5Fopen((dir / "long.h5").c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  std::vector<hsize_t> dims;
  const auto p = read_doubles(file, "position", dims);
  H5Fclose(file);
  ASSERT_EQ(dims, (std::vector<hsize_t>{static_cast<hsize_t>(n), 1, 3}));
  for (int k = 0; k < n; k += 997) EXPECT_EQ(p[static_cast<size_t>(3 * k + 1)], -k);
  EXPECT_EQ(p.back(), 0.5 * (n - 1));

  { auto abandoned = make_hdf5_writer(dir / "abandoned.h5", model, {}); }
  EXPECT_FALSE(std::filesystem::exists(dir / "abandoned.h5"));
  EXPECT_FALSE(has_temporaries(dir.path()));
}

/// The names of the objects in an HDF5 group, sorted.
std::vector<std::string> members(hid_t file, const char* group) {
  std::vector<std::string> out;
  H5Literate_by_name(
      file, group, H5_INDEX_NAME, H5_ITER_INC, nullptr,
      [](hid_t, const char* name, const H5L_info_t*, void* data) -> herr_t {
        static_cast<std::vector<std::string>*>(data)->push_back(name);
        return 0;
      },
      &out, H5P_DEFAULT);
  return out;
}

std::string dataset_attribute(hid_t file, const std::string& dataset, const char* name) {
  const hid_t set = H5Dopen2(file, dataset.c_str(), H5P_DEFAULT);
  const std::string s = read_string_attribute(set, name);
  H5Dclose(set);
  return s;
}

TEST(OutputFields, OneTableDrivesTheCsvColumnsAndTheHdf5Datasets) {
  // Every field, in reverse table order: both files follow the order and the table's names, units and
  // frames, and hold the values the table's functions compute.
  const Fixture f(/*central_body=*/true);
  std::vector<std::string> names;
  for (const BodyField& field : body_fields()) names.emplace_back(field.name);
  std::reverse(names.begin(), names.end());
  const std::vector<const BodyField*> fields = body_fields(names);
  test::TempDir dir("output_fields");
  TrajectoryInfo info{"", "scene.toml", "0", RunSettings{}, names, false, nullptr};
  auto csv = make_csv_writer(dir / "run.csv", dir / "run.diagnostics.csv", f.model, info);
  auto h5 = make_hdf5_writer(dir / "run.h5", f.model, info);
  for (const auto& s : f.states) {
    csv->write(f.model, s, f.drift(s));
    h5->write(f.model, s, f.drift(s));
  }
  csv->commit(true);
  h5->commit(true);

  const auto rows = lines(test::read_text(dir / "run.csv"));
  std::vector<std::string> header{"t", "body"};
  for (const BodyField* field : fields)
    header.insert(header.end(), field->columns.begin(), field->columns.begin() + field->width);
  EXPECT_EQ(split(rows[0], ','), header);

  const hid_t file = H5Fopen((dir / "run.h5").c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  ASSERT_GE(file, 0);
  std::vector<std::string> expected{"diagnostics", "names", "t"};
  for (const std::string& n : names) expected.push_back(n);
  std::sort(expected.begin(), expected.end());
  EXPECT_EQ(members(file, "/"), expected);
  const auto last = split(rows[rows.size() - 2], ',');  // the body's row of the last sample
  size_t column = 2;
  for (const BodyField* field : fields) {
    const std::string name(field->name);
    EXPECT_EQ(dataset_attribute(file, name, "unit"), field->unit) << name;
    EXPECT_EQ(dataset_attribute(file, name, "frame"), field->frame) << name;
    std::vector<hsize_t> dims;
    const auto data = read_doubles(file, name.c_str(), dims);
    const size_t width = static_cast<size_t>(field->width);
    ASSERT_EQ(dims, (std::vector<hsize_t>{f.states.size(), 2, width})) << name;
    double expect[4];
    field_of_row(*field, f.model, f.states.back(), 0, expect);
    for (size_t k = 0; k < width; ++k, ++column) {
      const double from_csv = std::strtod(last[column].c_str(), nullptr);
      const double from_h5 = data[(f.states.size() - 1) * 2 * width + k];
      EXPECT_EQ(from_csv, expect[k]) << name << " " << k;
      EXPECT_EQ(from_h5, expect[k]) << name << " " << k;
    }
  }
  EXPECT_EQ(dataset_attribute(file, "diagnostics/angular_momentum", "unit"), "kg m²/s");
  H5Fclose(file);
}

TEST(OutputFields, EveryFieldIsDocumentedWithItsColumns) {
  // docs/scene-format.md lists every field as a table row: `name` | `col,col,…` | unit | frame.
  const std::string doc = test::read_text(std::filesystem::path(TUMBLE_SOURCE_DIR) / "docs/scene-format.md");
  for (const BodyField& f : body_fields()) {
    const auto columns = fmt::format("{}", fmt::join(f.columns.begin(), f.columns.begin() + f.width, ","));
    const auto row = fmt::format("| `{}` | `{}` | {} |", f.name, columns, f.unit);
    EXPECT_NE(doc.find(row), std::string::npos) << "docs/scene-format.md lacks the row " << row;
  }
}

TEST(OutputFields, ARowOfEveryFieldHasTheValuesOfEachFieldAlone) {
  // fields_of_row computes the reference frame's state once for the fields derived from it: the same
  // numbers, bit for bit, as each field on its own (body and particle rows, every sample).
  const Fixture f(/*central_body=*/true);
  std::vector<const BodyField*> all;
  size_t width = 0;
  for (const BodyField& field : body_fields()) {
    all.push_back(&field);
    width += static_cast<size_t>(field.width);
  }
  for (const SystemState& s : f.states) {
    for (size_t r = 0; r < 2; ++r) {
      std::vector<double> row(width);
      fields_of_row(all, f.model, s, r, row.data());
      size_t at = 0;
      for (const BodyField* field : all) {
        double alone[4];
        field_of_row(*field, f.model, s, r, alone);
        for (int k = 0; k < field->width; ++k, ++at) {
          EXPECT_EQ(std::bit_cast<std::uint64_t>(row[at]), std::bit_cast<std::uint64_t>(alone[k]))
              << field->name << "[" << k << "] of row " << r << " at t = " << s.t;
        }
      }
    }
  }
}

TEST(OutputFields, AFieldWithoutAValueNamesTheRowAndTheTime) {
  // crp (classical Rodrigues parameters) is infinite at a half turn: the sample there is an error that
  // names the body and the time and what to ask for instead, never an infinity written.
  Model model;
  model.add_body(RigidBody::from_principal_moments(1.0, Vec3(1.0, 2.0, 3.0), "box"));
  SystemState x{2.5, {BodyState{}}, {}};
  x.bodies[0].q = Quat(0.0, 0.0, 1.0, 0.0);  // a half turn about y
  double out[3];
  for (const bool together : {false, true}) {
    try {
      const auto fields = body_fields({"crp"});
      if (together) {
        fields_of_row(fields, model, x, 0, out);
      } else {
        field_of_row(*fields[0], model, x, 0, out);
      }
      ADD_FAILURE() << "no error";
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find(
                    "'box' at t = 2.5 s: output field 'crp': the attitude is a half turn"),
                std::string::npos)
          << e.what();
      EXPECT_NE(std::string(e.what()).find("'mrp'"), std::string::npos) << e.what();
    }
  }
  x.bodies[0].q = Quat(Eigen::AngleAxisd(2.0, Vec3::UnitY()));
  field_of_row(*body_fields({"crp"})[0], model, x, 0, out);
  EXPECT_NEAR(out[1], std::tan(1.0), 1e-15 * (1 + std::tan(1.0) * std::tan(1.0)));
}

TEST(OutputFields, UnknownAndRepeatedFieldsAreRefusedByName) {
  try {
    body_fields({"position", "speed"});
    FAIL() << "an unknown field was accepted";
  } catch (const InvalidArgument& e) {
    EXPECT_NE(std::string(e.what()).find("unknown output field 'speed'"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("angular_velocity"), std::string::npos) << "lists the fields";
  }
  EXPECT_THROW(body_fields({"position", "position"}), InvalidArgument);
  EXPECT_EQ(body_fields({}), default_body_fields());
}

}  // namespace
}  // namespace tumble
