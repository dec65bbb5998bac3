// splitting, splitting4: kick–drift–kick with the exact free flow.
//
// Strang splitting of the equations of motion into the applied wrench ("kick": velocities and angular
// momentum change by the impulse while the pose is frozen) and the torque-free, force-free motion
// ("drift": o moves uniformly, the orientation and ^bω follow the exact Euler–Poinsot solution):
//   S(h) = K(h/2) ∘ D(h) ∘ K(h/2).
// Second order for forces that depend on position and time; exact, at any step, for a free body, and for
// a body under uniform gravity (the kick of a constant force is exact and the translation is then the
// Störmer–Verlet parabola, exact for constant acceleration). Each drift is a rotation and each kick
// changes L_w by hτ, so L_w is conserved exactly (to rounding) when no torque acts, and the free-body
// energy is exact. Velocity-dependent forces (damping, drag) are kicked with the velocities at the
// start of the kick: first order in them.
// Rotors (forces/rotors.hpp) are not kicked: their torque −ω × h − ḣ is velocity-dependent, and the
// gyrostat splits into two exact flows instead, the free one of ω₁ = ω + Λ⁻¹h and a turn about −Λ⁻¹h
// (gyrostat_split.hpp), so that the step stays second order and keeps L to rounding: the kicks load the
// bodies with the model's other forces, and the drift of a body with rotors is wrapped in those turns.
// A body whose motors hold its rotors' speeds over the step (h constant) needs no split: it drifts by the
// torque-free gyrostat's own flow, its Taylor series to rounding (gyrostat_series.hpp), and the
// splitting is exact for it without external torque, as for a free body.
// splitting4 is Yoshida's fourth-order composition S(w₁h) S(w₀h) S(w₁h), w₁ = 1/(2 − 2^⅓),
// w₀ = 1 − 2w₁ (the middle step runs backwards in time; the exact flow handles that).
//
// The loads at the end of a step are the loads at the start of the next: they are kept (with a copy of
// the state they belong to, to notice a state changed between steps), so a step costs one force
// evaluation (three for splitting4). The kick and the drift of a body follow its loads in the same
// pass over the block, a pack of bodies at a time; when every force is local and there are no
// particles, steps(count) takes each block through all its steps while it is in cache (fused, as rk4).
//
// A body that feels no torque keeps its flow. When neither half kick changes ω (a free body, uniform
// gravity, forces through the centre of mass), L_w is unchanged and consecutive drifts compose into one
// torque-free motion from the state entering the first of them. Each body keeps that flow, the time τ
// along it and the q, ω the last drift left (in the formulation's variables); a drift whose entering
// q, ω equal those bit for bit, with the same Λ, evaluates the kept flow at τ + h instead of setting up
// a new one. Anything else (a torque in either half kick, a state changed by the caller between steps,
// other moments, another formulation) sets up a fresh flow, and the step is then what a new integrator
// (which keeps nothing) makes of it, bit for bit (tests/integrate/splitting_reuse_test.cpp).
// splitting4's substeps add signed lengths to τ (the middle one is negative); nothing else changes.
//
// The flows on packs. A triaxial flow off the separatrix (every generic body) keeps its constants in
// FlowColumns, a block of 8 bodies at a time, and a pack of bodies evaluates them in one pass of
// detail::triaxial_state — the template EulerPoinsot evaluates on double: sn, cn, dn by the product form
// of the descending Landen transformation and Π as the argument plus tumble's Carlson R_J
// (jacobi_elliptic.hpp, math/carlson.hpp), branch-free, with per-lane step counts padded exactly. Two packs go together
// (PackPair: two independent chains the core overlaps). The other flows (rest, sphere, axisymmetric,
// separatrix) are evaluated by their EulerPoinsot body by body; which way a body goes depends on its
// flow alone, so a body steps the same whatever its neighbours, block or thread (tests/integrate/
// batch_test.cpp). A pack's lanes agree with double to xsimd's rounding of sin, cos, atan, hypot
// (≤ 32ε(1 + |phase|) in attitude, euler_poinsot_pack_test.cpp).
//  - Cost (`build/release/bin/batch_throughput out.csv 3 1000000 rk4,splitting,splitting4 1,2 1,16`,
//    free boxes under gravity, one thread, AVX-512): splitting 1.7e6 body-steps/s (24× an rk4
//    body-step) with a scalar flow per body; 2.2e7 on packs, flat from 10² to 10⁶ bodies, 2.8× an rk4
//    body-step (bench/results/amd-epyc-avx512/batch_throughput.txt, rk4_splitting_ab.txt). A flow
//    costs 25 ns a body on packs (euler_poinsot_bench: BM_StatePackPair), 0.28 µs on double.
//    On an Intel Xeon the flow is bound by the divider (≈ 40 square roots and divisions a pack, each
//    16+ cycles on 8 lanes): every one saved counts, which is why the Landen levels, R_J's steps and
//    the half-angles are written to take as few as they do (75 → 50 ns a body there,
//    bench/results/intel-xeon-avx512/flow_ab.txt).
//  - Accuracy: nothing is rounded between steps. A fresh flow every step rounds q and ω every step, and
//    the flips of a tumbling body amplify it: 5e-10–1e-9 rad after 1e5 steps of the T-handle, against 0 for
//    the kept flow, which is the exact flow from the first state evaluated at the summed time. Its own
//    error at τ is the rounding of its phases, ≤ 1.4 ε|ω|τ measured up to τ = 1e4 s against a long-double
//    reference: the attitude error that rounding τ itself to a double makes (euler_poinsot_test.cpp).
//  - No periodic re-anchoring: a new flow from the state every 10 s was 35× less accurate at 1e4 s. Each
//    anchor rounds the state; E and |L|, so the frequencies, then random-walk, and the phase error grows
//    faster than the rounding of τ, which is all one flow commits.
//  - τ is summed with compensation (TwoSum): a plain τ += h carries the rounding of every addition,
//    3.7e-10 rad after 2e4 steps of 5 ms in the tests, more than setting up a flow every step.
//  - Memory: one FreeFlight per body (its EulerPoinsot, ~1 KB: no heap) and ~70 doubles of FlowColumns,
//    sized on the first step of a run: 1.85 KB per body in all.
// Sensitivities (issue 25): StrangTangent takes the same steps on dual numbers, one body at a time: the
// kick<T> template, and the drift's derivatives from the exact flow differentiated (FreeFlowTangent).
#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <optional>
#include <span>
#include <type_traits>
#include <vector>

