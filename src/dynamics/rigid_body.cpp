#include "tumble/dynamics/rigid_body.hpp"

#include "tumble/dynamics/state.hpp"
#include "tumble/error.hpp"

namespace tumble {

RigidBody RigidBody::from_mass_properties(const MassProperties& mp, std::string name) {
  const PrincipalAxes pa = [&] {
    try {
      return mp.validated_principal_axes();
    } catch (const InvalidMassProperties& e) {
      // Named here, not by validate()'s `what`: a scene makes 10^5 bodies and that string for each.
      throw InvalidMassProperties("body '" + name + "': " + e.what());
    }
  }();
  return RigidBody(std::move(name), mp.mass, pa.Lambda, mp.center_of_mass, pa.U);
}

RigidBody RigidBody::from_inertia(double mass, const Mat3& inertia, const Vec3& center_of_mass,
                                  std::string name) {
  return from_mass_properties(MassProperties{mass, center_of_mass, inertia, 0.0}, std::move(name));
}

RigidBody RigidBody::from_principal_moments(double mass, const Vec3& moments, std::string name) {
  return from_inertia(mass, moments.asDiagonal(), Vec3::Zero(), std::move(name));
}

MassProperties RigidBody::mass_properties() const {
  return MassProperties{m_, c_, U_ * Lambda_.asDiagonal() * U_.transpose(), 0.0};
}

BodyState state_from_reference(const RigidBody& body, const Vec3& position, const Quat& orientation,
                               const Vec3& velocity, const Vec3& omega, Frame omega_frame) {
  const Quat q_ref = orientation.normalized();
  BodyState s;
  s.o = position + q_ref * body.center_of_mass();
  s.q = (q_ref * body.q_U()).normalized();
  // ^rω = U ^bω: principal components are first taken into reference axes.
  const Vec3 omega_ref = omega_frame == Frame::principal ? Vec3(body.U() * omega) : omega;
  s.omega_w = omega_frame == Frame::world ? omega : Vec3(q_ref * omega_ref);
  s.v = velocity + s.omega_w.cross(s.o - position);
  return s;
}

ReferenceFrameState reference_state(const RigidBody& body, const BodyState& s) {
  ReferenceFrameState r;
  r.orientation = (s.q * body.q_U().conjugate()).normalized();
  r.position = s.o - r.orientation * body.center_of_mass();
  r.velocity = s.v + s.omega_w.cross(r.position - s.o);
  r.omega_w = s.omega_w;
  return r;
}

}  // namespace tumble
