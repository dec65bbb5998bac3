#pragma once
// The rows of one output sample, shared by the trajectory writers: each body, then each particle (a
// frame at the particle with the identity orientation and no angular velocity), in model order. What
// a row holds is given by the output fields (sim/output_fields.hpp).
#include <string>
#include <vector>

#include "tumble/forces/model.hpp"
#include "tumble/sim/output_fields.hpp"

namespace tumble::io {

inline std::vector<std::string> row_names(const Model& model) {
  std::vector<std::string> names;
  for (const RigidBody& b : model.bodies) names.push_back(b.name());
  for (const Particle& p : model.particles) names.push_back(p.name);
  return names;
}

/// The `field.width` values of a field for row r of a sample.
inline void field_values(const BodyField& field, const Model& model, const SystemState& state, size_t r,
                         double* out) {
  const size_t n = model.bodies.size();
  if (r < n) {
    field.of_body(model.bodies[r], state.bodies[r], out);
  } else {
    field.of_particle(state.particles[r - n], out);
  }
}

}  // namespace tumble::io