#include "engine.hpp"
#include "euler_poinsot_flows.hpp"
#include "free_flow_tangent.hpp"
#include "gyrostat_series.hpp"
#include "gyrostat_split.hpp"
#include "methods.hpp"
#include "saved_state.hpp"
#include "tumble/integrate/euler_poinsot.hpp"
#include "tumble/math/pack_pair.hpp"

namespace tumble {
namespace {

using detail::FlowState;
using detail::TriaxialConstants;
using engine::Block;
using engine::kWidth;
using engine::Pack;

static_assert(std::is_same_v<Pack, PackPair::P>, "PackPair pairs the engine's packs");

/// Landen ratio columns kept per body: m₁ ≥ 1e-300 needs at most 15 AGM steps. A flow that needs
/// more is evaluated by its EulerPoinsot, like the regimes below.
constexpr int kRatioColumns = 16;

/// Where R_J's step count is among the constants (visit_constants' order).
size_t rj_steps_index() {
  TriaxialConstants<double> k;
  size_t index = 0, found = 0;
  detail::visit_constants(k, 0, [&](double& value) {
    if (&value == &k.pi.rj_steps) found = index;
    ++index;
  });
  return found;
}

/// How many constants visit_constants visits.
size_t constant_count() {
  TriaxialConstants<double> k;
  size_t count = 0;
  detail::visit_constants(k, kRatioColumns, [&](double&) { ++count; });
  return count;
}

/// The kept flows of all bodies as columns, one row per body: the bookkeeping of each kept flow (time
/// along it, the q and ω its last drift left, the Λ it was set up with) and, for a triaxial flow off
/// the separatrix, its constants, so that a pack of bodies evaluates its flows in one pass of
/// detail::triaxial_state<Pack>. Other flows (rest, sphere, axisymmetric, separatrix) are evaluated by
/// their EulerPoinsot, body by body: each body takes the same path whatever its neighbours.
struct FlowColumns {
  enum : size_t {
    tau,                     // time along the flow, τ + τ_lo (compensated sum of the drifts' h)
    tau_lo,                  // the rounding error of that sum (TwoSum)
    q,                       // 4: q the last drift left (w, x, y, z)
    omega = q + 4,           // 3: ω the last drift left, in the formulation's variables
    Lambda = omega + 3,      // 3: the moments the flow was set up with
    has_flow = Lambda + 3,   // 1 once set up
    in_pack = has_flow + 1,  // 1: a triaxial flow off the separatrix, evaluated in packs
    steps = in_pack + 1,     // its AGM steps
    constants = steps + 1    // visit_constants' order
  };
};

/// A body's torque-free motion since the last torque (or change of its state), kept between steps:
/// the flow and the state it was set up from (a checkpoint stores these, not the flow).
struct FreeFlight {
  std::optional<EulerPoinsot> flow;
  Quat q0{1.0, 0.0, 0.0, 0.0};
  Vec3 w0 = Vec3::Zero();
};

/// K(τ): v += τ f/m and L_w += τ τ_w with the pose frozen, in the formulation's variables.
template <class T>
TUMBLE_INLINE void kick(Formulation F, Coordinates<T>& c, T tau, const Vec3T<T>& f_w, const Vec3T<T>& tau_w,
                        const MassConstants<T>& mass) {
  const Vec3T<T> dv_w = tau * f_w * mass.m_inv;
  const Vec3T<T> dw_b = tau * rotate_inverse<T>(c.q, tau_w).cwiseProduct(mass.Lambda_inv);  // Λ⁻¹ Rᵀ Δl
  c.v += F == Formulation::body ? rotate_inverse<T>(c.q, dv_w) : dv_w;
  c.omega += F == Formulation::world ? rotate<T>(c.q, dw_b) : dw_b;
}

class Strang {
 public:
  /// `count` steps, each the composition of Strang steps of lengths w·h for w in `weights` (splitting:
  /// {1}; splitting4: Yoshida's three). When every force model is local and there are no particles, each
  /// block of bodies goes through all of them while it is in cache (engine.hpp, "fused"): the flows'
  /// values and the state cross memory once per call instead of twice per substep. Bit for bit the same
  /// as the substeps one by one (tested).
  void steps(const Model& model, Formulation F, SystemCoordinates& x, double h, long count, int threads,
             std::span<const double> weights) {
    engine_.prepare(rotor_split_.kick_model(model), F, threads);
    if (!engine_.fused() || rotor_split_.active()) {  // rotors: a(t) each (sub)step, step by step
      for (long r = 0; r < count; ++r) {
        const double t_end = x.t + h;
        for (const double w : weights) step(model, F, x, w * h, threads);
        if (weights.size() > 1) x.t = t_end;  // the substeps add to h up to rounding
      }
      return;
    }
    const size_t n = x.bodies.size();
    prepare(n, F);
    // The time of the kept loads when they belong to this state (NaN, equal to nothing, if none do).
    const double t_loads = cached_ && same(x) ? t_ : std::numeric_limits<double>::quiet_NaN();
    const BodyColumnsRef xr = x.bodies.ref();
    double t_last = t_loads;  // what every block ends with (the same for all)
    engine_.for_each_fused_block(n, [&](engine::Engine::FusedBlock& fb) {
      double t = x.t, t_kept = t_loads;
      for (long r = 0; r < count; ++r) {
        double t_sub = t;
        for (const double w : weights) {
          const double hs = w * h;
          // The loads at the start: kept from the last substep unless they belong to another time (as a
          // step-by-step run's check of x.t finds after splitting4 resets its clock).
          if (!(t_kept == t_sub)) keep_loads(fb.evaluate(xr, t_sub));
          kick_drift(F, xr, hs, fb.begin, fb.end, n);
          t_sub += hs;
          end_kick(F, xr, hs, fb.evaluate(xr, t_sub));
          t_kept = t_sub;
        }
        t = weights.size() > 1 ? t + h : t_sub;
      }
      if (fb.begin == 0) t_last = t_kept;
    });
    for (long r = 0; r < count; ++r) {
      double t_sub = x.t;
      for (const double w : weights) t_sub += w * h;
      x.t = weights.size() > 1 ? x.t + h : t_sub;
    }
    remember(x);
    t_ = t_last;
  }

