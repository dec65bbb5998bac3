// HDF5 trajectories (HDF5 C API), one file, readable by h5py:
//
//   /t                 (n,)          s
//   /names             (N,)          body names, then particle names (UTF-8 strings)
//   /<field>           (n, N, width) one dataset per chosen output field (output_fields.hpp), by
//                      default position, orientation (w, x, y, z), velocity and angular_velocity: the
//                      pose and velocity of each body's reference frame, world; particles are frames
//                      with the identity orientation and zero ω
//   /diagnostics/<field> (n,) or (n, 3): every SystemField defined at t = 0 (kinetic_energy, …,
//                      angular_momentum_drift; potential and total energy only when every force has a
//                      potential, a drift only where its scale at t = 0 is not zero)
//   /diagnostics/rotor_speed, rotor_torque (n, R), rotor_names (R,): with rotors, each one's speed
//                      relative to its body (rad/s) and motor torque (N m), in scene order
//   attributes of every field's dataset: unit, frame, meaning (from the same table)
//   attributes of /: tumble_version, scene (the scene file's text), scene_file, integrator,
//     formulation, timestep, duration, output_interval, complete (1, or 0 if interrupted), t_end
//
// Datasets are chunked and extendible along the sample axis, appended in blocks as the run goes.
#include <hdf5.h>

#include <fmt/format.h>

#include <array>
#include <cerrno>
#include <cstring>

#include "hdf5_file_driver.hpp"
#include "hdf5_util.hpp"
#include "staged_file.hpp"
#include "tumble/error.hpp"
#include "tumble/forces/rotors.hpp"
#include "tumble/integrate/integrator.hpp"
#include "tumble/io/trajectory_writer.hpp"
#include "tumble/sim/run_plan.hpp"

namespace tumble {
namespace {

using io::Checker;
using io::Handle;
using io::number_attribute;
using io::reason;
using io::string_attribute;
using io::string_type;
using io::untimed;

/// A dataset of shape (n, row...) growing along n, with rows buffered and appended in blocks.
class Series {
 public:
  /// A run planned to write `planned_samples` (run_plan.hpp) sizes its chunks by them.
  Series(hid_t loc, const char* name, std::vector<hsize_t> row_shape, double planned_samples,
         const Checker& check)
      : name_(name), writing_("write " + name_), row_shape_(std::move(row_shape)), check_(check) {
    row_size_ = 1;
    for (hsize_t d : row_shape_) row_size_ *= d;
    block_ = hdf5_chunk_samples(row_size_, planned_samples);
    std::vector<hsize_t> dims{0}, max{H5S_UNLIMITED}, chunk{block_};
    for (hsize_t d : row_shape_) {
      dims.push_back(d);
      max.push_back(d);
      chunk.push_back(d);
    }
    const Handle space(check(H5Screate_simple(static_cast<int>(dims.size()), dims.data(), max.data()),
                             "create a dataset"),
                       H5Sclose);
    const Handle props = untimed(H5P_DATASET_CREATE, "create a dataset", check);
    check(H5Pset_chunk(props.get(), static_cast<int>(chunk.size()), chunk.data()), "create a dataset");
    dataset_ = Handle(
        check(H5Dcreate2(loc, name, H5T_NATIVE_DOUBLE, space.get(), H5P_DEFAULT, props.get(), H5P_DEFAULT),
              "create a dataset"),
        H5Dclose);
  }

  /// Appends one row of row_size values.
  void append(const double* row) {
    pending_.insert(pending_.end(), row, row + row_size_);
    if (pending_.size() >= block_ * row_size_) flush();
  }
  void append(double x) { append(&x); }

