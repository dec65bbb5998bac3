#pragma once
// The state of a rigid body and its conversions between frames.
//
// tumble integrates the centre of mass o and the orientation of the principal frame {b}: R maps body
// coordinates to world, x_w = o + R x_b (R = R(q), q unit). What a user sees is the pose of the *body
// reference frame* (the frame its mesh or data is written in): R_ref = R Uᵀ and p_ref = o − R_ref c.
#include "tumble/dynamics/rigid_body.hpp"
#include "tumble/math/quaternion.hpp"

namespace tumble {

/// Which axes a vector is given in (docs/NOTATION.md).
enum class Frame {
  world,             ///< {w}
  reference,         ///< the body's reference frame axes (the user's axes for the body)
  principal,         ///< the body's principal axes {b} (moments ascending)
  body = reference,  ///< the older name of `reference`
};

/// State of a rigid body, world quantities (the tutorial's {w} / {s}).
struct BodyState {
  Vec3 o = Vec3::Zero();        ///< centre of mass, world (m)
  Quat q = Quat::Identity();    ///< orientation of {b}: R = R(q), x_w = o + R x_b
  Vec3 v = Vec3::Zero();        ///< velocity of the centre of mass, world (m/s)
  Vec3 omega_w = Vec3::Zero();  ///< angular velocity ω, world (rad/s)

  Mat3 R() const { return q.toRotationMatrix(); }
  /// ^bω = Rᵀ ω (tutorial, section VI).
  Vec3 omega_b() const { return rotate_inverse<double>(q, omega_w); }  // Eigen's q̄ ω, bit for bit
};

/// Pose and velocity of the body reference frame, as a user describes a body.
struct ReferenceFrameState {
  Vec3 position = Vec3::Zero();         ///< origin of the reference frame, world (m)
  Quat orientation = Quat::Identity();  ///< reference frame → world
  Vec3 velocity = Vec3::Zero();         ///< velocity of that origin, world (m/s)
  Vec3 omega_w = Vec3::Zero();          ///< angular velocity, world (rad/s)
};

/// From the pose of the reference frame, the velocity of its origin and ω in `omega_frame` axes
/// (world, the reference frame's or the principal ones): o = p + R_ref c, R = R_ref U,
/// v = v_p + ω × (o − p).
BodyState state_from_reference(const RigidBody& body, const Vec3& position, const Quat& orientation,
                               const Vec3& velocity, const Vec3& omega, Frame omega_frame = Frame::world);

/// The pose and velocity of the body reference frame: R_ref = R Uᵀ, p = o − R_ref c, v_p = v + ω × (p − o).
ReferenceFrameState reference_state(const RigidBody& body, const BodyState& state);

}  // namespace tumble