  void step(const Model& model, Formulation F, SystemCoordinates& x, double h, int threads) {
    engine_.prepare(rotor_split_.kick_model(model), F, threads);
    if (rotor_split_.active()) rotor_split_.momenta(x.t, h);
    const size_t n = x.bodies.size();
    prepare(n, F);
    const bool reuse = cached_ && same(x);
    const BodyColumnsRef xr = x.bodies.ref();
    // K(h/2) with the loads at the start, then D(h), a pack of bodies at a time.
    auto kick_drift_block = [&](const Block& blk, bool fresh) {
      if (fresh) keep_loads(blk);
      kick_drift(F, xr, h, blk.begin, blk.end, n);
    };
    if (reuse) {
      engine_.for_each_block(n, [&](const Block& blk) { kick_drift_block(blk, false); });
      for (size_t p = 0; p < x.particles.size(); ++p)
        x.particles[p].v += 0.5 * h * particle_loads_[p] / model.particles[p].mass;
    } else {
      engine_.evaluate(x, [&](const Block& blk) { kick_drift_block(blk, true); });
      for (size_t p = 0; p < x.particles.size(); ++p)
        x.particles[p].v += 0.5 * h * engine_.particle_rates(p, x.particles[p]).v;
    }
    for (auto& p : x.particles) p.x += h * p.v;
    x.t += h;
    // K(h/2) with the loads at the end, which are kept for the next step.
    engine_.evaluate(x, [&](const Block& blk) { end_kick(F, xr, h, blk); });
    particle_loads_.assign(engine_.particle_forces().begin(), engine_.particle_forces().end());
    for (size_t p = 0; p < x.particles.size(); ++p)
      x.particles[p].v += 0.5 * h * particle_loads_[p] / model.particles[p].mass;
    remember(x);
  }

  /// The kept flows (each as the state it was set up from: setting it up again gives the same flow,
  /// bit for bit), the end loads and the state they belong to.
  void save(std::vector<double>& out) const {
    saved::Writer w(out);
    w.put(static_cast<double>(flights_.size()));
    w.put(static_cast<double>(flights_formulation_));
    for (size_t i = 0; i < flights_.size(); ++i) {
      const FreeFlight& ff = flights_[i];
      w.put(ff.flow ? 1.0 : 0.0);
      w.put(ff.q0), w.put(ff.w0);
      w.put(*at(FlowColumns::tau, i)), w.put(*at(FlowColumns::tau_lo, i));
      w.put(Quat(*at(FlowColumns::q, i), *at(FlowColumns::q + 1, i), *at(FlowColumns::q + 2, i),
                 *at(FlowColumns::q + 3, i)));
      w.put(column_vec3(FlowColumns::omega, i));
    }
    w.put(cached_ ? 1.0 : 0.0);
    if (!cached_) return;
    w.put(loads_);
    w.put(particle_loads_);
    w.put(state_);
    w.put(particles_);
    w.put(t_);
  }

  void load(const Model& model, saved::Reader& r) {
    const size_t n = model.bodies.size(), np = model.particles.size();
    const size_t count = r.count(n);
    if (count != n && count != 0) r.fail();
    const auto F = static_cast<Formulation>(r.count(2));
    reset(count, F);
    for (size_t i = 0; i < count; ++i) {
      FreeFlight& ff = flights_[i];
      const bool has_flow = r.flag();
      ff.q0 = r.quat(), ff.w0 = r.vec3();
      *at(FlowColumns::tau, i) = r.get(), *at(FlowColumns::tau_lo, i) = r.get();
      const Quat q = r.quat();
      const Vec3 omega = r.vec3();
      if (has_flow) {
        ff.flow.emplace(model.bodies[i].Lambda(), ff.q0, ff.w0);
        adopt(i);
      }
      set_column_quat(FlowColumns::q, i, q);
      set_column_vec3(FlowColumns::omega, i, omega);
    }
    cached_ = r.flag();
    if (!cached_) return;
    r.columns(loads_, 6, n);
    particle_loads_ = r.vec3s(np);
    r.columns(state_, BodyColumns::kCount, n);
    particles_ = r.particles(np);
    t_ = r.get();
  }

 private:
  /// Where value k of body i is: the flows are stored a block of kColumnPadding bodies at a time (all the
  /// values of bodies 8b … 8b + 7 together, each value's 8 lanes in a row), so that a pack's ~70 values
  /// are one run of memory. As ~70 separate columns they were ~70 streams and a TLB miss each per pack:
  /// at 10⁵ bodies and more the drift ran at 60 % of its rate at 10⁴.
  double* at(size_t k, size_t i) {
    return flows_[0] + (i / kColumnPadding) * flows_.count() * kColumnPadding + k * kColumnPadding +
           i % kColumnPadding;
  }
  const double* at(size_t k, size_t i) const { return const_cast<Strang*>(this)->at(k, i); }

  using Mask = decltype(Pack() < Pack());

  /// A pack of bodies in the middle of D(h): its state, and what the flow evaluation needs and gives.
  struct Drift {
    Coordinates<Pack> c;
    Vec3T<Pack> v_w;  // v in world axes
    Mask real;        // the lanes that hold bodies (not padding)
    Mask in_pack;     // the lanes whose flow is evaluated on packs
    Pack t;           // time along each lane's flow
    FlowState<Pack> flow;
  };

  /// Sizes the loads and the flows (the first step of a run: allocates).
  void prepare(size_t n, Formulation F) {
    loads_.ensure(n, 6);
    if (flights_.size() != n || F != flights_formulation_) reset(n, F);
  }

  /// The block's loads, kept as the loads at the start of its next kick.
  void keep_loads(const Block& blk) {
    for (size_t i = blk.begin; i < blk.end; i += kWidth) {
      const Vec3T<Pack> f = blk.force<Pack>(i), tau = blk.torque<Pack>(i);
      for (size_t k = 0; k < 3; ++k) {
        f(static_cast<Eigen::Index>(k)).store_aligned(loads_[k] + i);
        tau(static_cast<Eigen::Index>(k)).store_aligned(loads_[3 + k] + i);
      }
    }
  }