  void flush() {
    if (pending_.empty()) return;
    const hsize_t rows = pending_.size() / row_size_;
    std::vector<hsize_t> new_dims{written_ + rows}, start{written_}, count{rows};
    for (hsize_t d : row_shape_) {
      new_dims.push_back(d);
      start.push_back(0);
      count.push_back(d);
    }
    check_(H5Dset_extent(dataset_.get(), new_dims.data()), writing_.c_str());
    const Handle file_space(check_(H5Dget_space(dataset_.get()), writing_.c_str()), H5Sclose);
    check_(H5Sselect_hyperslab(file_space.get(), H5S_SELECT_SET, start.data(), nullptr, count.data(),
                               nullptr),
           writing_.c_str());
    const Handle memory_space(check_(H5Screate_simple(static_cast<int>(count.size()), count.data(), nullptr),
                                     writing_.c_str()),
                              H5Sclose);
    check_(H5Dwrite(dataset_.get(), H5T_NATIVE_DOUBLE, memory_space.get(), file_space.get(), H5P_DEFAULT,
                    pending_.data()),
           writing_.c_str());
    written_ += rows;
    pending_.clear();
  }

  bool close() { return dataset_.reset(); }
  hid_t id() const { return dataset_.get(); }

 private:
  std::string name_;
  std::string writing_;  // "write position", for messages
  std::vector<hsize_t> row_shape_;
  Checker check_;
  hsize_t row_size_ = 1;
  hsize_t block_ = 1;
  hsize_t written_ = 0;
  std::vector<double> pending_;
  Handle dataset_;
};

class Hdf5Writer final : public TrajectoryWriter {
 public:
  Hdf5Writer(const std::filesystem::path& path, const Model& model, const TrajectoryInfo& info)
      : staged_(path, /*direct_allowed=*/false),
        check_{path.string(), &driver_},
        names_(row_names(model)),
        fields_(body_fields(info.fields, model)),
        unwrap_(info.unwrap_angles ? std::optional<AngleUnwrapper>(std::in_place, fields_, names_.size())
                                   : std::nullopt),
        planned_samples_(plan_run(info.settings, model.bodies.size(), model.particles.size()).samples),
        watch_events_(info.events) {
    if (const Rotors* rotors = rotors_of(model))
      for (const Rotor& r : rotors->rotors()) rotor_names_.push_back(r.name);
    // Errors are reported by return codes, turned into one FileError line; HDF5's own stack print
    // to stderr would only add noise.
    H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
    // Through tumble's file driver: a write error (a full disk) is reported, never a crash in HDF5's
    // exit handler (hdf5_file_driver.hpp).
    const Handle access(check_(io::hdf5_recording_fapl(&driver_), "set up its file driver"), H5Pclose);
    file_ = Handle(check_(H5Fcreate(staged_.temporary().c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, access.get()),
                          "create the file"),
                   H5Fclose);
    const hid_t root = file_.get();
    string_attribute(root, "tumble_version", info.tumble_version, check_);
    string_attribute(root, "scene", info.scene_text, check_);
    string_attribute(root, "scene_file", info.scene_path, check_);
    string_attribute(root, "integrator", info.settings.integrator, check_);
    string_attribute(root, "formulation", formulation_name(info.settings.formulation), check_);
    string_attribute(root, "conventions",
                     "SI units; position, orientation (w, x, y, z), velocity: the body's reference frame in "
                     "world; angular_velocity in world; diagnostics: momenta in world, angular momentum "
                     "about the world origin, drifts relative to t = 0",
                     check_);
    number_attribute(root, "timestep", info.settings.timestep, H5T_NATIVE_DOUBLE, check_);
    number_attribute(root, "duration", info.settings.duration, H5T_NATIVE_DOUBLE, check_);
    number_attribute(root, "output_interval", info.settings.output_interval, H5T_NATIVE_DOUBLE, check_);
    write_names();
    const hsize_t N = names_.size();
    t_.emplace(root, "t", std::vector<hsize_t>{}, planned_samples_, check_);
    string_attribute(t_->id(), "unit", "s", check_);
    field_series_.reserve(fields_.size());
    for (const BodyField* f : fields_) {
      const hsize_t width = static_cast<hsize_t>(f->width);
      Series& series = field_series_.emplace_back(root, std::string(f->name).c_str(),
                                                  std::vector<hsize_t>{N, width}, planned_samples_, check_);
      describe(series.id(), *f);
    }
    if (info.geometry) write_geometry(*info.geometry);
    const Handle group_props = untimed(H5P_GROUP_CREATE, "create group diagnostics", check_);
    diagnostics_ = Handle(check_(H5Gcreate2(root, "diagnostics", H5P_DEFAULT, group_props.get(), H5P_DEFAULT),
                                 "create group diagnostics"),
                          H5Gclose);
  }

