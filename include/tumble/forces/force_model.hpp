#pragma once
// Forces and torques. Every force model adds its contribution to one wrench per body (force in world,
// torque about the body's centre of mass in world) and one force per particle; the integrators sum
// them once per right-hand-side evaluation.
//
// Two kinds of model:
//  - local models (LocalForceModel: gravity, central gravity, damping, drag, applied forces and
//    torques, callbacks): the load on a body depends on that body's own state only. The engine hands
//    them the bodies block by block as columns (BodyBlock), so they run over many bodies at once, in
//    parallel, without gathering anything;
//  - system models (springs between bodies, and any model a user writes on ForceModel directly): they
//    see the whole system as per-body structs (SystemView) and may read and load any body or particle.
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "tumble/dynamics/particle.hpp"
#include "tumble/dynamics/state.hpp"
#include "tumble/dynamics/tangent.hpp"

namespace tumble {

/// Force and torque on a rigid body, world axes; the torque is about the centre of mass.
struct Wrench {
  Vec3 force = Vec3::Zero();   ///< N, world
  Vec3 torque = Vec3::Zero();  ///< N·m, world, about the centre of mass
};

/// What a system model can read: bodies, particles and their current states.
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
  std::vector<Vec3> particles;  ///< N, world

  void reset(size_t n_bodies, size_t n_particles);
  /// A force f applied at the world point x of body i: adds f and the moment (x − o) × f.
  void add_force_at(size_t i, const BodyState& s, const Vec3& f, const Vec3& x);
};

/// World quantities of the consecutive bodies begin … begin + count − 1 at time t, as columns indexed
/// by j = i − begin. v and omega_w are filled only when some model of the run needs_velocity().
struct BodyBlock {
  double t = 0.0;
  size_t begin = 0, count = 0;
  const RigidBody* bodies = nullptr;  ///< bodies[j]
  const double* m = nullptr;          ///< mass (kg)
  const double* Lambda[3] = {};       ///< principal moments (kg·m²)
  const double* o[3] = {};            ///< centre of mass, world (m)
  const double* q[4] = {};            ///< orientation of {b}, (w, x, y, z)
  const double* v[3] = {};            ///< velocity of the centre of mass, world (m/s)
  const double* omega_w[3] = {};      ///< angular velocity, world (rad/s)

  /// Body j as a struct (for models that treat one body at a time).
  BodyState state(size_t j) const;
  /// Whether global body index i is in this block.
  bool contains(size_t i) const { return i >= begin && i < begin + count; }
};

/// The loads of a block, columns indexed like BodyBlock: force (N) and torque about the centre of mass
/// (N·m), world axes.
struct BlockLoads {
  double* f[3] = {};
  double* tau[3] = {};

  void add(size_t j, const Vec3& force, const Vec3& torque) {
    for (int k = 0; k < 3; ++k) {
      f[k][j] += force(k);
      tau[k][j] += torque(k);
    }
  }
  /// A force applied at the world point x of body j, whose centre of mass is at o: f and (x − o) × f.
  void add_force_at(size_t j, const Vec3& o, const Vec3& force, const Vec3& x) {
    add(j, force, (x - o).cross(force));
  }
};

/// A body as the sensitivities see it (issue 25): its world state and its mass and principal moments,
/// all numbers of type T (TangentScalar: each carries its derivatives along the seeded directions, so a
/// load that depends on m or Λ differentiates with respect to them too).
template <class T>
struct BodyStateT {
  Vec3T<T> o;        ///< centre of mass, world
  QuatT<T> q;        ///< orientation of {b}
  Vec3T<T> v;        ///< velocity of the centre of mass, world
  Vec3T<T> omega_w;  ///< angular velocity, world
  T m;               ///< mass
  Vec3T<T> Lambda;   ///< principal moments
};
template <class T>
struct WrenchT {
  Vec3T<T> force = Vec3T<T>::Zero();   ///< world
  Vec3T<T> torque = Vec3T<T>::Zero();  ///< world, about the centre of mass
};

/// What a model differentiates: every body's state in dual numbers (ForceModel::accumulate_tangent).
struct TangentView {
  double t = 0.0;
  std::span<const RigidBody> bodies;  ///< their constant properties (centre of mass, principal axes, name)
  std::span<const BodyStateT<TangentScalar>> states;
  /// The model's own parameters() in dual numbers, in their order (seeded for ∂/∂p, issue 25).
  std::span<const TangentScalar> parameters;
};

/// The body a central gravity model pulls toward: its centre (world, m) and μ = GM (m³/s²).
struct CentralBody {
  Vec3 center = Vec3::Zero();
  double mu = 0.0;
};

