#pragma once
// The rows of one output sample, shared by the trajectory writers: the pose and velocity of each
// body's reference frame (world), then each particle as a frame with the identity orientation and no
// angular velocity.
#include <string>
#include <vector>

#include "tumble/dynamics/state.hpp"
#include "tumble/forces/model.hpp"

namespace tumble::io {

inline std::vector<std::string> row_names(const Model& model) {
  std::vector<std::string> names;
  for (const RigidBody& b : model.bodies) names.push_back(b.name());
  for (const Particle& p : model.particles) names.push_back(p.name);
  return names;
}

inline void sample_rows(const Model& model, const SystemState& state,
                        std::vector<ReferenceFrameState>& rows) {
  rows.clear();
  for (size_t i = 0; i < model.bodies.size(); ++i)
    rows.push_back(reference_state(model.bodies[i], state.bodies[i]));
  for (const ParticleState& p : state.particles) {
    rows.push_back(ReferenceFrameState{p.x, Quat::Identity(), p.v, Vec3::Zero()});
  }
}

}  // namespace tumble::io
