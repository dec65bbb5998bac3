#pragma once
// Forces and torques. Every force model adds its contribution to one wrench per body (force in world,
// torque about the body's centre of mass in world) and one force per particle; the integrators sum
// them once per right-hand-side evaluation.
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "tumble/dynamics/particle.hpp"
#include "tumble/dynamics/state.hpp"

namespace tumble {

/// Force and torque on a rigid body, world axes; the torque is about the centre of mass.
struct Wrench {
  Vec3 force = Vec3::Zero();
  Vec3 torque = Vec3::Zero();
};

/// What a force model can read: bodies, particles and their current states.
struct SystemView {
  double t = 0.0;
  std::span<const RigidBody> bodies;
  std::span<const BodyState> body_states;
  std::span<const Particle> particles;
  std::span<const ParticleState> particle_states;
};

/// What force models write: the summed loads.
struct Loads {
  std::vector<Wrench> bodies;
  std::vector<Vec3> particles;

  void reset(size_t n_bodies, size_t n_particles);
  /// A force f applied at the world point x of body i: adds f and the moment (x − o) × f.
  void add_force_at(size_t i, const BodyState& s, const Vec3& f, const Vec3& x);
};

class ForceModel {
 public:
  virtual ~ForceModel() = default;
  /// Add this model's forces and torques at the state in `view` to `loads`.
  virtual void accumulate(const SystemView& view, Loads& loads) const = 0;
  /// One line for summaries and error messages.
  virtual std::string describe() const = 0;
  /// The potential energy, for conservative models (gravity, springs); nullopt otherwise.
  virtual std::optional<double> potential_energy(const SystemView&) const { return std::nullopt; }
};

}  // namespace tumble
