#include "tumble/forces/rotors.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "tumble/error.hpp"
#include "tumble/math/simd.hpp"

namespace tumble {
namespace {

/// The rotors' torque on their body, world axes: −ω_w × R h − R ḣ (rotors.hpp), on double, packs of
/// bodies or dual numbers.
template <class T>
TUMBLE_INLINE Vec3T<T> rotor_torque(const QuatT<T>& q, const Vec3T<T>& omega_w, const Vec3T<T>& h_b,
                                    const Vec3T<T>& h_dot_b) {
  const Vec3T<T> h_w = rotate<T>(q, h_b);
  return -omega_w.cross(h_w) - rotate<T>(q, h_dot_b);
}

using Pack = xsimd::batch<double>;
constexpr size_t kWidth = Pack::size;

}  // namespace

Rotors::Rotors(std::vector<Rotor> rotors, std::span<const RigidBody> bodies)
    : rotors_(std::move(rotors)), n_bodies_(bodies.size()) {
  for (const Rotor& r : rotors_) {
    const std::string name = fmt::format("rotor '{}'", r.name);
    if (r.body >= bodies.size()) {
      throw InvalidArgument(
          fmt::format("{}: body index {} is out of range ({} bodies)", name, r.body, bodies.size()));
    }
    if (!(std::abs(r.axis.norm() - 1.0) <= 1e-6)) {
      throw InvalidArgument(fmt::format("{}: axis [{}] has length {:.6g}: give a unit vector", name,
                                        fmt::join(r.axis, ", "), r.axis.norm()));
    }
    if (!(r.moment > 0.0 && std::isfinite(r.moment))) {
      throw InvalidArgument(
          fmt::format("{}: moment = {} kg m^2: give the rotor's axial moment, > 0", name, r.moment));
    }
    if (!std::isfinite(r.speed) || !std::isfinite(r.torque) || !(r.max_speed >= 0.0) ||
        !std::isfinite(r.max_speed) || !(r.max_torque >= 0.0) || !std::isfinite(r.max_torque)) {
      throw InvalidArgument(
          fmt::format("{}: speed, torque, max_speed and max_torque must be finite (the limits >= 0)", name));
    }
    for (size_t k = 0; k < r.torque_table.size(); ++k) {
      const auto [t, u] = r.torque_table[k];
      if (!std::isfinite(t) || !std::isfinite(u) || (k > 0 && !(t > r.torque_table[k - 1].first))) {
        throw InvalidArgument(fmt::format(
            "{}: torque table row {} ({}, {}): give finite (t, u) rows with t increasing", name, k, t, u));
      }
      if (r.max_torque > 0.0 && std::abs(u) > r.max_torque) {
        throw InvalidArgument(fmt::format(
            "{}: torque table row {} asks {} N m, beyond its max_torque = {} N m", name, k, u, r.max_torque));
      }
    }
    if (!r.torque_table.empty() && r.max_speed > 0.0) {
      throw InvalidArgument(fmt::format(
          "{}: max_speed goes with a constant torque; a torque table sets the speeds itself", name));
    }
    if (r.max_speed > 0.0 && std::abs(r.speed) > r.max_speed) {
      throw InvalidArgument(
          fmt::format("{}: speed = {} rad/s is beyond its max_speed = {} rad/s", name, r.speed, r.max_speed));
    }
    if (r.max_torque > 0.0 && std::abs(r.torque) > r.max_torque) {
      throw InvalidArgument(
          fmt::format("{}: torque = {} N m is beyond its max_torque = {} N m", name, r.torque, r.max_torque));
    }
    // a_b = Uᵀ a: the axis in the principal frame (the reference frame's axes are R_ref = R Uᵀ).
    axis_b_.push_back((bodies[r.body].U().transpose() * r.axis.normalized()).eval());
  }
  // A body's rotors are one range of by_body_ (its Carrier), found by binary search.
  by_body_.resize(rotors_.size());
  for (size_t j = 0; j < rotors_.size(); ++j) by_body_[j] = j;
  std::stable_sort(by_body_.begin(), by_body_.end(),
                   [&](size_t a, size_t b) { return rotors_[a].body < rotors_[b].body; });
  for (size_t j = 0; j < rotors_.size(); ++j)
    initial_.push_back(piece(j, 0.0, rotors_[j].speed, rotors_[j].torque));
  hold(initial_);
}

Rotors::Piece Rotors::piece(size_t j, double t, double speed, double torque) const {
  const Rotor& r = rotors_[j];
  Piece p{t, speed, torque};
  // The motor runs until |Ω| reaches max_speed (then u = 0): Ω(τ) = Ω + u (τ − t)/J up to t_stop.
  if (torque != 0.0 && r.max_speed > 0.0) {
    p.t_stop = t + std::max(0.0, (std::copysign(r.max_speed, torque) - speed) * r.moment / torque);
  }
  return p;
}

void Rotors::hold(std::vector<Piece> pieces) const {
  // Each carrying body's rotors summed while every motor runs (O(1) a body), and the same sums as
  // columns over every body (zero where none), for the pack kernel. h(t) = Σ J (Ω_p + u (t − t_p)/J) a
  // = Σ (J Ω_p − u t_p) a + t Σ u a.
  Held& H = held_;
  H.pieces = std::move(pieces);
  H.carriers.clear();
  H.t_dense = std::numeric_limits<double>::infinity();
  for (int k = 0; k < 3; ++k) {
    H.h0[k].assign(n_bodies_, 0.0);
    H.h_dot[k].assign(n_bodies_, 0.0);
  }
  for (size_t s = 0; s < by_body_.size(); ++s) {
    const size_t j = by_body_[s];
    const Rotor& r = rotors_[j];
    const Piece& p = H.pieces[j];
    if (H.carriers.empty() || H.carriers.back().body != r.body) H.carriers.push_back({r.body, s, s});
    Carrier& c = H.carriers.back();
    c.last = s + 1;
    c.h0 += (r.moment * p.speed - p.torque * p.t) * axis_b_[j];
    c.h_dot += p.torque * axis_b_[j];
    // A table's torque changes with time: such a body's h is summed rotor by rotor, always.
    c.t_stop = r.torque_table.empty() ? std::min(c.t_stop, p.t_stop)
                                      : -std::numeric_limits<double>::infinity();
  }
  for (const Carrier& c : H.carriers) {
    for (int k = 0; k < 3; ++k) {
      H.h0[k][c.body] = c.h0(k);
      H.h_dot[k][c.body] = c.h_dot(k);
    }
    H.t_dense = std::min(H.t_dense, c.t_stop);
  }
}

std::shared_ptr<const Rotors> Rotors::controlled_by(RotorController controller) const {
  if (!(controller.interval > 0.0) || !std::isfinite(controller.interval)) {
    throw InvalidArgument(fmt::format(
        "rotor controller: interval = {} s; give the time between its samples, > 0", controller.interval));
  }
  if (!controller.law) throw InvalidArgument("rotor controller: it has no law (a function)");
  for (const Rotor& r : rotors_) {
    if (!r.torque_table.empty()) {
      throw InvalidArgument(fmt::format(
          "rotor '{}' has a torque table, but a controller sets every rotor's torque: remove the table",
          r.name));
    }
  }
  auto out = std::make_shared<Rotors>(*this);
  out->controller_ = std::move(controller);
  return out;
}

void Rotors::restart_inputs() const {
  if (controller_) hold(initial_);
}

void Rotors::sample_inputs(const SystemView& view) const {
  if (!controller_) return;
  const size_t n = rotors_.size();
  std::vector<double> speeds(n), torques(n);
  for (size_t j = 0; j < n; ++j) {
    speeds[j] = speed(j, view.t);
    torques[j] = held_.pieces[j].torque;
  }
  controller_->law(view, speeds, torques);
  std::vector<Piece> pieces(n);
  for (size_t j = 0; j < n; ++j) {
    const Rotor& r = rotors_[j];
    double u = torques[j];
    if (!std::isfinite(u)) {
      throw Error(
          fmt::format("rotor controller: the torque of rotor '{}' at t = {} s is {}: give finite torques",
                      r.name, view.t, u));
    }
    if (r.max_torque > 0.0) u = std::clamp(u, -r.max_torque, r.max_torque);  // the motor's saturation
    pieces[j] = piece(j, view.t, speeds[j], u);
  }
  hold(std::move(pieces));
}

namespace {

/// A torque table's u(t): linear between rows, held before the first and after the last.
double table_torque(const std::vector<std::pair<double, double>>& table, double t) {
  if (t <= table.front().first) return table.front().second;
  for (size_t k = 0; k + 1 < table.size(); ++k) {
    const auto [t0, u0] = table[k];
    const auto [t1, u1] = table[k + 1];
    if (t < t1) return u0 + (u1 - u0) * (t - t0) / (t1 - t0);
  }
  return table.back().second;
}

/// ∫₀ᵗ u for t ≥ 0: the trapezoid of each linear piece within [0, t] (exact for linear pieces).
double table_impulse(const std::vector<std::pair<double, double>>& table, double t) {
  const double inf = std::numeric_limits<double>::infinity();
  double impulse = 0.0;
  for (size_t k = 0; k <= table.size(); ++k) {  // pieces (−∞, t₀], [t₀, t₁], …, [t_n, ∞)
    const double lo = std::max(0.0, k == 0 ? -inf : table[k - 1].first);
    const double hi = std::min(t, k == table.size() ? inf : table[k].first);
    if (hi > lo) impulse += (hi - lo) * 0.5 * (table_torque(table, lo) + table_torque(table, hi));
  }
  return impulse;
}

}  // namespace

double Rotors::speed(size_t j, double t) const {
  const Rotor& r = rotors_[j];
  if (!r.torque_table.empty()) return r.speed + table_impulse(r.torque_table, t) / r.moment;
  const Piece& p = held_.pieces[j];
  return t < p.t_stop ? p.speed + p.torque * (t - p.t) / r.moment : std::copysign(r.max_speed, p.torque);
}
double Rotors::motor_torque(size_t j, double t) const {
  const Rotor& r = rotors_[j];
  if (!r.torque_table.empty()) return table_torque(r.torque_table, t);
  const Piece& p = held_.pieces[j];
  return t < p.t_stop ? p.torque : 0.0;
}

std::pair<Vec3, Vec3> Rotors::momentum(const Carrier& c, double t) const {
  if (t < c.t_stop) return {c.h0 + t * c.h_dot, c.h_dot};  // every motor runs: h = h0 + ḣ t
  Vec3 h = Vec3::Zero(), h_dot = Vec3::Zero();
  for (size_t s = c.first; s < c.last; ++s) {
    const size_t j = by_body_[s];
    h += rotors_[j].moment * speed(j, t) * axis_b_[j];  // h = Σ J Ω a
    h_dot += motor_torque(j, t) * axis_b_[j];           // ḣ = Σ u a
  }
  return {h, h_dot};
}

std::pair<Vec3, Vec3> Rotors::momentum(size_t body, double t) const {
  const auto c = std::lower_bound(held_.carriers.begin(), held_.carriers.end(), body,
                                  [](const Carrier& a, size_t b) { return a.body < b; });
  if (c == held_.carriers.end() || c->body != body) return {Vec3::Zero(), Vec3::Zero()};
  return momentum(*c, t);
}

template <class Each>
void Rotors::for_each_carrier(size_t begin, size_t end, Each&& each) const {
  auto c = std::lower_bound(held_.carriers.begin(), held_.carriers.end(), begin,
                            [](const Carrier& a, size_t b) { return a.body < b; });
  for (; c != held_.carriers.end() && c->body < end; ++c) each(*c);
}

void Rotors::accumulate_block(const BodyBlock& block, BlockLoads& loads) const {
  const Held& H = held_;
  if (block.t < held_.t_dense) {  // every motor runs (or none has a limit): h = h(0) + ḣ t, a pack at a time
    const Pack t(block.t);
    auto load = [](const double* p) { return Pack::load_unaligned(p); };
    size_t j = 0;
    for (; j + kWidth <= block.count; j += kWidth) {
      const size_t i = block.begin + j;
      const QuatT<Pack> q(load(block.q[0] + j), load(block.q[1] + j), load(block.q[2] + j),
                          load(block.q[3] + j));
      const Vec3T<Pack> omega_w(load(block.omega_w[0] + j), load(block.omega_w[1] + j),
                                load(block.omega_w[2] + j));
      const Vec3T<Pack> h_dot(load(&H.h_dot[0][i]), load(&H.h_dot[1][i]), load(&H.h_dot[2][i]));
      const Vec3T<Pack> h = Vec3T<Pack>(load(&H.h0[0][i]), load(&H.h0[1][i]), load(&H.h0[2][i])) + t * h_dot;
      const Vec3T<Pack> tau = rotor_torque<Pack>(q, omega_w, h, h_dot);  // 0 for a body without rotors
      for (int k = 0; k < 3; ++k) (load(loads.tau[k] + j) + tau(k)).store_unaligned(loads.tau[k] + j);
    }
    for (; j < block.count; ++j) {  // the last few bodies
      const size_t i = block.begin + j;
      const Quat q(block.q[0][j], block.q[1][j], block.q[2][j], block.q[3][j]);
      const Vec3 omega_w(block.omega_w[0][j], block.omega_w[1][j], block.omega_w[2][j]);
      const Vec3 h_dot(H.h_dot[0][i], H.h_dot[1][i], H.h_dot[2][i]);
      const Vec3 h = Vec3(H.h0[0][i], H.h0[1][i], H.h0[2][i]) + block.t * h_dot;
      loads.add(j, Vec3::Zero(), rotor_torque<double>(q, omega_w, h, h_dot));
    }
    return;
  }
  for_each_carrier(block.begin, block.begin + block.count, [&](const Carrier& c) {
    const size_t j = c.body - block.begin;
    const Quat q(block.q[0][j], block.q[1][j], block.q[2][j], block.q[3][j]);
    const Vec3 omega_w(block.omega_w[0][j], block.omega_w[1][j], block.omega_w[2][j]);
    const auto [h, h_dot] = momentum(c, block.t);
    loads.add(j, Vec3::Zero(), rotor_torque<double>(q, omega_w, h, h_dot));
  });
}

void Rotors::accumulate_tangent(const TangentView& view, std::span<WrenchT<TangentScalar>> loads) const {
  for_each_carrier(0, view.states.size(), [&](const Carrier& c) {
    const auto [h, h_dot] = momentum(c, view.t);
    const BodyStateT<TangentScalar>& s = view.states[c.body];
    loads[c.body].torque +=
        rotor_torque<TangentScalar>(s.q, s.omega_w, h.cast<TangentScalar>(), h_dot.cast<TangentScalar>());
  });
}

Vec3 Rotors::internal_angular_momentum(const SystemView& view) const {
  Vec3 L = Vec3::Zero();
  for_each_carrier(0, view.body_states.size(), [&](const Carrier& c) {
    L += view.body_states[c.body].q * momentum(c, view.t).first;  // Σ R h
  });
  return L;
}

std::optional<double> Rotors::potential_energy(const SystemView&) const {
  return motors_work() ? std::nullopt : std::optional<double>(0.0);
}

bool Rotors::motors_work() const {
  return controller_ || std::any_of(rotors_.begin(), rotors_.end(), [](const Rotor& r) {
           return r.torque != 0.0 || std::any_of(r.torque_table.begin(), r.torque_table.end(),
                                                 [](const auto& row) { return row.second != 0.0; });
         });
}

void Rotors::check(size_t n_bodies, size_t) const {
  for (const Rotor& r : rotors_) {
    if (r.body >= n_bodies) {
      throw InvalidArgument(
          fmt::format("rotor '{}': body index {} is out of range ({} bodies)", r.name, r.body, n_bodies));
    }
  }
}

std::string Rotors::describe(std::span<const RigidBody> bodies) const {
  std::vector<std::string> each;
  for (const Rotor& r : rotors_) {
    std::string motor = controller_ ? std::string("torque by the controller")
                        : r.torque_table.empty()
                            ? fmt::format("{} N m", r.torque)
                            : fmt::format("a torque table of {} rows", r.torque_table.size());
    if (r.max_speed > 0.0) motor += fmt::format(", up to {} rad/s", r.max_speed);
    if (r.max_torque > 0.0) motor += fmt::format(", at most {} N m", r.max_torque);
    each.push_back(fmt::format("'{}' on '{}' (J = {} kg m^2, {} rad/s, {})", r.name,
                               r.body < bodies.size() ? bodies[r.body].name() : std::to_string(r.body),
                               r.moment, r.speed, motor));
  }
  return fmt::format("rotors {}{}", fmt::join(each, ", "),
                     controller_ ? fmt::format("; a controller every {} s", controller_->interval) : "");
}

const Rotors* rotors_of(const Model& model) {
  for (const auto& f : model.forces)
    if (const auto* r = dynamic_cast<const Rotors*>(f.get())) return r;
  return nullptr;
}

}  // namespace tumble