  void write(const Model& model, const SystemState& state, const DriftSample& d) override {
    if (samples_ == 0) create_diagnostics(d);
    t_->append(state.t);
    // Every field of a row at once (the reference frame's state computed once), then each field's
    // dataset gathered from them.
    size_t row_width = 0;
    for (const BodyField* f : fields_) row_width += static_cast<size_t>(f->width);
    all_.resize(names_.size() * row_width);
    for (size_t r = 0; r < names_.size(); ++r) {
      fields_of_row(fields_, model, state, r, &all_[r * row_width]);
      if (unwrap_) unwrap_->row(r, &all_[r * row_width]);
    }
    for (size_t k = 0, at = 0; k < fields_.size(); at += static_cast<size_t>(fields_[k]->width), ++k) {
      const size_t width = static_cast<size_t>(fields_[k]->width);
      row_.resize(names_.size() * width);
      for (size_t r = 0; r < names_.size(); ++r)
        std::copy_n(&all_[r * row_width + at], width, &row_[r * width]);
      field_series_[k].append(row_.data());
    }
    double values[3];
    for (size_t k = 0; k < diagnostic_series_.size(); ++k) {
      if (!diagnostic_series_[k]) continue;
      const SystemField& f = system_fields()[k];
      // Defined at t = 0, so defined throughout (the force models and the scales at t = 0 fix it).
      if (!f.of_sample(d, values)) std::fill_n(values, f.width, 0.0);
      diagnostic_series_[k]->append(values);
    }
    if (rotor_speed_) {
      rotor_speed_->append(d.rotor_speed.data());
      rotor_torque_->append(d.rotor_torque.data());
    }
    t_end_ = state.t;
    ++samples_;
  }

  ~Hdf5Writer() override {
    // Closing an abandoned file (an error on the way out) must not fail inside HDF5.
    driver_.closing = true;
  }

  void event(std::string_view name, size_t row, double t) override {
    if (!watch_events_) return;
    event_names_.emplace_back(name);
    event_rows_.push_back(static_cast<long long>(row));
    event_times_.push_back(t);
  }

  void outcome(double, const std::vector<std::string>& warnings) override { warnings_ = warnings; }

  void commit(bool complete) override {
    for (Series* s : all_series()) s->flush();
    if (!warnings_.empty())
      string_attribute(file_.get(), "warnings", fmt::format("{}", fmt::join(warnings_, "\n")), check_);
    if (watch_events_) write_events();
    number_attribute(file_.get(), "complete", complete ? 1 : 0, H5T_NATIVE_INT, check_);
    number_attribute(file_.get(), "t_end", t_end_, H5T_NATIVE_DOUBLE, check_);
    // Everything written now, where an error is still HDF5's to report; from here on the driver
    // only records errors, so that every close completes (hdf5_file_driver.hpp).
    check_(H5Fflush(file_.get(), H5F_SCOPE_LOCAL), "write the file");
    driver_.closing = true;
    bool ok = true;
    for (Series* s : all_series()) ok = s->close() && ok;
    ok = diagnostics_.reset() && ok;
    ok = file_.reset() && ok;
    if (!ok || driver_.error != 0) {
      staged_.abandon();
      throw FileError(fmt::format("writing {} failed: {}; nothing was kept under that name",
                                  staged_.final_path().string(), reason(&driver_)));
    }
    staged_.commit();
  }

  std::vector<std::filesystem::path> outputs() const override { return {staged_.final_path()}; }
  long samples() const override { return samples_; }