  /// K(h/2) with the kept loads, then D(h), for the pack of bodies i … i + W − 1.
  void kick_drift(Formulation F, const BodyColumnsRef& xr, double h, size_t i, size_t n) {
    Drift d;
    begin_kick_drift(F, xr, h, d, i, n);
    evaluate_flows(d, i);
    held_rotor_drifts(F, d, h, i);
    end_drift(F, d, i);
    leave_rotors(F, d.c, h, i);
    xr.store(i, d.c);
  }
  /// The same for two packs (bodies i … i + 2W − 1), their flows evaluated together.
  void kick_drift_pair(Formulation F, const BodyColumnsRef& xr, double h, size_t i, size_t n) {
    Drift d0, d1;
    begin_kick_drift(F, xr, h, d0, i, n);
    begin_kick_drift(F, xr, h, d1, i + kWidth, n);
    evaluate_flows(d0, d1, i);
    held_rotor_drifts(F, d0, h, i);
    held_rotor_drifts(F, d1, h, i + kWidth);
    end_drift(F, d0, i);
    end_drift(F, d1, i + kWidth);
    leave_rotors(F, d0.c, h, i);
    leave_rotors(F, d1.c, h, i + kWidth);
    xr.store(i, d0.c);
    xr.store(i + kWidth, d1.c);
  }
  /// Every pack of bodies [begin, end), two at a time where it can.
  void kick_drift(Formulation F, const BodyColumnsRef& xr, double h, size_t begin, size_t end, size_t n) {
    size_t i = begin;
    for (; i + 2 * kWidth <= end; i += 2 * kWidth) kick_drift_pair(F, xr, h, i, n);
    for (; i < end; i += kWidth) kick_drift(F, xr, h, i, n);
  }
  void begin_kick_drift(Formulation F, const BodyColumnsRef& xr, double h, Drift& d, size_t i, size_t n) {
    d.c = xr.load<Pack>(i);
    kick<Pack>(F, d.c, Pack(0.5 * h), load3(0, i), load3(3, i), engine_.mass<Pack>(i));
    enter_rotors(F, d.c, h, i);
    begin_drift(F, d, h, engine_.Lambda<Pack>(i), i, n);
  }

  /// With rotors (gyrostat_split.hpp), before the drift: ω → ω₁ = ω + a, then G(h/2); and after it the
  /// reverse. Only the lanes of bodies with rotors change (a = 0 would leave the others as they are only
  /// to rounding of Λ⁻¹(Λω)): the others keep their bits, and so their kept flows.
  void enter_rotors(Formulation F, Coordinates<Pack>& c, double h, size_t i) const {
    turn_rotors(F, c, h, i, true);
  }
  void leave_rotors(Formulation F, Coordinates<Pack>& c, double h, size_t i) const {
    turn_rotors(F, c, h, i, false);
  }
  /// Entering: h at the step's start and middle; leaving: at its middle and end.
  void turn_rotors(Formulation F, Coordinates<Pack>& c, double h, size_t i, bool entering) const {
    if (!rotor_split_.active()) return;
    const int first = entering ? 0 : 1;
    const Vec3T<Pack> h_a = rotor_split_.h<Pack>(first, i), h_b = rotor_split_.h<Pack>(first + 1, i);
    const auto spins = (nonzero(h_a) || nonzero(h_b)) && !rotor_split_.held<Pack>(i);
    if (!xsimd::any(spins)) return;
    Coordinates<Pack> g = c;
    const MassConstants<Pack> mass = engine_.mass<Pack>(i);
    if (entering) {
      gyrostat::enter<Pack>(F, g, h_a, h_b, mass.Lambda, mass.Lambda_inv, Pack(0.5 * h));
    } else {
      gyrostat::leave<Pack>(F, g, h_a, h_b, mass.Lambda, mass.Lambda_inv, Pack(0.5 * h));
    }
    blend(spins, g, c);
  }
  /// The lanes whose rotors' speeds are held over the step drift by the torque-free gyrostat's flow
  /// from the kicked state (gyrostat_series.hpp), exact to rounding: the splitting is then exact for
  /// them without external torque, as for a free body.
  void held_rotor_drifts(Formulation F, Drift& d, double h, size_t i) const {
    if (!rotor_split_.active()) return;
    const Mask which = rotor_split_.held<Pack>(i) && d.real;
    if (!xsimd::any(which)) return;
    const MassConstants<Pack> mass = engine_.mass<Pack>(i);
    const Vec3T<Pack> h_b = rotor_split_.h<Pack>(0, i);
    const Coordinates<Pack>& c = d.c;
    const Vec3T<Pack> w_b = F == Formulation::world ? Vec3T<Pack>(c.q.conjugate() * c.omega) : c.omega;
    // Lanes not held: rate 0, one substep of the fewest terms (their result is not used).
    const Pack rate = select(which, gyrostat::series_rate<Pack>(w_b, h_b, mass.Lambda), Pack(0.0));
    const FlowState<Pack> s = gyrostat::series_flow<Pack, Pack>(mass.Lambda, h_b, c.q, w_b, h, rate);
    d.flow.q = QuatT<Pack>(select(which, s.q.w(), d.flow.q.w()), select(which, s.q.x(), d.flow.q.x()),
                           select(which, s.q.y(), d.flow.q.y()), select(which, s.q.z(), d.flow.q.z()));
    for (Eigen::Index k = 0; k < 3; ++k) d.flow.omega_b(k) = select(which, s.omega_b(k), d.flow.omega_b(k));
  }
  static Mask nonzero(const Vec3T<Pack>& v) {
    return v.x() != Pack(0.0) || v.y() != Pack(0.0) || v.z() != Pack(0.0);
  }
  /// c ← g in the lanes of `which`.
  static void blend(const Mask& which, const Coordinates<Pack>& g, Coordinates<Pack>& c) {
    for (Eigen::Index k = 0; k < 3; ++k) {
      c.o(k) = select(which, g.o(k), c.o(k));
      c.v(k) = select(which, g.v(k), c.v(k));
      c.omega(k) = select(which, g.omega(k), c.omega(k));
    }
    c.q = QuatT<Pack>(select(which, g.q.w(), c.q.w()), select(which, g.q.x(), c.q.x()),
                      select(which, g.q.y(), c.q.y()), select(which, g.q.z(), c.q.z()));
  }

