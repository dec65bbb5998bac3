#pragma once
// The table of output fields: every quantity a trajectory holds, with its name, unit, frame and how
// it is computed. The CSV header, the HDF5 datasets and their attributes (and the Python arrays) are
// all made from these two tables, so a quantity is defined — and documented — in one place.
//
//  - BodyField: one vector per body (and per particle) per sample, e.g. the position of the body's
//    reference frame. CSV: one row per body, `width` columns per field. HDF5: a dataset (n, N, width).
//  - SystemField: one vector per sample for the whole system (the diagnostics), e.g. the total
//    angular momentum and its drift. It may be undefined (no potential, a zero scale at t = 0).
#include <array>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "tumble/dynamics/particle.hpp"
#include "tumble/dynamics/state.hpp"
#include "tumble/forces/model.hpp"
#include "tumble/integrate/system_coordinates.hpp"
#include "tumble/sim/drift_monitor.hpp"

namespace tumble {

struct BodyField {
  std::string_view name;                    ///< HDF5 dataset and Python array, e.g. "position"
  int width;                                ///< number of values (≤ 4)
  std::array<std::string_view, 4> columns;  ///< CSV column names, the first `width` used
  std::string_view unit;                    ///< SI, e.g. "m/s"; "1" for a dimensionless quantity
  std::string_view frame;                   ///< axes the vector is in, e.g. "world"
  std::string_view meaning;                 ///< one line for docs, --help and HDF5 attributes
  /// The value for a body from its constants and its state (centre of mass, principal frame, world);
  /// null for a field relative to the orbit frame (of_orbit).
  void (*of_body)(const RigidBody& body, const BodyState& state, double* out);
  /// The value for a particle: a frame at the particle with the identity orientation and ω = 0.
  void (*of_particle)(const ParticleState& state, double* out);
  /// For a field of the reference frame's state alone: of_body is this of reference_state(body, state),
  /// which a writer of several such fields computes once per row.
  void (*of_reference)(const ReferenceFrameState& reference, double* out) = nullptr;
  /// For a field relative to the orbit frame (LVLH, dynamics/orbit_frame.hpp): the value from the
  /// reference frame's state and the LVLH frame (its orientation, LVLH → world, and angular velocity,
  /// world) of the centre of mass's orbit about the system's central body. field_of_row finds them.
  void (*of_orbit)(const ReferenceFrameState& reference, const Quat& lvlh, const Vec3& lvlh_omega,
                   double* out) = nullptr;
  /// Angles that jump by 2π where they pass ±π (Euler angles): what AngleUnwrapper makes continuous.
  bool wraps = false;
};

struct SystemField {
  std::string_view name;                    ///< HDF5 dataset in /diagnostics, e.g. "angular_momentum"
  int width;                                ///< number of values (≤ 3)
  std::array<std::string_view, 3> columns;  ///< CSV column names
  std::string_view unit;
  std::string_view frame;
  std::string_view meaning;
  /// Writes the value and returns true, or returns false where the quantity is undefined.
  bool (*of_sample)(const DriftSample& sample, double* out);
};

/// Every per-body field, in the order the docs list them.
std::span<const BodyField> body_fields();
/// The fields written when none are chosen: position, orientation, velocity, angular_velocity (the
/// pose and velocity of each body's reference frame, world).
std::vector<const BodyField*> default_body_fields();
/// The fields with these names, in the order given; an empty list gives the defaults. Throws
/// InvalidArgument naming an unknown or repeated field and listing the known ones.
std::vector<const BodyField*> body_fields(const std::vector<std::string>& names);
/// The same for a run of `model`: also throws InvalidArgument for a field relative to the orbit frame
/// when the model has no central body (a gravity_gradient force) or more than one.
std::vector<const BodyField*> body_fields(const std::vector<std::string>& names, const Model& model);
/// The central body of the model's central gravity (ForceModel::central_body): nullopt without one;
/// InvalidArgument when two models give different ones.
std::optional<CentralBody> central_body(const Model& model);

/// The names of a sample's rows: each body, then each particle, in model order.
std::vector<std::string> row_names(const Model& model);
/// The `field.width` values of a field for row r of a sample (a body, or a particle after the bodies).
/// A field relative to the orbit frame throws Error where the row has none (r × v = 0 about the central
/// body), naming the row and the time; InvalidArgument when the model has no central body.
void field_of_row(const BodyField& field, const Model& model, const SystemState& state, size_t r,
                  double* out);
/// The values of every field of `fields` for row r, one after the other (the reference frame's state,
/// which several fields derive from, computed once).
void fields_of_row(std::span<const BodyField* const> fields, const Model& model, const SystemState& state,
                   size_t r, double* out);
/// The field and the component that a CSV column name stands for, e.g. "w2" → angular_velocity_principal,
/// 1; nullopt for a name no field has.
std::optional<std::pair<const BodyField*, int>> find_column(std::string_view column);

/// One column of a field (component k) for a body, read from its variables in the run's formulation:
/// what events watch at every step and studies take extrema of at every sample, so it must not cost a
/// conversion of the whole state. ω in principal axes (w1, w2, w3) is the mixed and body formulations'
/// own ω, the centre of mass (com_x, …) their o: read as they are (not rotated to the world and back:
/// within rounding of the CSV's column, which is computed from the world state); any other column from
/// the body's state alone, as the CSV computes it.
class VariableColumn {
 public:
  /// Throws InvalidArgument for a field relative to the orbit frame (it needs the model's central body).
  VariableColumn(const BodyField& field, int component);
  /// The value for `body`, row i of x.
  double operator()(const RigidBody& body, const BodyColumns& x, size_t i, Formulation formulation) const {
    const int c = variable(formulation);
    return c >= 0 ? x[static_cast<size_t>(c)][i] : converted(body, x, i, formulation);
  }
  /// The column of BodyColumns that holds the value as it is in `formulation`, or −1 where it must be
  /// computed from the body's variables.
  int variable(Formulation formulation) const {
    if (read_ == Read::com) return static_cast<int>(BodyColumns::o) + k_;
    if (read_ == Read::omega_b && formulation != Formulation::world)
      return static_cast<int>(BodyColumns::omega) + k_;
    return -1;
  }
  /// Where the value comes from: the variables' ω or o, or the converted state.
  enum class Read { omega_b, com, state };

 private:
  double converted(const RigidBody& body, const BodyColumns& x, size_t i, Formulation formulation) const;
  Read read_;
  const BodyField* field_;
  int k_;
};

/// Makes the angle fields (BodyField::wraps) of a trajectory continuous from sample to sample, on
/// request (`--unwrap-angles`), so that a spinning body's roll is not a sawtooth: each value moves by
/// the multiple of 2π that brings it nearest the same row's previous value of that column (as
/// numpy.unwrap). The result is the body's true angle only where it changes by less than π between
/// samples; the first sample is left as it is.
class AngleUnwrapper {
 public:
  AngleUnwrapper(std::span<const BodyField* const> fields, size_t rows);
  /// Field k's values for `row` (field k's width of them), in place.
  void field(size_t row, size_t k, double* values);
  /// Every field's values for `row`, one field after the other (fields_of_row's layout), in place.
  void row(size_t row, double* values);

 private:
  std::vector<const BodyField*> fields_;
  std::vector<size_t> first_;  ///< field k's first column among the wrapping ones
  size_t columns_ = 0;         ///< wrapping columns per row
  std::vector<double> last_;   ///< rows × columns_, NaN before the first sample
};

/// Every diagnostics field (energies, momenta, drifts), in the order they are written.
std::span<const SystemField> system_fields();

}  // namespace tumble
