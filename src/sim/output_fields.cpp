#include "tumble/sim/output_fields.hpp"

#include <fmt/format.h>

#include <algorithm>

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
void reference_axis_angle(const ReferenceFrameState& r, double* out) {
  const AxisAngle a = axis_angle(r.orientation);
  put(a.axis, out);
  out[3] = a.angle;
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
     reference_euler_zyx},
    {"euler_zxz",
     3,
     {"phi", "theta", "psi"},
     "rad",
     "reference -> world",
     "R_ref = Rz(φ) Rx(θ) Rz(ψ) (3-1-3); φ, ψ in (−π, π], θ in [0, π]",
     via_reference<reference_euler_zxz>,
     [](const ParticleState&, double* out) { put(Vec3::Zero(), out); },
     reference_euler_zxz},
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

std::span<const SystemField> system_fields() { return kSystemFields; }

std::vector<std::string> row_names(const Model& model) {
  std::vector<std::string> names;
  names.reserve(model.bodies.size() + model.particles.size());
  prefer_huge_pages(names);
  for (const RigidBody& b : model.bodies) names.push_back(b.name());
  for (const Particle& p : model.particles) names.push_back(p.name);
  return names;
}

void field_of_row(const BodyField& field, const Model& model, const SystemState& state, size_t r,
                  double* out) {
  const size_t n = model.bodies.size();
  if (r < n) {
    field.of_body(model.bodies[r], state.bodies[r], out);
  } else {
    field.of_particle(state.particles[r - n], out);
  }
}

void fields_of_row(std::span<const BodyField* const> fields, const Model& model, const SystemState& state,
                   size_t r, double* out) {
  std::optional<ReferenceFrameState> reference;
  for (const BodyField* f : fields) {
    if (f->of_reference && r < model.bodies.size()) {
      if (!reference) reference = reference_state(model.bodies[r], state.bodies[r]);
      f->of_reference(*reference, out);
    } else {
      field_of_row(*f, model, state, r, out);
    }
    out += f->width;
  }
}

std::optional<std::pair<const BodyField*, int>> find_column(std::string_view column) {
  for (const BodyField& f : kBodyFields) {
    for (int k = 0; k < f.width; ++k) {
      if (f.columns[static_cast<size_t>(k)] == column) return std::pair{&f, k};
    }
  }
  return std::nullopt;
}

VariableColumn::VariableColumn(const BodyField& field, int component)
    : read_(field.name == "angular_velocity_principal" ? Read::omega_b
            : field.name == "com_position"             ? Read::com
                                                       : Read::state),
      field_(&field),
      k_(component) {}

double VariableColumn::converted(const RigidBody& body, const BodyColumns& x, size_t i, Formulation F) const {
  const auto k = static_cast<size_t>(k_);
  const Coordinates<double> c = x.load(i);
  if (read_ == Read::omega_b) return rotate_inverse<double>(c.q, c.omega)(k_);  // ^bω = Rᵀ ω
  double out[4];
  field_->of_body(body, to_state(F, c), out);
  return out[k];
}

}  // namespace tumble