  /// K(h/2) with the loads at the end of the step, which are kept for the next.
  void end_kick(Formulation F, const BodyColumnsRef& xr, double h, const Block& blk) {
    keep_loads(blk);
    for (size_t i = blk.begin; i < blk.end; i += kWidth) {
      Coordinates<Pack> c = xr.load<Pack>(i);
      kick<Pack>(F, c, Pack(0.5 * h), load3(0, i), load3(3, i), engine_.mass<Pack>(i));
      xr.store(i, c);
    }
  }

  Vec3T<Pack> load3(size_t first, size_t i) const {
    return {Pack::load_aligned(loads_[first] + i), Pack::load_aligned(loads_[first + 1] + i),
            Pack::load_aligned(loads_[first + 2] + i)};
  }
  Vec3 column_vec3(size_t first, size_t i) const {
    return {*at(first, i), *at(first + 1, i), *at(first + 2, i)};
  }
  void set_column_vec3(size_t first, size_t i, const Vec3& v) {
    for (size_t k = 0; k < 3; ++k) *at(first + k, i) = v(static_cast<Eigen::Index>(k));
  }
  void set_column_quat(size_t first, size_t i, const Quat& q) {
    *at(first, i) = q.w(), *at(first + 1, i) = q.x(), *at(first + 2, i) = q.y(), *at(first + 3, i) = q.z();
  }

  /// Sizes the flows for n bodies in formulation F, none set up yet. Padding rows hold the constants
  /// of a harmless flow, so that a partly filled pack computes finite numbers in its spare lanes.
  void reset(size_t n, Formulation F) {
    flights_.assign(n, FreeFlight{});
    flights_formulation_ = F;
    flows_.resize(n, FlowColumns::constants + constant_count());
    static const EulerPoinsot spare(Vec3(1.0, 2.0, 3.0), Quat::Identity(), Vec3(1.0, 0.5, 0.25));
    const detail::TriaxialRotation* spare_flow = spare.free_rotation().triaxial();  // triaxial: 1 < 2 < 3
    for (size_t i = n; i < flows_.stride() && spare_flow; ++i) write_constants(i, *spare_flow);
  }

  /// The columns of body i's newly set-up flow.
  void adopt(size_t i) {
    const EulerPoinsot& flow = *flights_[i].flow;
    *at(FlowColumns::has_flow, i) = 1.0;
    set_column_vec3(FlowColumns::Lambda, i, flow.Lambda());
    const detail::TriaxialRotation* triaxial = flow.free_rotation().triaxial();
    const bool in_pack = triaxial && !triaxial->separatrix() &&
                         triaxial->constants().jacobi.steps <= kRatioColumns;
    *at(FlowColumns::in_pack, i) = in_pack ? 1.0 : 0.0;
    if (in_pack) write_constants(i, *triaxial);
  }
  void write_constants(size_t i, const detail::TriaxialRotation& triaxial) {
    TriaxialConstants<double> k = triaxial.constants();
    for (int r = k.jacobi.steps; r < kRatioColumns; ++r)
      k.jacobi.ratio[r] = 0.0;  // the extra steps halve φ exactly
    *at(FlowColumns::in_pack, i) = 1.0;
    *at(FlowColumns::steps, i) = k.jacobi.steps;
    size_t column = FlowColumns::constants;
    detail::visit_constants(k, kRatioColumns, [&](double& value) { *at(column++, i) = value; });
  }

  /// D(h) for the pack of bodies i … i + W − 1, up to the flow: o moves uniformly. When a body's
  /// rotational state entering the drift is, bit for bit, what its last drift left (no torque in the
  /// kicks since, nobody changed it) and Λ is the same, the motion continues the flow set up then: it
  /// is evaluated at τ + h. Otherwise a new flow is set up from the body's state (set_up).
  void begin_drift(Formulation F, Drift& d, double h, const Vec3T<Pack>& Lambda, size_t i, size_t n) {
    Coordinates<Pack>& c = d.c;
    d.v_w = F == Formulation::body ? Vec3T<Pack>(c.q * c.v) : c.v;
    c.o += Pack(h) * d.v_w;
    auto column = [&](size_t k) { return Pack::load_aligned(at(k, i)); };
    alignas(64) double lane_index[kWidth];
    for (size_t l = 0; l < kWidth; ++l) lane_index[l] = static_cast<double>(i + l);
    d.real = Pack::load_aligned(lane_index) < Pack(static_cast<double>(n));
    auto kept = column(FlowColumns::has_flow) == Pack(1.0);
    for (size_t k = 0; k < 3; ++k) {
      kept = kept && column(FlowColumns::omega + k) == c.omega(static_cast<Eigen::Index>(k)) &&
             column(FlowColumns::Lambda + k) == Lambda(static_cast<Eigen::Index>(k));
    }
    kept = kept && column(FlowColumns::q) == c.q.w() && column(FlowColumns::q + 1) == c.q.x() &&
           column(FlowColumns::q + 2) == c.q.y() && column(FlowColumns::q + 3) == c.q.z();
    kept = kept || !d.real;  // spare lanes keep their harmless flow
    if (!xsimd::all(kept)) set_up(F, c, Lambda, kept, i, n);
    // τ += h by Knuth's TwoSum: the rounding error of each addition is exact and kept in τ_lo. A new
    // flow starts at τ = h.
    const Pack tau = column(FlowColumns::tau), tau_lo = column(FlowColumns::tau_lo), H(h);
    const Pack s = tau + H, b = s - tau;
    const Pack tau_next = select(kept, s, H),
               lo_next = select(kept, tau_lo + ((tau - (s - b)) + (H - b)), Pack(0.0));
    tau_next.store_aligned(at(FlowColumns::tau, i));
    lo_next.store_aligned(at(FlowColumns::tau_lo, i));
    d.t = tau_next + lo_next;
    d.in_pack = column(FlowColumns::in_pack) == Pack(1.0);
    d.flow = {QuatT<Pack>(Pack(1.0), Pack(0.0), Pack(0.0), Pack(0.0)), {Pack(0.0), Pack(0.0), Pack(0.0)}};
  }

