#pragma once
// The force models users apply. Indices refer to Model::bodies / Model::particles; points on a body are
// given in the body's reference frame (the user's axes), vectors in the Frame named beside them.
#include <functional>
#include <limits>

#include "tumble/forces/force_model.hpp"

namespace tumble {

/// Every body (or one) when a model may act on all of them.
inline constexpr size_t all_bodies = std::numeric_limits<size_t>::max();

/// Uniform gravity g (m/s²) on every body and particle: f = m g, potential −m g·x.
class UniformGravity final : public LocalForceModel {
 public:
  explicit UniformGravity(const Vec3& g) : g_(g) {}
  void accumulate_block(const BodyBlock& block, BlockLoads& loads) const override;
  void accumulate_tangent(const TangentView& view, std::span<WrenchT<TangentScalar>> loads) const override;
  std::vector<ForceParameter> parameters() const override;
  void accumulate_particles(const SystemView& view, std::span<Vec3> f) const override;
  bool needs_velocity() const override { return false; }
  std::optional<Vec3> uniform_acceleration() const override { return g_; }
  bool acts_alike_on_every_body() const override { return true; }
  std::string describe(std::span<const RigidBody> bodies) const override;
  std::optional<double> potential_energy(const SystemView& view) const override;

 private:
  Vec3 g_;
};

/// A constant force applied at a point: the force in world or body axes, the point body-fixed
/// (reference-frame coordinates, moving with the body) or fixed in the world. τ = (x − o) × f.
class PointForce final : public LocalForceModel {
 public:
  PointForce(size_t body, const Vec3& force, Frame force_frame, const Vec3& point, Frame point_frame)
      : body_(body), force_(force), force_frame_(force_frame), point_(point), point_frame_(point_frame) {}
  void accumulate_block(const BodyBlock& block, BlockLoads& loads) const override;
  void accumulate_tangent(const TangentView& view, std::span<WrenchT<TangentScalar>> loads) const override;
  std::vector<ForceParameter> parameters() const override;
  bool needs_velocity() const override { return false; }
  void check(size_t n_bodies, size_t n_particles) const override;
  std::string describe(std::span<const RigidBody> bodies) const override;

 private:
  size_t body_;
  Vec3 force_;
  Frame force_frame_;
  Vec3 point_;
  Frame point_frame_;
};

/// A pure torque (a couple), constant in world or body axes.
class PureTorque final : public LocalForceModel {
 public:
  PureTorque(size_t body, const Vec3& torque, Frame frame) : body_(body), torque_(torque), frame_(frame) {}
  void accumulate_block(const BodyBlock& block, BlockLoads& loads) const override;
  void accumulate_tangent(const TangentView& view, std::span<WrenchT<TangentScalar>> loads) const override;
  std::vector<ForceParameter> parameters() const override;
  bool needs_velocity() const override { return false; }
  void check(size_t n_bodies, size_t n_particles) const override;
  std::string describe(std::span<const RigidBody> bodies) const override;

 private:
  size_t body_;
  Vec3 torque_;
  Frame frame_;
};

/// Viscous damping: f = −c_v v, τ = −c_ω ω (world), on one body or all_bodies (and particles: f = −c_v v).
class ViscousDamping final : public LocalForceModel {
 public:
  ViscousDamping(size_t body, double linear, double angular)
      : body_(body), linear_(linear), angular_(angular) {}
  void accumulate_block(const BodyBlock& block, BlockLoads& loads) const override;
  void accumulate_tangent(const TangentView& view, std::span<WrenchT<TangentScalar>> loads) const override;
  std::vector<ForceParameter> parameters() const override;
  void accumulate_particles(const SystemView& view, std::span<Vec3> f) const override;
  void check(size_t n_bodies, size_t n_particles) const override;
  bool acts_alike_on_every_body() const override { return body_ == all_bodies; }
  std::string describe(std::span<const RigidBody> bodies) const override;

 private:
  size_t body_;
  double linear_, angular_;
};

/// Quadratic drag: f = −k_v |v| v, τ = −k_ω |ω| ω; k_v = ½ ρ_fluid C_d A.
class QuadraticDrag final : public LocalForceModel {
 public:
  QuadraticDrag(size_t body, double linear, double angular)
      : body_(body), linear_(linear), angular_(angular) {}
  void accumulate_block(const BodyBlock& block, BlockLoads& loads) const override;
  void accumulate_tangent(const TangentView& view, std::span<WrenchT<TangentScalar>> loads) const override;
  std::vector<ForceParameter> parameters() const override;
  void accumulate_particles(const SystemView& view, std::span<Vec3> f) const override;
  void check(size_t n_bodies, size_t n_particles) const override;
  bool acts_alike_on_every_body() const override { return body_ == all_bodies; }
  std::string describe(std::span<const RigidBody> bodies) const override;

