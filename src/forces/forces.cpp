#include "tumble/forces/forces.hpp"

#include <fmt/format.h>

#include "tumble/dynamics/quantities.hpp"
#include "tumble/error.hpp"

namespace tumble {
namespace {

std::string vec(const Vec3& v) { return fmt::format("({}, {}, {})", v.x(), v.y(), v.z()); }
const char* frame_name(Frame f) { return f == Frame::world ? "world" : "body"; }

void check_body(size_t i, const SystemView& view, const char* model) {
  if (i >= view.bodies.size()) {
    throw InvalidArgument(fmt::format("{} refers to body #{}, but the model has {} bodies", model, i,
                                      view.bodies.size()));
  }
}

/// Calls f(i) for body `which`, or for every body when which == all_bodies.
template <class F>
void for_bodies(size_t which, const SystemView& view, const char* model, F&& f) {
  if (which == all_bodies) {
    for (size_t i = 0; i < view.bodies.size(); ++i) f(i);
  } else {
    check_body(which, view, model);
    f(which);
  }
}

std::string target(size_t body) { return body == all_bodies ? "all bodies" : fmt::format("body #{}", body); }

}  // namespace

void Loads::reset(size_t n_bodies, size_t n_particles) {
  bodies.assign(n_bodies, Wrench{});
  particles.assign(n_particles, Vec3::Zero());
}

void Loads::add_force_at(size_t i, const BodyState& s, const Vec3& f, const Vec3& x) {
  bodies[i].force += f;
  bodies[i].torque += (x - s.o).cross(f);  // τ = (x − o) × f (tutorial, section I)
}

// ---- gravity ----------------------------------------------------------------------------------

void UniformGravity::accumulate(const SystemView& view, Loads& loads) const {
  for (size_t i = 0; i < view.bodies.size(); ++i) loads.bodies[i].force += view.bodies[i].mass() * g_;
  for (size_t i = 0; i < view.particles.size(); ++i) loads.particles[i] += view.particles[i].mass * g_;
}
std::string UniformGravity::describe() const { return "uniform gravity " + vec(g_) + " m/s^2"; }
std::optional<double> UniformGravity::potential_energy(const SystemView& view) const {
  double V = 0;
  for (size_t i = 0; i < view.bodies.size(); ++i) V -= view.bodies[i].mass() * g_.dot(view.body_states[i].o);
  for (size_t i = 0; i < view.particles.size(); ++i) V -= view.particles[i].mass * g_.dot(view.particle_states[i].x);
  return V;
}

// ---- applied forces and torques ----------------------------------------------------------------

void PointForce::accumulate(const SystemView& view, Loads& loads) const {
  check_body(body_, view, "point force");
  const RigidBody& b = view.bodies[body_];
  const BodyState& s = view.body_states[body_];
  const ReferenceFrameState ref = reference_state(b, s);
  const Vec3 f = force_frame_ == Frame::world ? force_ : Vec3(ref.orientation * force_);
  const Vec3 x = point_frame_ == Frame::world ? point_ : point_position(b, s, point_);
  loads.add_force_at(body_, s, f, x);
}
std::string PointForce::describe() const {
  return fmt::format("force {} N ({} axes) at {} ({} point) on body #{}", vec(force_),
                     frame_name(force_frame_), vec(point_), frame_name(point_frame_), body_);
}

void PureTorque::accumulate(const SystemView& view, Loads& loads) const {
  check_body(body_, view, "torque");
  const Vec3 tau = frame_ == Frame::world
                       ? torque_
                       : Vec3(reference_state(view.bodies[body_], view.body_states[body_]).orientation * torque_);
  loads.bodies[body_].torque += tau;
}
std::string PureTorque::describe() const {
  return fmt::format("torque {} N*m ({} axes) on body #{}", vec(torque_), frame_name(frame_), body_);
}

// ---- dissipation ------------------------------------------------------------------------------

void ViscousDamping::accumulate(const SystemView& view, Loads& loads) const {
  for_bodies(body_, view, "damping", [&](size_t i) {
    loads.bodies[i].force -= linear_ * view.body_states[i].v;
    loads.bodies[i].torque -= angular_ * view.body_states[i].omega_w;
  });
  if (body_ == all_bodies) {
    for (size_t i = 0; i < view.particles.size(); ++i) loads.particles[i] -= linear_ * view.particle_states[i].v;
  }
}
std::string ViscousDamping::describe() const {
  return fmt::format("viscous damping {} N*s/m, {} N*m*s on {}", linear_, angular_, target(body_));
}

void QuadraticDrag::accumulate(const SystemView& view, Loads& loads) const {
  for_bodies(body_, view, "drag", [&](size_t i) {
    const Vec3& v = view.body_states[i].v;
    const Vec3& w = view.body_states[i].omega_w;
    loads.bodies[i].force -= linear_ * v.norm() * v;
    loads.bodies[i].torque -= angular_ * w.norm() * w;
  });
  if (body_ == all_bodies) {
    for (size_t i = 0; i < view.particles.size(); ++i) {
      const Vec3& v = view.particle_states[i].v;
      loads.particles[i] -= linear_ * v.norm() * v;
    }
  }
}
std::string QuadraticDrag::describe() const {
  return fmt::format("quadratic drag {} kg/m, {} kg*m^2 on {}", linear_, angular_, target(body_));
}

// ---- springs ----------------------------------------------------------------------------------

std::pair<Vec3, Vec3> Spring::end_state(const End& e, const SystemView& view) const {
  if (e.particle != all_bodies) {
    if (e.particle >= view.particles.size()) {
      throw InvalidArgument(fmt::format("spring refers to particle #{}, but the model has {} particles", e.particle,
                                        view.particles.size()));
    }
    return {view.particle_states[e.particle].x, view.particle_states[e.particle].v};
  }
  if (e.body == all_bodies) return {e.point, Vec3::Zero()};
  check_body(e.body, view, "spring");
  const RigidBody& b = view.bodies[e.body];
  const BodyState& s = view.body_states[e.body];
  return {point_position(b, s, e.point), point_velocity(b, s, e.point)};
}

void Spring::accumulate(const SystemView& view, Loads& loads) const {
  const auto [xa, va] = end_state(a_, view);
  const auto [xb, vb] = end_state(b_, view);
  const Vec3 d = xa - xb;
  const double len = d.norm();
  if (len == 0.0) return;  // direction undefined; a spring of zero length pulls nowhere
  const Vec3 n = d / len;
  const Vec3 f = -(k_ * (len - rest_) + c_ * (va - vb).dot(n)) * n;  // on end a
  auto apply = [&](const End& e, const Vec3& force, const Vec3& x) {
    if (e.particle != all_bodies) {
      loads.particles[e.particle] += force;
    } else if (e.body != all_bodies) {
      loads.add_force_at(e.body, view.body_states[e.body], force, x);
    }
  };
  apply(a_, f, xa);
  apply(b_, -f, xb);
}
std::string Spring::describe() const {
  return fmt::format("spring k={} N/m, rest length {} m, damping {} N*s/m", k_, rest_, c_);
}
std::optional<double> Spring::potential_energy(const SystemView& view) const {
  const double stretch = (end_state(a_, view).first - end_state(b_, view).first).norm() - rest_;
  return 0.5 * k_ * stretch * stretch;
}

// ---- gravity gradient -------------------------------------------------------------------------

void GravityGradient::accumulate(const SystemView& view, Loads& loads) const {
  for (size_t i = 0; i < view.bodies.size(); ++i) {
    const BodyState& s = view.body_states[i];
    const Vec3 r = s.o - center_;
    const double r2 = r.squaredNorm();
    const double r1 = std::sqrt(r2);
    const Mat3 I = inertia_world(view.bodies[i], s);
    const Vec3 Ir = I * r;
    // τ = 3μ/|r|⁵ r × (I r)
    loads.bodies[i].torque += 3.0 * mu_ / (r2 * r2 * r1) * r.cross(Ir);
    if (torque_only_) continue;
    // f = −∇V with V = −μm/r + μ/2 (3 rᵀIr/r⁵ − tr I/r³): the point-mass pull plus the small
    // correction of the same expansion, which makes the model exactly conservative with the torque.
    const double r5 = r2 * r2 * r1, r7 = r5 * r2;
    const Vec3 grad_V2 = 0.5 * mu_ * (3.0 * (2.0 * Ir / r5 - 5.0 * r.dot(Ir) * r / r7) + 3.0 * I.trace() * r / r5);
    loads.bodies[i].force -= mu_ * view.bodies[i].mass() / (r2 * r1) * r + grad_V2;
  }
}
std::string GravityGradient::describe() const {
  return fmt::format("central gravity mu={} m^3/s^2 at {}{}", mu_, vec(center_),
                     torque_only_ ? " (gradient torque only)" : " with gravity-gradient torque");
}
std::optional<double> GravityGradient::potential_energy(const SystemView& view) const {
  if (torque_only_) return std::nullopt;
  double V = 0;
  for (size_t i = 0; i < view.bodies.size(); ++i) {
    const BodyState& s = view.body_states[i];
    const Vec3 r = s.o - center_;
    const double rn = r.norm();
    const Vec3 u = r / rn;
    const Mat3 I = inertia_world(view.bodies[i], s);
    V += -mu_ * view.bodies[i].mass() / rn + mu_ / (2 * rn * rn * rn) * (3 * u.dot(I * u) - I.trace());
  }
  return V;
}

// ---- user callbacks ---------------------------------------------------------------------------

void BodyCallback::accumulate(const SystemView& view, Loads& loads) const {
  check_body(body_, view, "callback");
  const Wrench w = f_(view.t, view.bodies[body_], view.body_states[body_]);
  if (!w.force.allFinite() || !w.torque.allFinite()) {
    throw InvalidArgument(fmt::format("{} returned a non-finite wrench at t = {} s for body '{}'", label_,
                                      view.t, view.bodies[body_].name()));
  }
  loads.bodies[body_].force += w.force;
  loads.bodies[body_].torque += w.torque;
}

}  // namespace tumble