  /// The flows of one pack (a Drift begun), then the lanes evaluated body by body.
  void evaluate_flows(Drift& d, size_t i) const {
    if (xsimd::any(d.in_pack && d.real)) d.flow = triaxial_state<Pack>(d.t, i);
    if (!xsimd::all(d.in_pack || !d.real)) evaluate_lanes(d.flow, d.t, d.in_pack, d.real, i);
  }

  /// The flows of two packs at once (bodies i … i + 2W − 1): the same lanes, bit for bit, as one pack at
  /// a time, but two independent chains of operations, which the core overlaps (PackPair): the flow
  /// costs 39 instead of 58 ns a body (euler_poinsot_bench).
  void evaluate_flows(Drift& d0, Drift& d1, size_t i) const {
    if (xsimd::any(d0.in_pack && d0.real) && xsimd::any(d1.in_pack && d1.real)) {
      const FlowState<PackPair> both = triaxial_state<PackPair>(PackPair(d0.t, d1.t), i);
      d0.flow = {QuatT<Pack>(both.q.w().a, both.q.x().a, both.q.y().a, both.q.z().a),
                 {both.omega_b(0).a, both.omega_b(1).a, both.omega_b(2).a}};
      d1.flow = {QuatT<Pack>(both.q.w().b, both.q.x().b, both.q.y().b, both.q.z().b),
                 {both.omega_b(0).b, both.omega_b(1).b, both.omega_b(2).b}};
      if (!xsimd::all(d0.in_pack || !d0.real)) evaluate_lanes(d0.flow, d0.t, d0.in_pack, d0.real, i);
      if (!xsimd::all(d1.in_pack || !d1.real)) evaluate_lanes(d1.flow, d1.t, d1.in_pack, d1.real, i + kWidth);
    } else {
      evaluate_flows(d0, i);
      evaluate_flows(d1, i + kWidth);
    }
  }

  /// The rest of D(h): the orientation and ω the flow gives (the formulation's variables), kept as what
  /// this drift left.
  void end_drift(Formulation F, Drift& d, size_t i) {
    Coordinates<Pack>& c = d.c;
    const FlowState<Pack>& flow = d.flow;
    c.q = QuatT<Pack>(select(d.real, flow.q.w(), c.q.w()), select(d.real, flow.q.x(), c.q.x()),
                      select(d.real, flow.q.y(), c.q.y()), select(d.real, flow.q.z(), c.q.z()));
    const Vec3T<Pack> omega = F == Formulation::world ? Vec3T<Pack>(c.q * flow.omega_b) : flow.omega_b;
    for (Eigen::Index k = 0; k < 3; ++k) c.omega(k) = select(d.real, omega(k), c.omega(k));
    if (F == Formulation::body) {
      const Vec3T<Pack> v_b = c.q.conjugate() * d.v_w;
      for (Eigen::Index k = 0; k < 3; ++k) c.v(k) = select(d.real, v_b(k), c.v(k));
    }
    c.q.w().store_aligned(at(FlowColumns::q, i));
    c.q.x().store_aligned(at(FlowColumns::q + 1, i));
    c.q.y().store_aligned(at(FlowColumns::q + 2, i));
    c.q.z().store_aligned(at(FlowColumns::q + 3, i));
    for (size_t k = 0; k < 3; ++k)
      c.omega(static_cast<Eigen::Index>(k)).store_aligned(at(FlowColumns::omega + k, i));
  }

  /// New flows for the bodies of the pack whose state is not what their last drift left. A body whose
  /// state is, bit for bit, the one its flow was set up from (with the same Λ) keeps that flow, started
  /// again at τ = h: setting it up anew would give the same flow. This is how a crossing is located:
  /// its probe steps the same start several times, by different lengths (sim/steppers.hpp).
  void set_up(Formulation F, const Coordinates<Pack>& c, const Vec3T<Pack>& Lambda,
              const decltype(Pack() < Pack())& kept, size_t i, size_t n) {
    alignas(64) double q[4][kWidth], w[3][kWidth], L[3][kWidth], keep[kWidth];
    c.q.w().store_aligned(q[0]), c.q.x().store_aligned(q[1]), c.q.y().store_aligned(q[2]),
        c.q.z().store_aligned(q[3]);
    for (size_t k = 0; k < 3; ++k) {
      c.omega(static_cast<Eigen::Index>(k)).store_aligned(w[k]);
      Lambda(static_cast<Eigen::Index>(k)).store_aligned(L[k]);
    }
    select(kept, Pack(1.0), Pack(0.0)).store_aligned(keep);
    for (size_t l = 0; l < kWidth && i + l < n; ++l) {
      if (keep[l] == 1.0) continue;
      const Quat q_l(q[0][l], q[1][l], q[2][l], q[3][l]);
      const Vec3 omega_l(w[0][l], w[1][l], w[2][l]);
      const Vec3 w_b = F == Formulation::world ? Vec3(q_l.conjugate() * omega_l) : omega_l;
      FreeFlight& ff = flights_[i + l];
      const Vec3 Lambda_l(L[0][l], L[1][l], L[2][l]);
      const auto same_bits = [](const auto& a, const auto& b) {  // == would take −0 for +0
        return std::memcmp(a.data(), b.data(), sizeof(double) * 3) == 0;
      };
      if (ff.flow && same_bits(ff.w0, w_b) && same_bits(ff.flow->Lambda(), Lambda_l) &&
          std::memcmp(ff.q0.coeffs().data(), q_l.coeffs().data(), sizeof(double) * 4) == 0)
        continue;
      ff.flow.emplace(Lambda_l, q_l, w_b);
      ff.q0 = q_l;
      ff.w0 = w_b;
      adopt(i + l);
    }
  }