  /// `stm` and `parameter_sensitivity`, one row per sample: (12B, 12B) and (12B, PB) for bodies that
  /// interact, each body's own blocks (B, 12, 12) and (B, 12, P) for bodies that do not (never a
  /// 12B × 12B matrix of zeros); the attribute `layout` says which, row-major either way.
  void sensitivities(const Sensitivities& S) override {
    const hsize_t rows = static_cast<hsize_t>(S.stm.rows());
    auto shape = [&](const Eigen::MatrixXd& M) {
      const hsize_t cols = static_cast<hsize_t>(M.cols());
      return S.coupled ? std::vector<hsize_t>{rows, cols} : std::vector<hsize_t>{rows / 12, 12, cols};
    };
    if (!stm_) {
      stm_.emplace(file_.get(), "stm", shape(S.stm), planned_samples_, check_);
      parameter_sensitivity_.emplace(file_.get(), "parameter_sensitivity", shape(S.parameters),
                                     planned_samples_, check_);
      for (Series* series : {&*stm_, &*parameter_sensitivity_}) {
        string_attribute(series->id(), "layout", S.coupled ? "dense" : "block_diagonal", check_);
        string_attribute(series->id(), "tangent",
                         "per body dp, dtheta, dv, domega (world axes; theta: R <- exp([dtheta]x) R); "
                         "body-major; docs/sensitivities.md",
                         check_);
      }
      string_attribute(parameter_sensitivity_->id(), "parameters",
                       S.of == SensitivityParameters::inertia ? "inertia (I1, I2, I3 of each body)"
                       : S.of == SensitivityParameters::mass
                           ? "mass"
                           : "forces (the force models' parameters, shared by every body: parameter_names)",
                       check_);
      std::string names;
      for (const std::string& n : S.parameter_names) names += (names.empty() ? "" : "\n") + n;
      string_attribute(parameter_sensitivity_->id(), "parameter_names", names, check_);
    }
    for (auto [series, M] : {std::pair{&*stm_, &S.stm}, std::pair{&*parameter_sensitivity_, &S.parameters}}) {
      row_.resize(static_cast<size_t>(M->size()));
      size_t k = 0;
      for (Eigen::Index i = 0; i < M->rows(); ++i)
        for (Eigen::Index j = 0; j < M->cols(); ++j) row_[k++] = (*M)(i, j);  // row-major
      series->append(row_.data());
    }
  }

 private:
  void write_names() {
    const Handle type = string_type();
    const hsize_t n = names_.size();
    const Handle space(check_(H5Screate_simple(1, &n, nullptr), "create a dataspace"), H5Sclose);
    const Handle props = untimed(H5P_DATASET_CREATE, "create dataset names", check_);
    const Handle set(check_(H5Dcreate2(file_.get(), "names", type.get(), space.get(), H5P_DEFAULT,
                                       props.get(), H5P_DEFAULT),
                            "create dataset names"),
                     H5Dclose);
    std::vector<const char*> p;
    for (const auto& s : names_) p.push_back(s.c_str());
    check_(H5Dwrite(set.get(), type.get(), H5S_ALL, H5S_ALL, H5P_DEFAULT, p.data()), "write names");
  }

  /// The group `events`: t (s), event (its name) and body (its row in `names`), one entry per crossing in
  /// time order; present, perhaps empty, whenever the run watched events.
  void write_events() {
    const Handle group_props = untimed(H5P_GROUP_CREATE, "create group events", check_);
    const Handle group(check_(H5Gcreate2(file_.get(), "events", H5P_DEFAULT, group_props.get(), H5P_DEFAULT),
                              "create group events"),
                       H5Gclose);
    const hsize_t n = event_times_.size();
    auto dataset = [&](const char* name, hid_t type, const void* data, const char* unit,
                       const char* meaning) {
      io::fixed_dataset(group.get(), name, type, {n}, data, check_);
      const Handle set(check_(H5Dopen2(group.get(), name, H5P_DEFAULT), "write events"), H5Dclose);
      if (unit != nullptr) string_attribute(set.get(), "unit", unit, check_);
      string_attribute(set.get(), "meaning", meaning, check_);
    };
    dataset("t", H5T_NATIVE_DOUBLE, event_times_.data(), "s", "time of the crossing");
    const Handle type = string_type();
    std::vector<const char*> names;
    for (const std::string& e : event_names_) names.push_back(e.c_str());
    dataset("event", type.get(), names.data(), nullptr, "the event's name ([[events]] name)");
    dataset("body", H5T_NATIVE_LLONG, event_rows_.data(), nullptr,
            "index in /names of the body or particle the event watches");
  }

