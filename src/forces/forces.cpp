#include "tumble/forces/forces.hpp"

#include <fmt/format.h>

#include <tuple>
#include <type_traits>

#include "tumble/dynamics/quantities.hpp"
#include "tumble/error.hpp"

namespace tumble {
namespace {

std::string vec(const Vec3& v) { return fmt::format("({}, {}, {})", v.x(), v.y(), v.z()); }
const char* frame_name(Frame f) {
  return f == Frame::world ? "world" : f == Frame::principal ? "principal" : "reference";
}

/// A direction given in `frame` axes, in world axes: R_ref v (reference) or R v (principal).
Vec3 in_world(Frame frame, const Vec3& v, const RigidBody& b, const BodyState& s) {
  if (frame == Frame::world) return v;
  if (frame == Frame::principal) return s.q * v;
  return reference_state(b, s).orientation * v;
}
/// The same on dual numbers: R_ref v = R Uᵀ v.
Vec3T<TangentScalar> in_world(Frame frame, const Vec3T<TangentScalar>& v, const RigidBody& b,
                              const BodyStateT<TangentScalar>& s) {
  using T = TangentScalar;
  if (frame == Frame::world) return v;
  const Vec3T<T> principal = frame == Frame::principal ? v : Vec3T<T>(b.U().transpose().cast<T>() * v);
  return rotate<T>(s.q, principal);
}

/// Parameters k … k + 2 of a model as a vector (TangentView::parameters).
Vec3T<TangentScalar> parameter_vec(const TangentView& view, size_t k) {
  return {view.parameters[k], view.parameters[k + 1], view.parameters[k + 2]};
}
std::vector<ForceParameter> vector_parameters(const char* name, const Vec3& v) {
  const std::string n = name;
  return {{n + "_x", v.x()}, {n + "_y", v.y()}, {n + "_z", v.z()}};
}
/// World position of a body point given in `frame` coordinates (world: a fixed point; principal: about
/// the centre of mass; reference: the reference frame's point): x = o + R Uᵀ(r − c) for the latter.
Vec3T<TangentScalar> point_in_world(Frame frame, const Vec3& r, const RigidBody& b,
                                    const BodyStateT<TangentScalar>& s) {
  using T = TangentScalar;
  if (frame == Frame::world) return r.cast<T>();
  const Vec3 principal = frame == Frame::principal ? r : Vec3(b.U().transpose() * (r - b.center_of_mass()));
  return s.o + rotate<T>(s.q, principal.cast<T>());
}

/// The force of a spring–damper on its end a at xa (velocity va), the other end at xb (vb):
/// f = −(k(|d| − L₀) + c ḋ·d̂) d̂, d = xa − xb; zero at zero length (the direction is undefined: a spring
/// of zero length pulls nowhere).
template <class T>
Vec3T<T> spring_force(const T& k, const T& rest, const T& c, const Vec3T<T>& xa, const Vec3T<T>& xb,
                      const Vec3T<T>& va, const Vec3T<T>& vb) {
  using std::sqrt;
  const Vec3T<T> d = xa - xb;
  const T len = sqrt(d.squaredNorm());
  if (len == T(0.0)) return Vec3T<T>::Zero();
  const Vec3T<T> n = d / len;
  return -(k * (len - rest) + c * (va - vb).dot(n)) * n;
}

/// |u|, with the derivative 0 where u = 0 (where √ has none, and every law here multiplies |u| by u).
template <class T>
T magnitude(const Vec3T<T>& u) {
  if constexpr (std::is_same_v<T, double>) {
    return u.norm();
  } else {
    using std::sqrt;
    const T u2 = u.squaredNorm();
    return u2.v > 0 ? sqrt(u2) : T(0.0);
  }
}

/// Quadratic drag: f = −k_v |v| v, τ = −k_ω |ω| ω.
template <class T>
WrenchT<T> drag_law(const T& k_v, const T& k_omega, const Vec3T<T>& v, const Vec3T<T>& w) {
  return {Vec3T<T>(-k_v * magnitude<T>(v) * v), Vec3T<T>(-k_omega * magnitude<T>(w) * w)};
}

/// The gravity-gradient load of a point-mass field μ at `center` on a body at o with I = R Λ Rᵀ:
///   τ = 3μ/|r|⁵ r × (I r),  r = o − center,
/// and (unless torque_only) f = −∇V with V = −μm/r + μ/2 (3 rᵀIr/r⁵ − tr I/r³): the point-mass pull
/// plus the small correction of the same expansion, which makes the model exactly conservative with
/// the torque.
template <class T>
WrenchT<T> gravity_gradient_law(const T& mu, const Vec3& center, bool torque_only, const Vec3T<T>& o,
                                const QuatT<T>& q, const T& m, const Vec3T<T>& Lambda) {
  using std::sqrt;
  const Vec3T<T> r = o - center.cast<T>();
  const T r2 = r.squaredNorm();
  const T r1 = sqrt(r2);
  const Mat3T<T> R = q.toRotationMatrix();
  const Mat3T<T> I = R * Lambda.asDiagonal() * R.transpose();  // I = R Λ Rᵀ
  const Vec3T<T> Ir = I * r;
  WrenchT<T> w;
  w.torque = T(3.0) * mu / (r2 * r2 * r1) * r.cross(Ir);
  if (torque_only) return w;
  const T r5 = r2 * r2 * r1, r7 = r5 * r2;
  const Vec3T<T> grad_V2 =
      T(0.5) * mu * (T(3.0) * (T(2.0) * Ir / r5 - T(5.0) * r.dot(Ir) * r / r7) + T(3.0) * I.trace() * r / r5);
  w.force = -(mu * m / (r2 * r1) * r + grad_V2);
  return w;
}

void check_body(size_t i, size_t n_bodies, const char* model) {
  if (i != all_bodies && i >= n_bodies) {
    throw InvalidArgument(
        fmt::format("{} refers to body #{}, but the model has {} bodies", model, i, n_bodies));
  }
}

/// Calls f(j) for the bodies of the block that `which` selects: all of them, or body #which if it is
/// in the block.
template <class F>
void for_bodies(size_t which, const BodyBlock& block, F&& f) {
  if (which == all_bodies) {
    for (size_t j = 0; j < block.count; ++j) f(j);
  } else if (block.contains(which)) {
    f(which - block.begin);
  }
}

Vec3 column_vec(const double* const c[3], size_t j) { return {c[0][j], c[1][j], c[2][j]}; }

/// "body 'name'" (its index if the model has no such body: describe() may run before check()).
std::string body_label(std::span<const RigidBody> bodies, size_t body) {
  return body < bodies.size() ? fmt::format("body '{}'", bodies[body].name()) : fmt::format("body #{}", body);
}

std::string target(std::span<const RigidBody> bodies, size_t body) {
  return body == all_bodies ? "all bodies" : body_label(bodies, body);
}

}  // namespace

void ForceModel::accumulate_tangent(const TangentView& view, std::span<WrenchT<TangentScalar>>) const {
  throw InvalidArgument(fmt::format(
      "sensitivities: the force model '{}' cannot be differentiated (tumble differentiates its own force "
      "models; a user function's derivatives are unknown to it): run without sensitivities, or estimate "
      "them by finite differences (stm_by_central_differences)",
      describe(view.bodies)));
}

void Loads::reset(size_t n_bodies, size_t n_particles) {
  bodies.assign(n_bodies, Wrench{});
  particles.assign(n_particles, Vec3::Zero());
}

void Loads::add_force_at(size_t i, const BodyState& s, const Vec3& f, const Vec3& x) {
  bodies[i].force += f;
  bodies[i].torque += (x - s.o).cross(f);  // τ = (x − o) × f (tutorial, section I)
}

BodyState BodyBlock::state(size_t j) const {
  BodyState s;
  s.o = column_vec(o, j);
  s.q = Quat(q[0][j], q[1][j], q[2][j], q[3][j]);
  if (v[0]) s.v = column_vec(v, j);
  if (omega_w[0]) s.omega_w = column_vec(omega_w, j);
  return s;
}

void LocalForceModel::accumulate(const SystemView& view, Loads& loads) const {
  // The same code as the engine runs, on one block gathered from the structs.
  const size_t n = view.bodies.size();
  std::vector<double> columns(18 * n, 0.0);
  auto column = [&](size_t k) { return columns.data() + k * n; };
  std::vector<double> m(n);
  BodyBlock block;
  block.t = view.t;
  block.count = n;
  block.bodies = view.bodies.data();
  block.m = m.data();
  for (size_t k = 0; k < 3; ++k) {
    block.Lambda[k] = column(k);
    block.o[k] = column(3 + k);
    block.v[k] = column(10 + k);
    block.omega_w[k] = column(13 + k);
  }
  for (size_t k = 0; k < 4; ++k) block.q[k] = column(6 + k);
  for (size_t j = 0; j < n; ++j) {
    const RigidBody& b = view.bodies[j];
    const BodyState& s = view.body_states[j];
    m[j] = b.mass();
    const double q[4] = {s.q.w(), s.q.x(), s.q.y(), s.q.z()};
    for (size_t k = 0; k < 3; ++k) {
      column(k)[j] = b.Lambda()(static_cast<Eigen::Index>(k));
      column(3 + k)[j] = s.o(static_cast<Eigen::Index>(k));
      column(10 + k)[j] = s.v(static_cast<Eigen::Index>(k));
      column(13 + k)[j] = s.omega_w(static_cast<Eigen::Index>(k));
    }
    for (size_t k = 0; k < 4; ++k) column(6 + k)[j] = q[k];
  }
  std::vector<double> out(6 * n, 0.0);
  BlockLoads block_loads;
  for (size_t k = 0; k < 3; ++k) {
    block_loads.f[k] = out.data() + k * n;
    block_loads.tau[k] = out.data() + (3 + k) * n;
  }
  accumulate_block(block, block_loads);
  for (size_t j = 0; j < n; ++j) {
    for (Eigen::Index k = 0; k < 3; ++k) {
      loads.bodies[j].force(k) += block_loads.f[k][j];
      loads.bodies[j].torque(k) += block_loads.tau[k][j];
    }
  }
  accumulate_particles(view, loads.particles);
}

// ---- gravity ----------------------------------------------------------------------------------

void UniformGravity::accumulate_block(const BodyBlock& block, BlockLoads& loads) const {
  for (size_t k = 0; k < 3; ++k) {
    const double g = g_(static_cast<Eigen::Index>(k));
    for (size_t j = 0; j < block.count; ++j) loads.f[k][j] += block.m[j] * g;  // f = m g
  }
}
void UniformGravity::accumulate_tangent(const TangentView& view,
                                        std::span<WrenchT<TangentScalar>> loads) const {
  // f = m g, as accumulate_block's column loop (kept there for the engine's speed).
  const Vec3T<TangentScalar> g = parameter_vec(view, 0);
  for (size_t i = 0; i < view.states.size(); ++i) loads[i].force += view.states[i].m * g;
}
std::vector<ForceParameter> UniformGravity::parameters() const { return vector_parameters("g", g_); }
void UniformGravity::accumulate_particles(const SystemView& view, std::span<Vec3> f) const {
  for (size_t i = 0; i < view.particles.size(); ++i) f[i] += view.particles[i].mass * g_;
}
std::string UniformGravity::describe(std::span<const RigidBody>) const {
  return "uniform gravity " + vec(g_) + " m/s^2";
}
std::optional<double> UniformGravity::potential_energy(const SystemView& view) const {
  double V = 0;
  for (size_t i = 0; i < view.bodies.size(); ++i) V -= view.bodies[i].mass() * g_.dot(view.body_states[i].o);
  for (size_t i = 0; i < view.particles.size(); ++i)
    V -= view.particles[i].mass * g_.dot(view.particle_states[i].x);
  return V;
}

// ---- applied forces and torques ----------------------------------------------------------------

void PointForce::accumulate_block(const BodyBlock& block, BlockLoads& loads) const {
  if (!block.contains(body_)) return;
  const size_t j = body_ - block.begin;
  const RigidBody& b = block.bodies[j];
  const BodyState s = block.state(j);
  const Vec3 f = in_world(force_frame_, force_, b, s);
  // A body-fixed point: x_w = o + R x_b (principal coordinates, about the centre of mass) or the
  // reference frame's point.
  const Vec3 x = point_frame_ == Frame::world       ? point_
                 : point_frame_ == Frame::principal ? Vec3(s.o + s.q * point_)
                                                    : point_position(b, s, point_);
  loads.add_force_at(j, s.o, f, x);
}
void PointForce::accumulate_tangent(const TangentView& view, std::span<WrenchT<TangentScalar>> loads) const {
  const RigidBody& b = view.bodies[body_];
  const BodyStateT<TangentScalar>& s = view.states[body_];
  const Vec3T<TangentScalar> f = in_world(force_frame_, parameter_vec(view, 0), b, s);
  loads[body_].force += f;
  loads[body_].torque += (point_in_world(point_frame_, point_, b, s) - s.o).cross(f);  // τ = (x − o) × f
}
std::vector<ForceParameter> PointForce::parameters() const { return vector_parameters("f", force_); }
void PointForce::check(size_t n_bodies, size_t) const { check_body(body_, n_bodies, "point force"); }
std::string PointForce::describe(std::span<const RigidBody> bodies) const {
  return fmt::format("force {} N ({} axes) at {} ({} point) on {}", vec(force_), frame_name(force_frame_),
                     vec(point_), frame_name(point_frame_), body_label(bodies, body_));
}

void PureTorque::accumulate_block(const BodyBlock& block, BlockLoads& loads) const {
  if (!block.contains(body_)) return;
  const size_t j = body_ - block.begin;
  const Vec3 tau = in_world(frame_, torque_, block.bodies[j], block.state(j));
  loads.add(j, Vec3::Zero(), tau);
}
void PureTorque::accumulate_tangent(const TangentView& view, std::span<WrenchT<TangentScalar>> loads) const {
  loads[body_].torque += in_world(frame_, parameter_vec(view, 0), view.bodies[body_], view.states[body_]);
}
std::vector<ForceParameter> PureTorque::parameters() const { return vector_parameters("tau", torque_); }
void PureTorque::check(size_t n_bodies, size_t) const { check_body(body_, n_bodies, "torque"); }
std::string PureTorque::describe(std::span<const RigidBody> bodies) const {
  return fmt::format("torque {} N*m ({} axes) on {}", vec(torque_), frame_name(frame_),
                     body_label(bodies, body_));
}

// ---- dissipation ------------------------------------------------------------------------------

void ViscousDamping::accumulate_block(const BodyBlock& block, BlockLoads& loads) const {
  for_bodies(body_, block, [&](size_t j) {
    loads.add(j, -linear_ * column_vec(block.v, j), -angular_ * column_vec(block.omega_w, j));
  });
}
void ViscousDamping::accumulate_tangent(const TangentView& view,
                                        std::span<WrenchT<TangentScalar>> loads) const {
  for (size_t i = 0; i < view.states.size(); ++i) {
    if (body_ != all_bodies && body_ != i) continue;
    loads[i].force -= view.parameters[0] * view.states[i].v;
    loads[i].torque -= view.parameters[1] * view.states[i].omega_w;
  }
}
std::vector<ForceParameter> ViscousDamping::parameters() const {
  return {{"linear", linear_}, {"angular", angular_}};
}
void ViscousDamping::accumulate_particles(const SystemView& view, std::span<Vec3> f) const {
  if (body_ != all_bodies) return;
  for (size_t i = 0; i < view.particles.size(); ++i) f[i] -= linear_ * view.particle_states[i].v;
}
void ViscousDamping::check(size_t n_bodies, size_t) const { check_body(body_, n_bodies, "damping"); }
std::string ViscousDamping::describe(std::span<const RigidBody> bodies) const {
  return fmt::format("viscous damping {} N*s/m, {} N*m*s on {}", linear_, angular_, target(bodies, body_));
}

void QuadraticDrag::accumulate_block(const BodyBlock& block, BlockLoads& loads) const {
  for_bodies(body_, block, [&](size_t j) {
    const WrenchT<double> w =
        drag_law<double>(linear_, angular_, column_vec(block.v, j), column_vec(block.omega_w, j));
    loads.add(j, w.force, w.torque);
  });
}
void QuadraticDrag::accumulate_tangent(const TangentView& view,
                                       std::span<WrenchT<TangentScalar>> loads) const {
  for (size_t i = 0; i < view.states.size(); ++i) {
    if (body_ != all_bodies && body_ != i) continue;
    const WrenchT<TangentScalar> w = drag_law<TangentScalar>(view.parameters[0], view.parameters[1],
                                                             view.states[i].v, view.states[i].omega_w);
    loads[i].force += w.force;
    loads[i].torque += w.torque;
  }
}
std::vector<ForceParameter> QuadraticDrag::parameters() const {
  return {{"linear", linear_}, {"angular", angular_}};
}
void QuadraticDrag::accumulate_particles(const SystemView& view, std::span<Vec3> f) const {
  if (body_ != all_bodies) return;
  for (size_t i = 0; i < view.particles.size(); ++i) {
    const Vec3& v = view.particle_states[i].v;
    f[i] -= linear_ * v.norm() * v;
  }
}
void QuadraticDrag::check(size_t n_bodies, size_t) const { check_body(body_, n_bodies, "drag"); }
std::string QuadraticDrag::describe(std::span<const RigidBody> bodies) const {
  return fmt::format("quadratic drag {} kg/m, {} kg*m^2 on {}", linear_, angular_, target(bodies, body_));
}

// ---- springs ----------------------------------------------------------------------------------

void Spring::accumulate_tangent(const TangentView& view, std::span<WrenchT<TangentScalar>> loads) const {
  using T = TangentScalar;
  // The ends as the run sees them: a body point x = o + R Uᵀ(r − c), moving with v + ω × (x − o), or
  // a world anchor (particles are refused before: sensitivities are of rigid bodies).
  auto end = [&](const End& e) -> std::pair<Vec3T<T>, Vec3T<T>> {
    if (e.body == all_bodies) return {e.point.cast<T>(), Vec3T<T>::Zero()};
    const BodyStateT<T>& s = view.states[e.body];
    const Vec3T<T> x = point_in_world(Frame::reference, e.point, view.bodies[e.body], s);
    return {x, s.v + s.omega_w.cross(x - s.o)};
  };
  const auto [xa, va] = end(a_);
  const auto [xb, vb] = end(b_);
  const Vec3T<T> f =
      spring_force<T>(view.parameters[0], view.parameters[1], view.parameters[2], xa, xb, va, vb);
  for (const auto& [e, force, x] : {std::tuple{a_, f, xa}, std::tuple{b_, Vec3T<T>(-f), xb}}) {
    if (e.body == all_bodies) continue;
    loads[e.body].force += force;
    loads[e.body].torque += (x - view.states[e.body].o).cross(force);  // τ = (x − o) × f
  }
}

std::vector<ForceParameter> Spring::parameters() const {
  return {{"stiffness", k_}, {"rest_length", rest_}, {"damping", c_}};
}

std::pair<Vec3, Vec3> Spring::end_state(const End& e, const SystemView& view) const {
  if (e.particle != all_bodies) {
    return {view.particle_states[e.particle].x, view.particle_states[e.particle].v};
  }
  if (e.body == all_bodies) return {e.point, Vec3::Zero()};
  const RigidBody& b = view.bodies[e.body];
  const BodyState& s = view.body_states[e.body];
  return {point_position(b, s, e.point), point_velocity(b, s, e.point)};
}

void Spring::accumulate(const SystemView& view, Loads& loads) const {
  const auto [xa, va] = end_state(a_, view);
  const auto [xb, vb] = end_state(b_, view);
  const Vec3 f = spring_force<double>(k_, rest_, c_, xa, xb, va, vb);
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
void Spring::check(size_t n_bodies, size_t n_particles) const {
  for (const End& e : {a_, b_}) {
    if (e.particle != all_bodies && e.particle >= n_particles) {
      throw InvalidArgument(fmt::format("spring refers to particle #{}, but the model has {} particles",
                                        e.particle, n_particles));
    }
    if (e.particle == all_bodies) check_body(e.body, n_bodies, "spring");
  }
}
std::string Spring::describe(std::span<const RigidBody>) const {
  return fmt::format("spring k={} N/m, rest length {} m, damping {} N*s/m", k_, rest_, c_);
}
std::optional<double> Spring::potential_energy(const SystemView& view) const {
  const double stretch = (end_state(a_, view).first - end_state(b_, view).first).norm() - rest_;
  return 0.5 * k_ * stretch * stretch;
}

// ---- gravity gradient -------------------------------------------------------------------------

void GravityGradient::accumulate_block(const BodyBlock& block, BlockLoads& loads) const {
  for (size_t j = 0; j < block.count; ++j) {
    const Quat q(block.q[0][j], block.q[1][j], block.q[2][j], block.q[3][j]);
    const Vec3 Lambda(block.Lambda[0][j], block.Lambda[1][j], block.Lambda[2][j]);
    const WrenchT<double> w = gravity_gradient_law<double>(mu_, center_, torque_only_, column_vec(block.o, j),
                                                           q, block.m[j], Lambda);
    loads.add(j, w.force, w.torque);
  }
}
void GravityGradient::accumulate_tangent(const TangentView& view,
                                         std::span<WrenchT<TangentScalar>> loads) const {
  for (size_t i = 0; i < view.states.size(); ++i) {
    const BodyStateT<TangentScalar>& s = view.states[i];
    const WrenchT<TangentScalar> w = gravity_gradient_law<TangentScalar>(
        view.parameters[0], center_, torque_only_, s.o, s.q, s.m, s.Lambda);
    loads[i].force += w.force;
    loads[i].torque += w.torque;
  }
}
std::vector<ForceParameter> GravityGradient::parameters() const { return {{"mu", mu_}}; }
std::string GravityGradient::describe(std::span<const RigidBody>) const {
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

void BodyCallback::accumulate_block(const BodyBlock& block, BlockLoads& loads) const {
  if (!block.contains(body_)) return;
  const size_t j = body_ - block.begin;
  const Wrench w = f_(block.t, block.bodies[j], block.state(j));
  if (!w.force.allFinite() || !w.torque.allFinite()) {
    throw InvalidArgument(fmt::format("{} returned a non-finite wrench at t = {} s for body '{}'", label_,
                                      block.t, block.bodies[j].name()));
  }
  loads.add(j, w.force, w.torque);
}
void BodyCallback::check(size_t n_bodies, size_t) const { check_body(body_, n_bodies, "callback"); }

}  // namespace tumble
