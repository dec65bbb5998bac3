#pragma once
// A rigid body as the dynamics sees it: mass m, principal moments Λ, and where its principal frame {b}
// sits in the user's body reference frame (centre of mass c, principal rotation U: x_ref = c + U x_b).
#include <cmath>
#include <string>

#include "tumble/debug_assert.hpp"
#include "tumble/mass/mass_properties.hpp"

namespace tumble {

class RigidBody {
 public:
  /// From mass properties in the body reference frame (validated: throws InvalidMassProperties).
  static RigidBody from_mass_properties(const MassProperties& mp, std::string name = "body");
  /// From a mass and an inertia tensor about the centre of mass c, in reference-frame axes.
  static RigidBody from_inertia(double mass, const Mat3& inertia, const Vec3& center_of_mass = Vec3::Zero(),
                                std::string name = "body");
  /// From a mass and principal moments along the reference axes x, y, z (centre of mass at the origin).
  static RigidBody from_principal_moments(double mass, const Vec3& moments, std::string name = "body");

  const std::string& name() const { return name_; }
  double mass() const { return m_; }
  /// Principal moments λ₁ ≤ λ₂ ≤ λ₃ (kg·m²): the inertia tensor in {b}.
  const Vec3& Lambda() const { return Lambda_; }
  /// Centre of mass in the reference frame.
  const Vec3& center_of_mass() const { return c_; }
  /// Principal axes in the reference frame (columns), a proper rotation: x_ref = c + U x_b.
  const Mat3& U() const { return U_; }
  /// U as a unit quaternion, converted once: every conversion between the reference and the principal
  /// frame's pose needs it (for each body of each output row).
  const Quat& q_U() const { return q_U_; }
  /// The mass properties in the reference frame: I = U Λ Uᵀ about c.
  MassProperties mass_properties() const;

 private:
  RigidBody(std::string name, double m, const Vec3& Lambda, const Vec3& c, const Mat3& U)
      : name_(std::move(name)), m_(m), Lambda_(Lambda), c_(c), U_(U), q_U_(U) {
    // The factories validate the mass properties (InvalidMassProperties for bad input): what reaches
    // here is a positive mass, positive moments and a proper rotation, to rounding.
    TUMBLE_DEBUG_ASSERT(m > 0 && (Lambda.array() > 0).all(),
                        "a body's mass and principal moments are positive");
    TUMBLE_DEBUG_ASSERT((U.transpose() * U - Mat3::Identity()).cwiseAbs().maxCoeff() < 1e-12 &&
                            std::abs(U.determinant() - 1.0) < 1e-12,
                        "a body's principal axes U are a proper rotation");
  }
  std::string name_;
  double m_;
  Vec3 Lambda_;
  Vec3 c_;
  Mat3 U_;
  Quat q_U_;
};

}  // namespace tumble