  /// A fixed-size dataset `name` in `loc` of the given shape and native type, written from `data`.
  void dataset(hid_t loc, const char* name, hid_t type, const std::vector<hsize_t>& shape, const void* data) {
    io::fixed_dataset(loc, name, type, shape, data, check_);
  }

  /// The group `geometry`, for `tumble report`: per body (B of them) mass (B), center_of_mass (B, 3),
  /// principal_axes (B, 3, 3: columns are the axes), principal_moments (B, 3), all in the reference
  /// frame; the display meshes concatenated, vertices (V, 3) in m and triangles (F, 3) of indices into
  /// the body's own vertices, body i owning vertices [vertex_offsets[i], vertex_offsets[i+1]) and
  /// likewise triangles; springs (S, 2) rows of their ends (−1: a world anchor) and spring_points (S, 2, 3).
  void write_geometry(const SceneGeometry& g) {
    const Handle props = untimed(H5P_GROUP_CREATE, "create group geometry", check_);
    const Handle group(check_(H5Gcreate2(file_.get(), "geometry", H5P_DEFAULT, props.get(), H5P_DEFAULT),
                              "create group geometry"),
                       H5Gclose);
    const hsize_t B = g.bodies.size();
    std::vector<double> mass, com, U, Lambda, vertices;
    std::vector<std::uint64_t> vertex_offsets{0}, triangle_offsets{0};
    std::vector<std::uint32_t> triangles;
    for (const BodyGeometry& b : g.bodies) {
      mass.push_back(b.mass);
      com.insert(com.end(), {b.com.x(), b.com.y(), b.com.z()});
      for (int r = 0; r < 3; ++r) U.insert(U.end(), {b.U(r, 0), b.U(r, 1), b.U(r, 2)});
      Lambda.insert(Lambda.end(), {b.Lambda.x(), b.Lambda.y(), b.Lambda.z()});
      for (const Vec3& v : b.surface().vertices) vertices.insert(vertices.end(), {v.x(), v.y(), v.z()});
      for (const auto& t : b.surface().triangles) triangles.insert(triangles.end(), t.begin(), t.end());
      vertex_offsets.push_back(vertices.size() / 3);
      triangle_offsets.push_back(triangles.size() / 3);
    }
    dataset(group.get(), "mass", H5T_NATIVE_DOUBLE, {B}, mass.data());
    dataset(group.get(), "center_of_mass", H5T_NATIVE_DOUBLE, {B, 3}, com.data());
    dataset(group.get(), "principal_axes", H5T_NATIVE_DOUBLE, {B, 3, 3}, U.data());
    dataset(group.get(), "principal_moments", H5T_NATIVE_DOUBLE, {B, 3}, Lambda.data());
    dataset(group.get(), "vertex_offsets", H5T_NATIVE_UINT64, {B + 1}, vertex_offsets.data());
    dataset(group.get(), "triangle_offsets", H5T_NATIVE_UINT64, {B + 1}, triangle_offsets.data());
    dataset(group.get(), "vertices", H5T_NATIVE_DOUBLE, {vertices.size() / 3, 3}, vertices.data());
    dataset(group.get(), "triangles", H5T_NATIVE_UINT32, {triangles.size() / 3, 3}, triangles.data());
    std::vector<long long> ends;
    std::vector<double> points;
    for (const SpringGeometry& s : g.springs) {
      ends.insert(ends.end(), {s.a, s.b});
      points.insert(points.end(), {s.point_a.x(), s.point_a.y(), s.point_a.z(), s.point_b.x(), s.point_b.y(),
                                   s.point_b.z()});
    }
    dataset(group.get(), "springs", H5T_NATIVE_LLONG, {g.springs.size(), 2}, ends.data());
    dataset(group.get(), "spring_points", H5T_NATIVE_DOUBLE, {g.springs.size(), 2, 3}, points.data());
  }

