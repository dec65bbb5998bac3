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
// Here each motor torque is a constant (zero holds the relative speed), so Ω_j(t) = Ω_j(0) + u_j t/J_j
// exactly, until a speed limit stops the motor (u_j = 0 from then on, Ω_j = ±max_speed); or a table
// of times and torques, linear between them (an open-loop slew: a jump would cost every integrator
// its order at the step that holds it, a ramp whose corners fall on step ends costs nothing),
// Ω_j(t) = Ω_j(0) + (1/J_j) ∫₀ᵗ u_j: the rotors' state is a known function of time. A torque that depends on the state
// (a controller) would make Ω a variable of the run; that is not supported yet.
#include <limits>
#include <optional>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "tumble/forces/force_model.hpp"

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
  /// (t, u) rows, t increasing: u linear between rows, held before the first and after the last (then
  /// `torque` is not used, and there is no speed limit).
  std::vector<std::pair<double, double>> torque_table;
};

/// The rotors of a system, as the internal torque they exert on their bodies.
class Rotors final : public LocalForceModel {
 public:
  /// `rotors` refer to bodies of `bodies` (their axes turned into the principal frames here).
  /// Throws InvalidArgument for a non-unit axis, J ≤ 0, a speed beyond its limit, a bad body index.
  Rotors(std::vector<Rotor> rotors, std::span<const RigidBody> bodies);

  /// Ω_j(t) and u_j(t) (zero once the speed limit is reached).
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
  /// Whether a motor torque is ever non-zero (then the bodies' kinetic energy is not conserved).
  bool motors_work() const;
  /// The rotors, sorted by body (in scene order within a body).
  const std::vector<Rotor>& rotors() const { return rotors_; }

 private:
  /// A body that carries rotors: its rotors rotors_[first, last), and their sums while every motor runs.
  struct Carrier {
    size_t body = 0, first = 0, last = 0;
    Vec3 h0 = Vec3::Zero();                                   ///< h(0) = Σ J Ω(0) a
    Vec3 h_dot = Vec3::Zero();                                ///< ḣ = Σ u a
    double t_stop = std::numeric_limits<double>::infinity();  ///< the first of its motors' stops
  };
  std::pair<Vec3, Vec3> momentum(const Carrier& c, double t) const;
  /// each(carrier) for the carriers of bodies in [begin, end).
  template <class Each>
  void for_each_carrier(size_t begin, size_t end, Each&& each) const;

  std::vector<Rotor> rotors_;      ///< sorted by body
  std::vector<Vec3> axis_b_;       ///< each axis in its body's principal frame, Uᵀ a
  std::vector<double> t_stop_;     ///< when each motor reaches its speed limit (∞: never)
  std::vector<Carrier> carriers_;  ///< sorted by body
  /// The carriers' h(0) and ḣ as columns over every body of the model (zero where none): the pack
  /// kernel's data, valid while t < t_dense_ (every motor runs, no table).
  std::vector<double> h0_[3], h_dot_[3];
  double t_dense_ = std::numeric_limits<double>::infinity();
};

}  // namespace tumble
