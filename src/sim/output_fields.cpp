#include "tumble/sim/output_fields.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "tumble/dynamics/orbit_frame.hpp"
#include "tumble/error.hpp"
#include "tumble/math/huge_pages.hpp"
#include "tumble/math/rotations.hpp"

namespace tumble {
namespace {

void put(const Vec3& x, double* out) {
  out[0] = x.x();
  out[1] = x.y();
  out[2] = x.z();
}
void put(const Quat& q, double* out) {  // w first: the order of every tumble file
  out[0] = q.w();
  out[1] = q.x();
  out[2] = q.y();
  out[3] = q.z();
}

/// A field of the reference frame's state, for a body (BodyField::of_body).
template <void (*of_reference)(const ReferenceFrameState&, double*)>
void via_reference(const RigidBody& b, const BodyState& s, double* out) {
  of_reference(reference_state(b, s), out);
}
void reference_position(const ReferenceFrameState& r, double* out) { put(r.position, out); }
void reference_orientation(const ReferenceFrameState& r, double* out) { put(r.orientation, out); }
void reference_velocity(const ReferenceFrameState& r, double* out) { put(r.velocity, out); }
void reference_euler_zyx(const ReferenceFrameState& r, double* out) {
  put(euler_zyx(r.orientation.toRotationMatrix()), out);
}
void reference_euler_zxz(const ReferenceFrameState& r, double* out) {
  put(euler_zxz(r.orientation.toRotationMatrix()), out);
}
void reference_mrp(const ReferenceFrameState& r, double* out) { put(mrp(r.orientation), out); }

/// A field with no value at this state (field_of_row and fields_of_row say which row and when).
struct UndefinedField : Error {
  using Error::Error;
};
void reference_crp(const ReferenceFrameState& r, double* out) {
  const std::optional<Vec3> g = crp(r.orientation);
  if (!g) {
    throw UndefinedField(
        "output field 'crp': the attitude is a half turn, where the classical Rodrigues parameters are "
        "infinite; ask for 'mrp' (which switches to its shadow set there) or 'axis_angle'");
  }
  put(*g, out);
}
void reference_axis_angle(const ReferenceFrameState& r, double* out) {
  const AxisAngle a = axis_angle(r.orientation);
  put(a.axis, out);
  out[3] = a.angle;
}

// Relative to the orbit frame (orbit_frame.hpp): R_rel = R_lvlhᵀ R_ref (reference → LVLH), and the
// reference frame's angular velocity relative to LVLH in its own axes, R_refᵀ (ω − Ω_lvlh).
Quat relative_to_lvlh(const ReferenceFrameState& r, const Quat& lvlh) {
  return (lvlh.conjugate() * r.orientation).normalized();
}
void euler_zyx_relative(const ReferenceFrameState& r, const Quat& lvlh, const Vec3&, double* out) {
  put(euler_zyx(relative_to_lvlh(r, lvlh).toRotationMatrix()), out);
}
void mrp_relative(const ReferenceFrameState& r, const Quat& lvlh, const Vec3&, double* out) {
  put(mrp(relative_to_lvlh(r, lvlh)), out);
}
void angular_velocity_relative(const ReferenceFrameState& r, const Quat&, const Vec3& lvlh_omega,
                               double* out) {
  put(Vec3(rotate_inverse<double>(r.orientation, Vec3(r.omega_w - lvlh_omega))), out);
}

// The reference frame's pose: R_ref = R Uᵀ, p = o − R_ref c, v_p = v + ω × (p − o) (state.hpp).
constexpr BodyField kBodyFields[] = {
    {"position",
     3,
     {"px", "py", "pz"},
     "m",
     "world",
     "origin of the body's reference frame",
     via_reference<reference_position>,
     [](const ParticleState& p, double* out) { put(p.x, out); },
     reference_position},
    {"orientation",
     4,
     {"qw", "qx", "qy", "qz"},
     "1",
     "reference -> world",
     "unit quaternion (w, x, y, z) of the body's reference frame",
     via_reference<reference_orientation>,
     [](const ParticleState&, double* out) { put(Quat::Identity(), out); },
     reference_orientation},
    {"velocity",
     3,
     {"vx", "vy", "vz"},
     "m/s",
     "world",
     "velocity of the reference frame's origin",
     via_reference<reference_velocity>,
     [](const ParticleState& p, double* out) { put(p.v, out); },
     reference_velocity},
    {"angular_velocity",
     3,
     {"wx", "wy", "wz"},
     "rad/s",
     "world",
     "angular velocity ω",
     [](const RigidBody&, const BodyState& s, double* out) { put(s.omega_w, out); },
     [](const ParticleState&, double* out) { put(Vec3::Zero(), out); }},
    // Beyond the defaults: what users otherwise derive by hand (issue: outputs in the user's frames).
    {"com_position",
     3,
     {"com_x", "com_y", "com_z"},
     "m",
     "world",
     "centre of mass o",
     [](const RigidBody&, const BodyState& s, double* out) { put(s.o, out); },
     [](const ParticleState& p, double* out) { put(p.x, out); }},
    {"com_velocity",
     3,
     {"com_vx", "com_vy", "com_vz"},
     "m/s",
     "world",
     "velocity of the centre of mass",
     [](const RigidBody&, const BodyState& s, double* out) { put(s.v, out); },
     [](const ParticleState& p, double* out) { put(p.v, out); }},
    {"angular_velocity_reference",
     3,
     {"wx_ref", "wy_ref", "wz_ref"},
     "rad/s",
     "reference",
     "ω in the body's reference axes: R_refᵀ ω = U ^bω",
     [](const RigidBody& b, const BodyState& s, double* out) { put(Vec3(b.U() * s.omega_b()), out); },
     [](const ParticleState&, double* out) { put(Vec3::Zero(), out); }},
    {"angular_velocity_principal",
     3,
     {"w1", "w2", "w3"},
     "rad/s",
     "principal",
     "^bω = Rᵀ ω: components about the principal axes, moments λ₁ ≤ λ₂ ≤ λ₃",
     [](const RigidBody&, const BodyState& s, double* out) { put(s.omega_b(), out); },
     [](const ParticleState&, double* out) { put(Vec3::Zero(), out); }},
    {"orientation_principal",
     4,
     {"qbw", "qbx", "qby", "qbz"},
     "1",
     "principal -> world",
     "unit quaternion (w, x, y, z) of the principal frame {b}: R",
     [](const RigidBody&, const BodyState& s, double* out) { put(s.q, out); },
     [](const ParticleState&, double* out) { put(Quat::Identity(), out); }},
    {"euler_zyx",
     3,
     {"yaw", "pitch", "roll"},
     "rad",
     "reference -> world",
     "R_ref = Rz(yaw) Ry(pitch) Rx(roll); yaw, roll in (−π, π], pitch in [−π/2, π/2]",
     via_reference<reference_euler_zyx>,
     [](const ParticleState&, double* out) { put(Vec3::Zero(), out); },
     reference_euler_zyx,
     nullptr,
     true},
    {"euler_zxz",
     3,
     {"phi", "theta", "psi"},
     "rad",
     "reference -> world",
     "R_ref = Rz(φ) Rx(θ) Rz(ψ) (3-1-3); φ, ψ in (−π, π], θ in [0, π]",
     via_reference<reference_euler_zxz>,
     [](const ParticleState&, double* out) { put(Vec3::Zero(), out); },
     reference_euler_zxz,
     nullptr,
     true},
    {"axis_angle",
     4,
     {"axis_x", "axis_y", "axis_z", "angle"},
     "1, rad",
     "reference -> world",
     "R_ref = exp(angle [axis]×), angle in [0, π]; axis (1, 0, 0) at angle 0",
     via_reference<reference_axis_angle>,
     [](const ParticleState&, double* out) {
       put(Vec3::UnitX(), out);
       out[3] = 0.0;
     },
     reference_axis_angle},
    {"mrp",
     3,
     {"mrp1", "mrp2", "mrp3"},
     "1",
     "reference -> world",
     "modified Rodrigues parameters σ = tan(angle/4) axis of R_ref, |σ| ≤ 1: the shadow set −σ/|σ|² "
     "where |σ| would pass 1",
     via_reference<reference_mrp>,
     [](const ParticleState&, double* out) { put(Vec3::Zero(), out); },
     reference_mrp},
    {"crp",
     3,
     {"crp1", "crp2", "crp3"},
     "1",
     "reference -> world",
     "classical Rodrigues parameters g = tan(angle/2) axis of R_ref (the Gibbs vector); infinite at a half "
     "turn: a sample there stops the run with an error",
     via_reference<reference_crp>,
     [](const ParticleState&, double* out) { put(Vec3::Zero(), out); },
     reference_crp},
    // Relative to the orbit frame of the centre of mass about the central body (gravity_gradient).
    {"euler_zyx_lvlh",
     3,
     {"yaw_lvlh", "pitch_lvlh", "roll_lvlh"},
     "rad",
     "reference -> LVLH",
     "R_lvlhᵀ R_ref = Rz(yaw) Ry(pitch) Rx(roll): attitude relative to the orbit frame (LVLH: z to the "
     "central body, y opposite the orbit normal)",
     nullptr,
     nullptr,
     nullptr,
     euler_zyx_relative,
     true},
    {"mrp_lvlh",
     3,
     {"mrp1_lvlh", "mrp2_lvlh", "mrp3_lvlh"},
     "1",
     "reference -> LVLH",
     "modified Rodrigues parameters of R_lvlhᵀ R_ref, |σ| ≤ 1 (shadow set beyond)",
     nullptr,
     nullptr,
     nullptr,
     mrp_relative},
    {"angular_velocity_lvlh",
     3,
     {"wx_lvlh", "wy_lvlh", "wz_lvlh"},
     "rad/s",
     "reference",
     "angular velocity relative to the orbit frame, R_refᵀ (ω − Ω_lvlh), Ω_lvlh = (r × v)/|r|²",
     nullptr,
     nullptr,
     nullptr,
     angular_velocity_relative},
};
constexpr size_t kDefaultBodyFields = 4;

bool put_optional(const std::optional<double>& x, double* out) {
  if (x) *out = *x;
  return x.has_value();
}

// Momenta in world, L about the world origin; drifts relative to t = 0 (drift_monitor.hpp).
constexpr SystemField kSystemFields[] = {
    {"kinetic_energy",
     1,
     {"kinetic_energy"},
     "J",
     "",
     "Σ ½ m v² + ½ ωᵀ I ω",
     [](const DriftSample& d, double* out) {
       *out = d.invariants.kinetic_energy;
       return true;
     }},
    {"potential_energy",
     1,
     {"potential_energy"},
     "J",
     "",
     "sum of the force models' potentials (undefined if one has none)",
     [](const DriftSample& d, double* out) { return put_optional(d.invariants.potential_energy, out); }},
    {"total_energy",
     1,
     {"total_energy"},
     "J",
     "",
     "kinetic + potential",
     [](const DriftSample& d, double* out) { return put_optional(d.invariants.total_energy(), out); }},
    {"linear_momentum",
     3,
     {"px", "py", "pz"},
     "kg m/s",
     "world",
     "Σ m v",
     [](const DriftSample& d, double* out) {
       put(d.invariants.linear_momentum, out);
       return true;
     }},
    {"angular_momentum",
     3,
     {"Lx", "Ly", "Lz"},
     "kg m²/s",
     "world",
     "about the world origin: Σ (o × p + Iω)",
     [](const DriftSample& d, double* out) {
       put(d.invariants.angular_momentum, out);
       return true;
     }},
    {"energy_drift",
     1,
     {"energy_drift"},
     "1",
     "",
     "(E − E₀) / max(|E₀|, T₀)",
     [](const DriftSample& d, double* out) { return put_optional(d.energy_drift, out); }},
    {"linear_momentum_drift",
     1,
     {"linear_momentum_drift"},
     "1",
     "",
     "|p − p₀| / |p₀|",
     [](const DriftSample& d, double* out) { return put_optional(d.linear_momentum_drift, out); }},
    {"angular_momentum_drift",
     1,
     {"angular_momentum_drift"},
     "1",
     "",
     "|L − L₀| / |L₀|",
     [](const DriftSample& d, double* out) { return put_optional(d.angular_momentum_drift, out); }},
};

}  // namespace

std::span<const BodyField> body_fields() { return kBodyFields; }

std::vector<const BodyField*> default_body_fields() {
  std::vector<const BodyField*> out;
  for (size_t i = 0; i < kDefaultBodyFields; ++i) out.push_back(&kBodyFields[i]);
  return out;
}

std::vector<const BodyField*> body_fields(const std::vector<std::string>& names) {
  if (names.empty()) return default_body_fields();
  std::vector<const BodyField*> out;
  for (const std::string& name : names) {
    const auto* f = std::find_if(std::begin(kBodyFields), std::end(kBodyFields),
                                 [&](const BodyField& x) { return x.name == name; });
    if (f == std::end(kBodyFields)) {
      std::vector<std::string_view> known;
      for (const BodyField& x : kBodyFields) known.push_back(x.name);
      throw InvalidArgument(
          fmt::format("unknown output field '{}': the fields are {}", name, fmt::join(known, ", ")));
    }
    if (std::find(out.begin(), out.end(), f) != out.end()) {
      throw InvalidArgument(fmt::format("output field '{}' is listed twice: give each field once", name));
    }
    out.push_back(f);
  }
  return out;
}

std::optional<CentralBody> central_body(const Model& model) {
  std::optional<CentralBody> found;
  for (const auto& f : model.forces) {
    const std::optional<CentralBody> c = f->central_body();
    if (!c) continue;
    if (found && (found->center != c->center || found->mu != c->mu)) {
      throw InvalidArgument(
          fmt::format("the system has two central bodies (gravity_gradient at {} and at {}, or two μ's): "
                      "orbit frames and "
                      "orbits need one",
                      fmt::join(found->center, ", "), fmt::join(c->center, ", ")));
    }
    found = c;
  }
  return found;
}

std::vector<const BodyField*> body_fields(const std::vector<std::string>& names, const Model& model) {
  std::vector<const BodyField*> fields = body_fields(names);
  for (const BodyField* f : fields) {
    if (f->of_orbit && !central_body(model)) {
      throw InvalidArgument(fmt::format(
          "output field '{}' is relative to the orbit frame (LVLH) of each body about its central body, and "
          "the system has none: add a gravity_gradient force (the central body's gravity), or choose a field "
          "in world axes",
          f->name));
    }
  }
  return fields;
}

std::span<const SystemField> system_fields() { return kSystemFields; }

std::vector<std::string> row_names(const Model& model) {
  std::vector<std::string> names;
  names.reserve(model.bodies.size() + model.particles.size());
  prefer_huge_pages(names);
  for (const RigidBody& b : model.bodies) names.push_back(b.name());
  for (const Particle& p : model.particles) names.push_back(p.name);
  return names;
}

namespace {

/// Row r's reference frame: a body's, or a particle's (at it, the identity orientation, ω = 0).
ReferenceFrameState reference_of_row(const Model& model, const SystemState& state, size_t r) {
  const size_t n = model.bodies.size();
  if (r < n) return reference_state(model.bodies[r], state.bodies[r]);
  const ParticleState& p = state.particles[r - n];
  return {p.x, Quat::Identity(), p.v, Vec3::Zero()};
}

/// An orbit-frame field for row r, whose reference frame is `reference`: the LVLH frame of its centre of
/// mass about the central body.
void orbit_field(const BodyField& field, const Model& model, const SystemState& state, size_t r,
                 const ReferenceFrameState& reference, double* out) {
  const std::optional<CentralBody> c = central_body(model);
  if (!c) (void)body_fields({std::string(field.name)}, model);  // throws, saying why
  const size_t n = model.bodies.size();
  const Vec3 o = r < n ? state.bodies[r].o : state.particles[r - n].x;
  const Vec3 v = r < n ? state.bodies[r].v : state.particles[r - n].v;
  const Vec3 rel = o - c->center;
  const std::optional<Quat> lvlh = lvlh_orientation(rel, v);
  if (!lvlh) {
    throw Error(fmt::format(
        "output field '{}': '{}' has no orbit frame at t = {} s: its velocity relative to the central body "
        "is along its position, or zero (r × v = 0), so the orbit plane is undefined",
        field.name, r < n ? model.bodies[r].name() : model.particles[r - n].name, state.t));
  }
  field.of_orbit(reference, *lvlh, lvlh_angular_velocity(rel, v), out);
}

}  // namespace

namespace {
/// An UndefinedField's message with the row and the time.
[[noreturn]] void rethrow_with_row(const UndefinedField& e, const Model& model, const SystemState& state,
                                   size_t r) {
  const size_t n = model.bodies.size();
  throw Error(fmt::format("'{}' at t = {} s: {}",
                          r < n ? model.bodies[r].name() : model.particles[r - n].name, state.t, e.what()));
}
}  // namespace

void field_of_row(const BodyField& field, const Model& model, const SystemState& state, size_t r,
                  double* out) try {
  const size_t n = model.bodies.size();
  if (field.of_orbit) {
    orbit_field(field, model, state, r, reference_of_row(model, state, r), out);
  } else if (r < n) {
    field.of_body(model.bodies[r], state.bodies[r], out);
  } else {
    field.of_particle(state.particles[r - n], out);
  }
} catch (const UndefinedField& e) {
  rethrow_with_row(e, model, state, r);
}

void fields_of_row(std::span<const BodyField* const> fields, const Model& model, const SystemState& state,
                   size_t r, double* out) try {
  std::optional<ReferenceFrameState> reference;
  for (const BodyField* f : fields) {
    if ((f->of_reference && r < model.bodies.size()) || f->of_orbit) {
      if (!reference) reference = reference_of_row(model, state, r);
      if (f->of_orbit) {
        orbit_field(*f, model, state, r, *reference, out);
      } else {
        f->of_reference(*reference, out);
      }
    } else {
      field_of_row(*f, model, state, r, out);
    }
    out += f->width;
  }
} catch (const UndefinedField& e) {
  rethrow_with_row(e, model, state, r);
}

AngleUnwrapper::AngleUnwrapper(std::span<const BodyField* const> fields, size_t rows)
    : fields_(fields.begin(), fields.end()) {
  for (const BodyField* f : fields_) {
    first_.push_back(columns_);
    if (f->wraps) columns_ += static_cast<size_t>(f->width);
  }
  last_.assign(rows * columns_, std::numeric_limits<double>::quiet_NaN());
}

void AngleUnwrapper::field(size_t row, size_t k, double* values) {
  if (!fields_[k]->wraps) return;
  constexpr double turn = 2 * std::numbers::pi;
  double* last = &last_[row * columns_ + first_[k]];
  for (int c = 0; c < fields_[k]->width; ++c) {
    double& x = values[c];
    if (!std::isnan(last[c])) x += turn * std::nearbyint((last[c] - x) / turn);  // nearest the previous
    last[c] = x;
  }
}

void AngleUnwrapper::row(size_t row, double* values) {
  for (size_t k = 0; k < fields_.size(); values += fields_[k]->width, ++k) field(row, k, values);
}

std::optional<std::pair<const BodyField*, int>> find_column(std::string_view column) {
  for (const BodyField& f : kBodyFields) {
    for (int k = 0; k < f.width; ++k) {
      if (f.columns[static_cast<size_t>(k)] == column) return std::pair{&f, k};
    }
  }
  return std::nullopt;
}

namespace {
VariableColumn::Read read_of(const BodyField& field, int component) {
  if (field.of_orbit) {
    throw InvalidArgument(fmt::format(
        "the column '{}' is relative to the orbit frame: events and a study's extrema watch columns in world "
        "or body axes only (yaw, w1, ...)",
        field.columns[static_cast<size_t>(component)]));
  }
  if (field.name == "angular_velocity_principal") return VariableColumn::Read::omega_b;
  if (field.name == "com_position") return VariableColumn::Read::com;
  return VariableColumn::Read::state;
}
}  // namespace

VariableColumn::VariableColumn(const BodyField& field, int component)
    : read_(read_of(field, component)), field_(&field), k_(component) {}

double VariableColumn::converted(const RigidBody& body, const BodyColumns& x, size_t i, Formulation F) const {
  const auto k = static_cast<size_t>(k_);
  const Coordinates<double> c = x.load(i);
  if (read_ == Read::omega_b) return rotate_inverse<double>(c.q, c.omega)(k_);  // ^bω = Rᵀ ω
  double out[4];
  field_->of_body(body, to_state(F, c), out);
  return out[k];
}

}  // namespace tumble