 private:
  size_t body_;
  double linear_, angular_;
};

/// A linear spring–damper between any two of: a body point, a particle, a world anchor:
/// f = −(k(|d| − L₀) + c ḋ·d̂) d̂ on the first end (d from the second end to the first), the opposite
/// on the second. Potential ½k(|d| − L₀)².
class Spring final : public ForceModel {
 public:
  struct End {
    size_t body = all_bodies;      ///< a body index; all_bodies means a world anchor or a particle
    Vec3 point = Vec3::Zero();     ///< reference-frame coordinates on the body, or the world anchor
    size_t particle = all_bodies;  ///< a particle index (then body and point are not used)
  };
  Spring(End a, End b, double stiffness, double rest_length, double damping)
      : a_(a), b_(b), k_(stiffness), rest_(rest_length), c_(damping) {}
  void accumulate(const SystemView& view, Loads& loads) const override;
  void accumulate_tangent(const TangentView& view, std::span<WrenchT<TangentScalar>> loads) const override;
  std::vector<ForceParameter> parameters() const override;
  void check(size_t n_bodies, size_t n_particles) const override;
  std::string describe(std::span<const RigidBody> bodies) const override;
  std::optional<double> potential_energy(const SystemView& view) const override;
  const End& a() const { return a_; }
  const End& b() const { return b_; }

 private:
  std::pair<Vec3, Vec3> end_state(const End& e, const SystemView& view) const;  // position, velocity
  End a_, b_;
  double k_, rest_, c_;
};

/// Point-mass gravity of a central body (μ = GM, m³/s²) at `center`, with the gravity-gradient torque
/// τ = 3μ/|r|⁵ r × (I r), r = o − center (spacecraft attitude). Unless `torque_only`, the force
/// −∇V is applied too, with the potential of the same second-order expansion,
/// V = −μm/|r| + μ/(2|r|³)(3 r̂ᵀI r̂ − tr I): the point-mass pull −μ m r/|r|³ plus a correction of
/// relative size I/(m r²), so that energy is conserved exactly by the model.
class GravityGradient final : public LocalForceModel {
 public:
  GravityGradient(double mu, const Vec3& center, bool torque_only = false)
      : mu_(mu), center_(center), torque_only_(torque_only) {}
  void accumulate_block(const BodyBlock& block, BlockLoads& loads) const override;
  void accumulate_tangent(const TangentView& view, std::span<WrenchT<TangentScalar>> loads) const override;
  std::vector<ForceParameter> parameters() const override;
  bool needs_velocity() const override { return false; }
  bool acts_alike_on_every_body() const override { return true; }
  std::string describe(std::span<const RigidBody> bodies) const override;
  std::optional<double> potential_energy(const SystemView& view) const override;
  std::optional<CentralBody> central_body() const override { return CentralBody{center_, mu_}; }

 private:
  double mu_;
  Vec3 center_;
  bool torque_only_;
};

/// A user function of time and state returning the wrench on one body (world axes, torque about the
/// centre of mass). Called at every right-hand-side evaluation, so it must be smooth in t for
/// higher-order integrators to keep their order.
class BodyCallback final : public LocalForceModel {
 public:
  using Function = std::function<Wrench(double t, const RigidBody& body, const BodyState& state)>;
  BodyCallback(size_t body, Function f, std::string label = "callback")
      : body_(body), f_(std::move(f)), label_(std::move(label)) {}
  void accumulate_block(const BodyBlock& block, BlockLoads& loads) const override;
  void check(size_t n_bodies, size_t n_particles) const override;
  std::string describe(std::span<const RigidBody>) const override { return label_; }

 private:
  size_t body_;
  Function f_;
  std::string label_;
};

/// A user function that loads a whole block of bodies at once, given their world quantities as columns
/// (BodyBlock, BlockLoads): the fast way to apply a custom force law to many bodies (thrust laws, fluid
/// forces, controllers), called once per block and right-hand-side evaluation, never once per body.
/// It must add to `loads` only; blocks may be evaluated in parallel, so it must not write shared state.
class BlockCallback final : public LocalForceModel {
 public:
  using Function = std::function<void(const BodyBlock& block, BlockLoads& loads)>;
  BlockCallback(Function f, std::string label = "block callback", bool needs_velocity = true)
      : f_(std::move(f)), label_(std::move(label)), needs_velocity_(needs_velocity) {}
  void accumulate_block(const BodyBlock& block, BlockLoads& loads) const override { f_(block, loads); }
  bool needs_velocity() const override { return needs_velocity_; }
  std::string describe(std::span<const RigidBody>) const override { return label_; }

 private:
  Function f_;
  std::string label_;
  bool needs_velocity_;
};

}  // namespace tumble