/// A number a force model's law depends on (a component of g, a drag coefficient, a stiffness), for
/// sensitivities with respect to it: its name (unique within the model) and value.
struct ForceParameter {
  std::string name;
  double value = 0.0;
};

class ForceModel {
 public:
  virtual ~ForceModel() = default;
  /// Add this model's forces and torques at the state in `view` to `loads`.
  virtual void accumulate(const SystemView& view, Loads& loads) const = 0;
  /// One line for summaries and error messages; bodies are named from `bodies` (the model's).
  virtual std::string describe(std::span<const RigidBody> bodies) const = 0;
  /// The potential energy, for conservative models (gravity, springs); nullopt otherwise.
  virtual std::optional<double> potential_energy(const SystemView&) const { return std::nullopt; }
  /// Local models are evaluated block by block (LocalForceModel); the others on the whole system.
  virtual bool local() const { return false; }
  /// Whether the model reads velocities (the engine then forms world v and ω for it).
  virtual bool needs_velocity() const { return true; }
  /// For a uniform field: the acceleration g it gives every body and particle, as a force m g through
  /// each centre of mass (no torque about it). nullopt for every other model. The `exact` integrator
  /// and the drift monitor's advice ask it.
  virtual std::optional<Vec3> uniform_acceleration() const { return std::nullopt; }
  /// Angular momentum the model's own parts carry beyond the bodies' Iω (spinning rotors: Σ R h),
  /// world axes: the diagnostics add it to the system's L, which then stays conserved. Zero by default.
  virtual Vec3 internal_angular_momentum(const SystemView& /*view*/) const { return Vec3::Zero(); }
  /// Inputs sampled at a rate and held between samples (a controller's zero-order hold, as flight
  /// software commands its actuators at its task rate): the time between samples (s), 0 for a model
  /// without such inputs. simulate() then ends steps at t₀ + k·interval and calls sample_inputs there,
  /// so the loads are smooth within every step and each integrator keeps its order.
  virtual double input_interval() const { return 0.0; }
  /// Goes back to the inputs a run starts with (the scene's): called before a run (Run, simulate), so
  /// that a model can run again and its diagnostics at the start are the start's.
  virtual void restart_inputs() const {}
  /// Samples the inputs from the system's state, at its time, and holds them until the next call.
  /// Called by the time loop between steps only, never during one: with restart_inputs, the one moment a
  /// model changes, hence const.
  virtual void sample_inputs(const SystemView& /*view*/) const {}
  /// For central gravity: the central body (its centre, world, and μ = GM), which orbit frames (the
  /// LVLH output fields) and initial orbits are relative to. nullopt for every other model.
  virtual std::optional<CentralBody> central_body() const { return std::nullopt; }
  /// Whether the model treats every body by the same rule, whatever its index (uniform gravity, central
  /// gravity, damping of all bodies): runs stacked into one system (stack.hpp) then share it as it is.
  virtual bool acts_alike_on_every_body() const { return false; }
  /// Throws InvalidArgument when the model refers to a body or particle index the system does not
  /// have. Called once before a run, so that evaluations need not check.
  virtual void check(size_t /*n_bodies*/, size_t /*n_particles*/) const {}
  /// Add this model's loads at the states of `view`, in dual numbers, to `loads` (one per body): the
  /// same law as accumulate(), instantiated on TangentScalar, so sensitivities differentiate the loads
  /// a run applies. The default throws InvalidArgument naming the model: a user's function (callbacks)
  /// cannot be differentiated by tumble.
  virtual void accumulate_tangent(const TangentView& view, std::span<WrenchT<TangentScalar>> loads) const;
  /// The numbers of the law accumulate_tangent reads from TangentView::parameters, in that order (none
  /// by default): what sensitivities with respect to the force models differentiate.
  virtual std::vector<ForceParameter> parameters() const { return {}; }
};

/// A model whose load on each body depends only on that body's state. It is written once, over a
/// block of bodies in columns; `accumulate` on a SystemView runs the same code on one block gathered
/// from the structs.
class LocalForceModel : public ForceModel {
 public:
  /// Add the loads on the bodies of `block` to `loads` (same indices j).
  virtual void accumulate_block(const BodyBlock& block, BlockLoads& loads) const = 0;
  /// Add the loads on particles (default: none).
  virtual void accumulate_particles(const SystemView&, std::span<Vec3>) const {}

  void accumulate(const SystemView& view, Loads& loads) const final;
  bool local() const final { return true; }
};

}  // namespace tumble