  /// detail::triaxial_state at times t on the constants of the bodies from i on: a pack (T = Pack) or two
  /// (T = PackPair).
  template <class T>
  FlowState<T> triaxial_state(const T& t, size_t i) const {
    constexpr size_t width = Lanes<T>::width;
    // The pack runs as many Landen steps as its slowest lane; the others have zero ratios there. The
    // ratios come last, and only those the pack uses are loaded.
    double steps = 0.0, rj_steps = 0.0;
    for (size_t l = 0; l < width; ++l) {
      steps = std::max(steps, *at(FlowColumns::steps, i + l));
      rj_steps = std::max(rj_steps, *at(FlowColumns::constants + rj_steps_index_, i + l));
    }
    TriaxialConstants<T> k;
    k.jacobi.steps = static_cast<int>(steps);
    k.pi.rj_max_steps = static_cast<int>(rj_steps);
    size_t column = FlowColumns::constants;
    detail::visit_constants(k, k.jacobi.steps, [&](T& value) { value = load(column++, i, value); });
    return detail::triaxial_state<T>(k, t);
  }
  Pack load(size_t k, size_t i, const Pack&) const { return Pack::load_aligned(at(k, i)); }
  PackPair load(size_t k, size_t i, const PackPair&) const {
    return {Pack::load_aligned(at(k, i)), Pack::load_aligned(at(k, i + kWidth))};
  }

  /// The lanes whose flow is not evaluated in packs, each by its EulerPoinsot.
  void evaluate_lanes(FlowState<Pack>& flow, const Pack& t, const decltype(Pack() < Pack())& in_pack,
                      const decltype(Pack() < Pack())& real, size_t i) const {
    alignas(64) double q[4][kWidth], w[3][kWidth], times[kWidth], scalar[kWidth];
    flow.q.w().store_aligned(q[0]), flow.q.x().store_aligned(q[1]), flow.q.y().store_aligned(q[2]),
        flow.q.z().store_aligned(q[3]);
    for (size_t k = 0; k < 3; ++k) flow.omega_b(static_cast<Eigen::Index>(k)).store_aligned(w[k]);
    t.store_aligned(times);
    select(real && !in_pack, Pack(1.0), Pack(0.0)).store_aligned(scalar);
    for (size_t l = 0; l < kWidth; ++l) {
      if (scalar[l] != 1.0) continue;
      const EulerPoinsot::State s = flights_[i + l].flow->state(times[l]);
      q[0][l] = s.q.w(), q[1][l] = s.q.x(), q[2][l] = s.q.y(), q[3][l] = s.q.z();
      for (size_t k = 0; k < 3; ++k) w[k][l] = s.omega_b(static_cast<Eigen::Index>(k));
    }
    flow.q = QuatT<Pack>(Pack::load_aligned(q[0]), Pack::load_aligned(q[1]), Pack::load_aligned(q[2]),
                         Pack::load_aligned(q[3]));
    for (size_t k = 0; k < 3; ++k) flow.omega_b(static_cast<Eigen::Index>(k)) = Pack::load_aligned(w[k]);
  }

  void remember(const SystemCoordinates& x) {
    state_ = x.bodies;  // same shape from the second step on: a copy, no allocation
    particles_ = x.particles;
    t_ = x.t;
    cached_ = true;
  }
  bool same(const SystemCoordinates& x) const { return x.t == t_ && same_variables(x, state_, particles_); }

  engine::Engine engine_;
  gyrostat::RotorSplit rotor_split_;  // the model's rotors, whose torque the flows carry
  std::vector<FreeFlight> flights_;   // one per body
  Columns flows_;                     // FlowColumns, one row per body, addressed by at()
  size_t rj_steps_index_ = rj_steps_index();
  Formulation flights_formulation_ = Formulation::mixed;
  Columns loads_;  // loads at the end of the last step: f (3), τ (3)
  std::vector<Vec3> particle_loads_;
  bool cached_ = false;
  BodyColumns state_;  // the state they belong to
  std::vector<ParticleState> particles_;
  double t_ = 0.0;
};

/// The Strang steps on dual numbers (Integrator::step_tangent) and what they keep between steps: as on
/// double, the loads at the end of a (sub)step are those of the next one's first kick when it starts
/// from the state they were left with (for a velocity-dependent force they were evaluated before the
/// end kick: that is the map the steps on double apply, and so the one differentiated).
class StrangTangent {
 public:
  /// The steps of lengths w·h (w in `weights`): the same kick<T>, the loads of every force model's
  /// templated law, and for the drift the exact flow differentiated (FreeFlowTangent). Each drift sets
  /// up its flow from the state entering it, where the steps on double continue a kept flow: the same
  /// motion, so the values agree to rounding.
  void steps(const Model& model, Formulation F, TangentCoordinates& x, double h,
             std::span<const double> weights) {
    using T = TangentScalar;
    const double t_end = x.t + h;
    const Model& kicked = rotor_split_.kick_model(model);  // with rotors: their torque is in the flows
    auto kick_all = [&](double tau, std::span<const WrenchT<T>> loads) {
      for (size_t i = 0; i < x.bodies.size(); ++i) {
        kick<T>(F, x.bodies[i], T(tau), loads[i].force, loads[i].torque,
                mass_constants<T>(x.m[i], x.Lambda[i]));
      }
    };
    for (const double w : weights) {
      const double hs = w * h;
      if (!same(x)) {
        const std::span<const WrenchT<T>> start = rates_.loads(kicked, F, x);
        loads_.assign(start.begin(), start.end());
      }
      kick_all(0.5 * hs, loads_);
      if (rotor_split_.active()) rotor_split_.momenta(x.t, hs);
      // Whether body i has rotors turning it by G (h ≠ 0 at the step's start or middle, or middle or
      // end, and not held: a held h drifts with the body by the gyrostat's series flow).
      const auto spins = [&](size_t i, int first) {
        return !(rotor_split_.h<double>(first, i).isZero(0.0) && rotor_split_.h<double>(1, i).isZero(0.0)) &&
               !rotor_split_.held<double>(i);
      };
      for (size_t i = 0; i < x.bodies.size(); ++i) {
        Coordinates<T>& c = x.bodies[i];
        const MassConstants<T> mass = mass_constants<T>(x.m[i], x.Lambda[i]);
        const bool held = rotor_split_.active() && rotor_split_.held<double>(i);
        if (rotor_split_.active() && spins(i, 0)) {
          gyrostat::enter<T>(F, c, rotor_split_.h<T>(0, i), rotor_split_.h<T>(1, i), mass.Lambda,
                             mass.Lambda_inv, T(0.5 * hs));
        }
        const Vec3T<T> v_w = F == Formulation::body ? rotate<T>(c.q, c.v) : c.v;
        c.o += T(hs) * v_w;
        const Vec3T<T> w_b = F == Formulation::world ? rotate_inverse<T>(c.q, c.omega) : c.omega;
        const detail::FlowState<T> flow = held ? held_rotor_flow(c, w_b, mass, i, hs)
                                               : FreeFlowTangent(x.Lambda[i], c.q, w_b).at(hs);
        c.q = flow.q;
        c.omega = F == Formulation::world ? rotate<T>(c.q, flow.omega_b) : flow.omega_b;
        if (F == Formulation::body) c.v = rotate_inverse<T>(c.q, v_w);
        if (rotor_split_.active() && spins(i, 2)) {
          gyrostat::leave<T>(F, c, rotor_split_.h<T>(1, i), rotor_split_.h<T>(2, i), mass.Lambda,
                             mass.Lambda_inv, T(0.5 * hs));
        }
      }
      x.t += hs;
      const std::span<const WrenchT<T>> end = rates_.loads(kicked, F, x);
      loads_.assign(end.begin(), end.end());
      kick_all(0.5 * hs, loads_);
      remember(x);
    }
    if (weights.size() > 1) x.t = t_end;  // the substeps add to h up to rounding
  }

