#pragma once
// What is simulated: rigid bodies, particles and the force models acting on them, and their state.
#include <memory>
#include <string>
#include <vector>

#include "tumble/forces/force_model.hpp"

namespace tumble {

/// The state of everything in a Model at time t.
struct SystemState {
  double t = 0.0;
  std::vector<BodyState> bodies;
  std::vector<ParticleState> particles;
};

struct Model {
  std::vector<RigidBody> bodies;
  std::vector<Particle> particles;
  std::vector<std::shared_ptr<const ForceModel>> forces;

  size_t add_body(RigidBody body) {
    bodies.push_back(std::move(body));
    return bodies.size() - 1;
  }
  size_t add_particle(Particle particle) {
    particles.push_back(std::move(particle));
    return particles.size() - 1;
  }
  template <class F, class... Args>
  void add_force(Args&&... args) {
    forces.push_back(std::make_shared<const F>(std::forward<Args>(args)...));
  }
  /// Index of the body with this name; throws InvalidArgument listing the names there are.
  size_t body_index(const std::string& name) const;

  SystemView view(const SystemState& state) const {
    return SystemView{state.t, bodies, state.bodies, particles, state.particles};
  }
};

/// The loads of every force model, summed, at `state`.
Loads evaluate_loads(const Model& model, const SystemState& state);
/// Same, reusing `loads` (no allocation once sized).
void evaluate_loads(const Model& model, const SystemState& state, Loads& loads);

}  // namespace tumble
