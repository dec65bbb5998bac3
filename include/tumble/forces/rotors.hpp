#pragma once
// Spinning rotors carried by bodies (reaction and momentum wheels, a dual-spin platform's rotor): a
// gyrostat (issue 26; docs/NOTATION.md, "Rotors"). In the carrying body's principal axes {b}, with I = Λ
// the whole body's inertia (the rotors' mass and inertia, as if locked, are part of the body, as any
// part is), a_j the unit spin axis, J_j the rotor's axial moment, Ω_j its spin relative to the body and
// u_j its motor torque:
//   h = Σ J_j Ω_j a_j                       the rotors' angular momentum relative to the body,
//   J_j Ω̇_j = u_j                           (u_j: the rate of the relative angular momentum),
//   Λ ω̇ = τ − ω × (Λ ω + h) − ḣ,  ḣ = Σ u_j a_j.
// Derivation: the angular momentum about the centre of mass is L = R (Λ ω + h) (the locked body plus
// each rotor's spin relative to it). Euler's law in world axes, dL/dt = τ_w, written in the rotating
// frame {b} (d/dt R x = R (ẋ + ω × x)), gives Λ ω̇ + ḣ + ω × (Λ ω + h) = τ_b. So the rotors act on the
// body as the internal torque τ_rotors = −ω × h − ḣ, which is how this model applies them (in world
// axes: −ω_w × R h − R ḣ): every integrator then carries them. Without external torque L is conserved
// whatever the motors do; the body's ½ ωᵀ Λ ω is conserved only while every u_j = 0 (then h is
// constant: the classical gyrostat).
//
// Each motor torque is a constant (zero holds the relative speed), so Ω_j(t) = Ω_j(0) + u_j t/J_j
// exactly, until a speed limit stops the motor (u_j = 0 from then on, Ω_j = ±max_speed); or a table
// of times and torques, linear between them (an open-loop slew: a jump would cost every integrator
// its order at the step that holds it, a ramp whose corners fall on step ends costs nothing),
// Ω_j(t) = Ω_j(0) + (1/J_j) ∫₀ᵗ u_j; or set by a controller (RotorController), a function of the
// state and the speeds sampled every `interval` and held between samples — a zero-order hold, as flight
// software commands wheels at its task rate. The speeds are then the run's state, carried from sample to
// sample (Ω_j = Ω_j(t_k) + u_j (t − t_k)/J_j after sample k); the time loop ends steps at the samples
// (ForceModel::input_interval), so within a step every law here is a polynomial in t and the integrators
// keep their order.
#include <functional>
#include <limits>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "tumble/forces/force_model.hpp"
#include "tumble/forces/model.hpp"

namespace tumble {

/// One rotor as a scene describes it.
struct Rotor {
  std::string name;
  size_t body = 0;            ///< the carrying body's index
  Vec3 axis = Vec3::UnitX();  ///< unit spin axis in the body's reference frame
  double moment = 0.0;        ///< J, the axial moment (kg·m²), > 0
  double speed = 0.0;         ///< Ω(0), spin relative to the body (rad/s)
  double torque = 0.0;        ///< u, the motor torque (N·m), constant
  double max_speed = 0.0;     ///< |Ω| at which the motor stops (rad/s); 0: no limit
  double max_torque = 0.0;    ///< |u| the motor can give (N·m): a controller's command is clipped to it;
                              ///< 0: no limit
  /// (t, u) rows, t increasing: u linear between rows, held before the first and after the last (then
  /// `torque` is not used, and there is no speed limit).
  std::vector<std::pair<double, double>> torque_table;
};

/// A controller of every rotor's motor: sampled every `interval` seconds from the run's start, its
/// torques held until the next sample (zero-order hold).
struct RotorController {
  double interval = 0.0;  ///< s, > 0
  /// Writes the motor torques u (N·m, one per rotor in scene order: Rotors::rotors()) from the system's
  /// state at view.t and the rotors' speeds Ω relative to their bodies there (rad/s, the same order).
  /// `torques` holds the torques of the sample before (the scene's at the first).
  std::function<void(const SystemView& view, std::span<const double> speeds, std::span<double> torques)> law;
};

/// The rotors of a system, as the internal torque they exert on their bodies.
class Rotors final : public LocalForceModel {
 public:
  /// `rotors` refer to bodies of `bodies` (their axes turned into the principal frames here).
  /// Throws InvalidArgument for a non-unit axis, J ≤ 0, a speed or torque beyond its limit, a bad body
  /// index.
  Rotors(std::vector<Rotor> rotors, std::span<const RigidBody> bodies);
  /// These rotors with their torques set by `controller` (a new model: a scene's rotors stay as they
  /// are). Throws InvalidArgument for an interval that is not > 0 and finite, no law, or a rotor with a
  /// torque table (the controller sets every torque).
  std::shared_ptr<const Rotors> controlled_by(RotorController controller) const;