 private:
  /// The drift of a body whose rotors' speeds are held: the series flow, as the steps on packs take it.
  detail::FlowState<TangentScalar> held_rotor_flow(const Coordinates<TangentScalar>& c,
                                                   const Vec3T<TangentScalar>& w_b,
                                                   const MassConstants<TangentScalar>& mass, size_t i,
                                                   double hs) const {
    using T = TangentScalar;
    const Vec3T<T> h_b = rotor_split_.h<T>(0, i);
    const double rate = gyrostat::series_rate<T>(w_b, h_b, mass.Lambda).v;
    return gyrostat::series_flow<T, double>(mass.Lambda, h_b, c.q, w_b, hs, rate);
  }

  /// Whether x is, value for value, the state the last substep left (at the same time).
  bool same(const TangentCoordinates& x) const {
    if (!(x.t == t_) || x.bodies.size() != left_.size()) return false;
    for (size_t i = 0; i < left_.size(); ++i) {
      const Coordinates<TangentScalar>& c = x.bodies[i];
      const Coordinates<double>& l = left_[i];
      for (int k = 0; k < 3; ++k) {
        if (c.o(k).v != l.o(k) || c.v(k).v != l.v(k) || c.omega(k).v != l.omega(k)) return false;
      }
      for (int k = 0; k < 4; ++k) {
        if (c.q.coeffs()(k).v != l.q.coeffs()(k)) return false;
      }
    }
    return true;
  }
  void remember(const TangentCoordinates& x) {
    t_ = x.t;
    left_.resize(x.bodies.size());
    for (size_t i = 0; i < left_.size(); ++i) {
      const Coordinates<TangentScalar>& c = x.bodies[i];
      Coordinates<double>& l = left_[i];
      for (int k = 0; k < 3; ++k) l.o(k) = c.o(k).v, l.v(k) = c.v(k).v, l.omega(k) = c.omega(k).v;
      for (int k = 0; k < 4; ++k) l.q.coeffs()(k) = c.q.coeffs()(k).v;
    }
  }

  TangentRates rates_;
  gyrostat::RotorSplit rotor_split_;
  std::vector<WrenchT<TangentScalar>> loads_;  // the loads of the next kick
  std::vector<Coordinates<double>> left_;      // the values the last substep left, at t_
  double t_ = std::numeric_limits<double>::quiet_NaN();
};

/// What the splitting methods share: the Strang step with its kept flows, and their saving for resume.
class StrangIntegrator : public Integrator {
 public:
  std::vector<double> save_state() const override {
    std::vector<double> out;
    strang_.save(out);
    return out;
  }
  void load_state(const Model& model, Formulation, const std::vector<double>& state) override {
    saved::Reader r(state, name());
    strang_.load(model, r);
    r.done();
  }

 protected:
  Strang strang_;
  StrangTangent tangent_;
};

class Splitting2 final : public StrangIntegrator {
 public:
  std::string name() const override { return "splitting"; }
  int order() const override { return 2; }
  int evaluations_per_step() const override { return 1; }
  bool fuses_steps(const Model& model) const override { return engine::Engine::fusable(model); }
  void step(const Model& model, Formulation F, SystemCoordinates& x, double h) override {
    steps(model, F, x, h, 1);
  }
  void steps(const Model& model, Formulation F, SystemCoordinates& x, double h, long count) override {
    strang_.steps(model, F, x, h, count, threads_, kWeights);
  }
  void step_tangent(const Model& model, Formulation F, TangentCoordinates& x, double h) override {
    tangent_.steps(model, F, x, h, kWeights);
  }

 private:
  static constexpr double kWeights[] = {1.0};
};

class Splitting4 final : public StrangIntegrator {
 public:
  std::string name() const override { return "splitting4"; }
  int order() const override { return 4; }
  int evaluations_per_step() const override { return 3; }
  bool fuses_steps(const Model& model) const override { return engine::Engine::fusable(model); }
  void step(const Model& model, Formulation F, SystemCoordinates& x, double h) override {
    steps(model, F, x, h, 1);
  }
  void steps(const Model& model, Formulation F, SystemCoordinates& x, double h, long count) override {
    strang_.steps(model, F, x, h, count, threads_, weights());
  }
  void step_tangent(const Model& model, Formulation F, TangentCoordinates& x, double h) override {
    tangent_.steps(model, F, x, h, weights());
  }

 private:
  /// Yoshida's: w₁ = 1/(2 − 2^⅓) twice around w₀ = 1 − 2w₁.
  static std::span<const double> weights() {
    static const double w1 = 1.0 / (2.0 - std::cbrt(2.0));
    static const double w[] = {w1, 1.0 - 2.0 * w1, w1};
    return w;
  }
};

}  // namespace

namespace methods {
std::unique_ptr<Integrator> splitting() { return std::make_unique<Splitting2>(); }
std::unique_ptr<Integrator> splitting4() { return std::make_unique<Splitting4>(); }
}  // namespace methods

}  // namespace tumble