  /// Which diagnostics exist is fixed by the model and the state at t = 0: create those datasets.
  void create_diagnostics(const DriftSample& d) {
    double values[3];
    for (const SystemField& f : system_fields()) {
      std::optional<Series>& series = diagnostic_series_.emplace_back();
      if (!f.of_sample(d, values)) continue;
      const std::vector<hsize_t> shape = f.width == 1 ? std::vector<hsize_t>{}
                                                      : std::vector<hsize_t>{static_cast<hsize_t>(f.width)};
      series.emplace(diagnostics_.get(), std::string(f.name).c_str(), shape, planned_samples_, check_);
      describe(series->id(), f);
    }
    if (d.rotor_speed.empty()) return;
    const std::vector<hsize_t> shape{d.rotor_speed.size()};
    rotor_speed_.emplace(diagnostics_.get(), "rotor_speed", shape, planned_samples_, check_);
    string_attribute(rotor_speed_->id(), "unit", "rad/s", check_);
    string_attribute(rotor_speed_->id(), "meaning", "each rotor's spin relative to its body (rotor_names)",
                     check_);
    rotor_torque_.emplace(diagnostics_.get(), "rotor_torque", shape, planned_samples_, check_);
    string_attribute(rotor_torque_->id(), "unit", "N*m", check_);
    string_attribute(rotor_torque_->id(), "meaning",
                     "each rotor's motor torque, the one held until the sample (rotor_names)", check_);
    string_dataset(diagnostics_.get(), "rotor_names", rotor_names_, check_);
  }

  template <class Field>
  void describe(hid_t dataset, const Field& f) {
    string_attribute(dataset, "unit", std::string(f.unit), check_);
    if (!f.frame.empty()) string_attribute(dataset, "frame", std::string(f.frame), check_);
    string_attribute(dataset, "meaning", std::string(f.meaning), check_);
  }

  std::vector<Series*> all_series() {
    std::vector<Series*> out{&*t_};
    for (Series& s : field_series_) out.push_back(&s);
    for (auto& s : diagnostic_series_) {
      if (s) out.push_back(&*s);
    }
    if (stm_) out.insert(out.end(), {&*stm_, &*parameter_sensitivity_});
    if (rotor_speed_) out.insert(out.end(), {&*rotor_speed_, &*rotor_torque_});
    return out;
  }

  io::Hdf5DriverState driver_;  ///< outlives file_: its driver reports here until it is closed
  io::StagedFile staged_;
  Checker check_;
  std::vector<std::string> names_;
  Handle file_;
  Handle diagnostics_;
  std::vector<const BodyField*> fields_;
  std::optional<AngleUnwrapper> unwrap_;  // --unwrap-angles
  double planned_samples_;                // what the run's settings will write: sizes the chunks
  std::optional<Series> t_;
  std::vector<Series> field_series_;
  std::vector<std::optional<Series>> diagnostic_series_;  ///< one per SystemField, empty if undefined
  std::optional<Series> stm_, parameter_sensitivity_;     ///< when the run carries sensitivities
  std::optional<Series> rotor_speed_, rotor_torque_;      ///< when the model has rotors
  std::vector<std::string> rotor_names_;
  std::vector<double> row_;  // one field of every row
  std::vector<double> all_;  // every field of every row, row by row
  bool watch_events_ = false;
  std::vector<std::string> warnings_;
  std::vector<std::string> event_names_;
  std::vector<long long> event_rows_;
  std::vector<double> event_times_;
  double t_end_ = 0.0;
  long samples_ = 0;
};

}  // namespace

std::unique_ptr<TrajectoryWriter> make_hdf5_writer(const std::filesystem::path& path, const Model& model,
                                                   const TrajectoryInfo& info) {
  return std::make_unique<Hdf5Writer>(path, model, info);
}

}  // namespace tumble