  /// Ω_j(t) and u_j(t) (zero once the speed limit is reached), j in scene order. With a controller, t
  /// within the current sample's interval.
  double speed(size_t j, double t) const;
  double motor_torque(size_t j, double t) const;
  /// h and ḣ of body i at time t, in its principal axes.
  std::pair<Vec3, Vec3> momentum(size_t body, double t) const;

  void accumulate_block(const BodyBlock& block, BlockLoads& loads) const override;
  void accumulate_tangent(const TangentView& view, std::span<WrenchT<TangentScalar>> loads) const override;
  std::string describe(std::span<const RigidBody> bodies) const override;
  void check(size_t n_bodies, size_t n_particles) const override;
  /// 0 while no motor works (the rotors store no energy of position, and the bodies' ½ ωᵀ Λ ω is then
  /// conserved: the energy stays defined), nullopt otherwise (the motors do work).
  std::optional<double> potential_energy(const SystemView& view) const override;
  /// Σ R h over the rotors' bodies: the angular momentum the diagnostics add to the bodies' Iω.
  Vec3 internal_angular_momentum(const SystemView& view) const override;
  /// The controller's interval (0 without one).
  double input_interval() const override { return controller_ ? controller_->interval : 0.0; }
  /// Calls the controller with the speeds at view.t and holds the torques it gives (clipped to
  /// max_torque; a motor at its speed limit that would pass it stays stopped). Throws Error naming the
  /// rotor and the time for a torque that is not finite.
  void sample_inputs(const SystemView& view) const override;
  /// The scene's speeds and torques again (as from t = 0).
  void restart_inputs() const override;
  /// Whether a motor torque is ever non-zero (then the bodies' kinetic energy is not conserved).
  bool motors_work() const;
  /// The rotors, in scene order.
  const std::vector<Rotor>& rotors() const { return rotors_; }

 private:
  /// Rotor j's motor from time t on: Ω(τ) = speed + torque (τ − t)/J until t_stop (its speed limit),
  /// then ±max_speed with the motor stopped. A constant torque is one piece from t = 0; a controller
  /// starts a new piece at each sample.
  struct Piece {
    double t = 0.0, speed = 0.0, torque = 0.0;
    double t_stop = std::numeric_limits<double>::infinity();
  };
  /// A body that carries rotors: its rotors by_body_[first, last), and their sums while every motor runs.
  struct Carrier {
    size_t body = 0, first = 0, last = 0;
    Vec3 h0 = Vec3::Zero();                                   ///< h(t) = h0 + ḣ t: Σ (J Ω_p − u t_p) a
    Vec3 h_dot = Vec3::Zero();                                ///< ḣ = Σ u a
    double t_stop = std::numeric_limits<double>::infinity();  ///< the first of its motors' stops
  };
  /// What the motors do now: set at construction and by sample_inputs (between steps only).
  struct Held {
    std::vector<Piece> pieces;  ///< scene order
    std::vector<Carrier> carriers;
    /// The carriers' h0 and ḣ as columns over every body of the model (zero where none): the pack
    /// kernel's data, valid while t < t_dense (every motor runs, no table).
    std::vector<double> h0[3], h_dot[3];
    double t_dense = std::numeric_limits<double>::infinity();
  };
  /// The piece of rotor j whose motor gives `torque` from time t at speed Ω (its speed limit's stop).
  Piece piece(size_t j, double t, double speed, double torque) const;
  /// Holds these pieces: the carriers' sums and columns from them.
  void hold(std::vector<Piece> pieces) const;
  std::pair<Vec3, Vec3> momentum(const Carrier& c, double t) const;
  /// each(carrier) for the carriers of bodies in [begin, end).
  template <class Each>
  void for_each_carrier(size_t begin, size_t end, Each&& each) const;

  std::vector<Rotor> rotors_;    ///< scene order
  std::vector<size_t> by_body_;  ///< rotor indices sorted by body (scene order within a body)
  std::vector<Vec3> axis_b_;     ///< each axis in its body's principal frame, Uᵀ a
  size_t n_bodies_ = 0;
  std::vector<Piece> initial_;  ///< the scene's pieces, from t = 0
  std::optional<RotorController> controller_;
  mutable Held held_;
};

/// The model's rotors (the one Rotors among its forces), or null.
const Rotors* rotors_of(const Model& model);

}  // namespace tumble
