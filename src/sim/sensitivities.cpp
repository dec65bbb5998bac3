// simulate_sensitivities: the run on dual numbers. Each pass seeds up to kTangentDirections columns
// (tangent directions of x(0) and parameters) and steps the whole system with Integrator::step_tangent;
// the derivatives read at a sample are the columns of the pass.
#include "tumble/sim/sensitivities.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <memory>

#include "held_inputs.hpp"
#include "steppers.hpp"
#include "tumble/error.hpp"

namespace tumble {
namespace {

using T = TangentScalar;
constexpr int D = kTangentDirections;

/// One pass: its own integrator and the system's variables carrying up to D seeded columns: slot s of
/// pass k is column k·D + s (the state's columns, then the parameters': simulate_sensitivities).
struct Pass {
  std::unique_ptr<Integrator> integrator;        // a fixed-step method
  std::unique_ptr<AdaptiveIntegrator> adaptive;  // or an adaptive one, which replays its accepted steps
  TangentCoordinates x;
};

/// Body b's state and parameters as dual numbers seeded along the directions `slot_of(j)` gives for its
/// tangent components j = 0 … 11 and parameters j = 12 … (−1: not seeded in this pass). The values are
/// the state's own, bit for bit; the derivatives those of moving x(0) along each tangent direction with
/// the other world components of the reference frame held fixed (dynamics/tangent.hpp, perturbed()).
template <class SlotOf>
void seed_body(const RigidBody& body, const BodyState& s, Formulation F, SensitivityParameters parameters,
               SlotOf&& slot_of, Coordinates<T>& x, T& m, Vec3T<T>& Lambda) {
  const ReferenceFrameState r = reference_state(body, s);
  Vec3T<T> d_p, d_theta, d_v, d_omega;
  Vec3T<T>* parts[4] = {&d_p, &d_theta, &d_v, &d_omega};
  for (int j = 0; j < 12; ++j) {
    const int slot = slot_of(j);
    (*parts[j / 3])(j % 3) = slot >= 0 ? T::variable(0.0, slot) : T(0.0);
  }
  // x(0) moved along δ: p + δp, R_ref ← exp([δθ]×) R_ref, v_p + δv, ω + δω, and the centre-of-mass
  // state of that reference frame: o = p + R_ref c, R = R_ref U, v = v_p + ω × (o − p).
  const Vec3T<T> p = r.position.cast<T>() + d_p;
  const QuatT<T> q_ref = quat_mul<T>(quat_exp<T>(d_theta), r.orientation.cast<T>());
  const Vec3T<T> omega_w = r.omega_w.cast<T>() + d_omega;
  const Vec3T<T> o = p + rotate<T>(q_ref, body.center_of_mass().cast<T>());
  const QuatT<T> q = quat_mul<T>(q_ref, body.q_U().cast<T>());
  const Vec3T<T> v = r.velocity.cast<T>() + d_v + omega_w.cross(o - p);
  switch (F) {
    case Formulation::world:
      x = {o, q, v, omega_w};
      break;
    case Formulation::mixed:
      x = {o, q, v, rotate_inverse<T>(q, omega_w)};
      break;
    case Formulation::body:
      x = {o, q, rotate_inverse<T>(q, v), rotate_inverse<T>(q, omega_w)};
      break;
  }
  // The values are the run's own initial variables, bit for bit (the reference frame's round trip
  // above rounds them).
  const Coordinates<double> exact = to_coordinates(F, s);
  for (int k = 0; k < 3; ++k) {
    x.o(k).v = exact.o(k);
    x.v(k).v = exact.v(k);
    x.omega(k).v = exact.omega(k);
  }
  x.q.coeffs()(0).v = exact.q.coeffs()(0);
  x.q.coeffs()(1).v = exact.q.coeffs()(1);
  x.q.coeffs()(2).v = exact.q.coeffs()(2);
  x.q.coeffs()(3).v = exact.q.coeffs()(3);
  m = T(body.mass());
  Lambda = body.Lambda().cast<T>();
  for (int k = 0; k < parameters_per_body(parameters); ++k) {
    const int slot = slot_of(12 + k);
    if (slot < 0) continue;
    if (parameters == SensitivityParameters::inertia) {
      Lambda(k) = T::variable(body.Lambda()(k), slot);
    } else if (parameters == SensitivityParameters::mass) {
      m = T::variable(body.mass(), slot);
    }
  }
}

/// Body b's reference-frame state read back from its variables: the value, and along slot s the tangent
/// (δp, δθ, δv, δω) with δθ = vee(log(R′ Rᵀ)) = 2 vec(q̇ ⊗ q̄)/|q|², all in world axes.
struct ReadBody {
  ReferenceFrameState value;
  Vec3T<T> p, v, omega;
  QuatT<T> q_ref;

  ReadBody(const RigidBody& body, Formulation F, const Coordinates<T>& x) {
    const auto [v_w, omega_w] = world_velocities<T>(F, x);
    q_ref = quat_mul<T>(x.q, body.q_U().conjugate().cast<T>());
    p = x.o - rotate<T>(q_ref, body.center_of_mass().cast<T>());
    v = v_w + omega_w.cross(p - x.o);
    omega = omega_w;
  }
  Tangent along(int slot) const {
    Tangent t;
    const Quat q(q_ref.w().v, q_ref.x().v, q_ref.y().v, q_ref.z().v);
    const Quat dq(q_ref.w().d[slot], q_ref.x().d[slot], q_ref.y().d[slot], q_ref.z().d[slot]);
    const Quat w = dq * q.conjugate();
    for (int k = 0; k < 3; ++k) {
      t(k) = p(k).d[slot];
      t(6 + k) = v(k).d[slot];
      t(9 + k) = omega(k).d[slot];
    }
    t.segment<3>(3) = 2.0 * w.vec() / q.squaredNorm();
    return t;
  }
};

BodyState value_state(Formulation F, const Coordinates<T>& x) {
  Coordinates<double> c;
  for (int k = 0; k < 3; ++k) {
    c.o(k) = x.o(k).v;
    c.v(k) = x.v(k).v;
    c.omega(k) = x.omega(k).v;
  }
  c.q = Quat(x.q.w().v, x.q.x().v, x.q.y().v, x.q.z().v);
  return to_state(F, c);
}

bool finite(const Coordinates<T>& x) {
  auto ok = [](const T& a) {
    if (!std::isfinite(a.v)) return false;
    for (double d : a.d)
      if (!std::isfinite(d)) return false;
    return true;
  };
  for (int k = 0; k < 3; ++k)
    if (!ok(x.o(k)) || !ok(x.v(k)) || !ok(x.omega(k))) return false;
  for (int k = 0; k < 4; ++k)
    if (!ok(x.q.coeffs()(k))) return false;
  return true;
}

}  // namespace

SensitivityParameters parse_sensitivity_parameters(const std::string& name) {
  if (name == "inertia") return SensitivityParameters::inertia;
  if (name == "mass") return SensitivityParameters::mass;
  if (name == "forces") return SensitivityParameters::forces;
  throw InvalidArgument(fmt::format(
      "unknown sensitivity parameters '{}': choose inertia (each body's principal moments I1, I2, I3), "
      "mass, or forces (the force models' parameters: g, drag coefficients, stiffnesses, ...)",
      name));
}
std::string sensitivity_parameters_name(SensitivityParameters parameters) {
  switch (parameters) {
    case SensitivityParameters::inertia:
      return "inertia";
    case SensitivityParameters::mass:
      return "mass";
    case SensitivityParameters::forces:
      return "forces";
  }
  return "?";
}
int parameters_per_body(SensitivityParameters parameters) {
  return parameters == SensitivityParameters::inertia ? 3 : parameters == SensitivityParameters::mass ? 1 : 0;
}

std::vector<std::string> parameter_names(const Model& model, SensitivityParameters parameters) {
  std::vector<std::string> names;
  if (parameters == SensitivityParameters::forces) {
    for (size_t k = 0; k < model.forces.size(); ++k) {
      for (const ForceParameter& p : model.forces[k]->parameters()) {
        names.push_back(fmt::format("force {} ({}): {}", k, model.forces[k]->describe(model.bodies), p.name));
      }
    }
    return names;
  }
  for (const RigidBody& b : model.bodies) {
    if (parameters == SensitivityParameters::mass) {
      names.push_back(b.name() + ": m");
    } else {
      for (const char* I : {"I1", "I2", "I3"}) names.push_back(b.name() + ": " + I);
    }
  }
  return names;
}

Eigen::MatrixXd Sensitivities::dense_stm() const {
  if (coupled) return stm;
  const Eigen::Index n = stm.rows();
  Eigen::MatrixXd M = Eigen::MatrixXd::Zero(n, n);
  for (Eigen::Index b = 0; b < n / 12; ++b) M.block(12 * b, 12 * b, 12, 12) = stm.block(12 * b, 0, 12, 12);
  return M;
}
Eigen::MatrixXd Sensitivities::dense_parameters() const {
  if (coupled || parameters_per_body == 0) return parameters;  // coupled, or parameters every body shares
  const Eigen::Index n = parameters.rows(), P = parameters_per_body;
  Eigen::MatrixXd M = Eigen::MatrixXd::Zero(n, n / 12 * P);
  for (Eigen::Index b = 0; b < n / 12; ++b)
    M.block(12 * b, P * b, 12, P) = parameters.block(12 * b, 0, 12, P);
  return M;
}

SystemState simulate_sensitivities(const Model& model, const SystemState& state, const RunSettings& settings,
                                   SensitivityParameters parameters, const SensitivitySink& on_sample) {
  validate(settings);
  const bool adaptive = is_adaptive(settings.integrator);
  if (!model.particles.empty()) {
    throw InvalidArgument(fmt::format(
        "sensitivities are of rigid bodies: the system has {} particle{} (model them as small bodies)",
        model.particles.size(), model.particles.size() == 1 ? "" : "s"));
  }
  if (state.bodies.size() != model.bodies.size()) {
    throw InvalidArgument(
        fmt::format("state has {} bodies, the model {}", state.bodies.size(), model.bodies.size()));
  }
  if (input_interval(model) > 0.0) {
    throw InvalidArgument(
        "sensitivities cannot be carried through a rotor controller (tumble does not know its law's "
        "derivatives): use finite differences (finite_difference_stm), which run it as it is");
  }
  const Formulation F = settings.formulation;
  const size_t B = model.bodies.size();
  const int P = parameters_per_body(parameters);
  bool coupled = false;
  for (const auto& f : model.forces) coupled = coupled || !f->local();
  for (const auto& f : model.forces) f->check(B, 0);
  // The force models' parameters, in model order (shared by every body: columns of their own).
  const bool shared = parameters == SensitivityParameters::forces;
  std::vector<std::vector<double>> force_values;
  size_t force_count = 0;
  for (const auto& f : model.forces) {
    force_values.emplace_back();
    for (const ForceParameter& p : f->parameters()) force_values.back().push_back(p.value);
    force_count += force_values.back().size();
  }
  if (shared && force_count == 0) {
    throw InvalidArgument(
        "sensitivities with respect to the force models' parameters: the system has no force model with "
        "parameters (a built-in model: gravity, a point force or torque, damping, drag, a spring, central "
        "gravity); choose inertia or mass");
  }

  // Coupled bodies give a dense 12B × 12B matrix per sample: past 10⁸ numbers (0.8 GB) a sample would
  // not fit beside the others, and the run would take (12 + P)B/16 whole-system passes.
  if (coupled && 144.0 * static_cast<double>(B) * static_cast<double>(B) > 1e8) {
    throw InvalidArgument(fmt::format(
        "sensitivities: the {} bodies interact (a spring joins some of them), so each sample's state "
        "transition matrix is dense, {} x {} numbers ({:.1f} GB): take the bodies the springs join as a "
        "smaller scene",
        B, 12 * B, 12 * B, 144.0 * static_cast<double>(B) * static_cast<double>(B) * 8e-9));
  }
  // The columns: the state's (12B when the bodies interact, else each body's own 12, which all bodies
  // seed alike), then the parameters' (each body's P, or the force models' shared ones). Pass k carries
  // columns 16k … 16k + 15 in its slots: for bodies apart and inertia one pass of 15, for interacting
  // bodies ⌈(12 + P)B/16⌉.
  const size_t state_columns = coupled ? 12 * B : 12;
  const size_t parameter_columns = shared ? force_count : coupled ? static_cast<size_t>(P) * B : P;
  const size_t columns = state_columns + parameter_columns;
  const size_t passes = (columns + D - 1) / D;
  auto slot_of = [&](size_t pass, size_t column) -> int {
    return column / D == pass ? static_cast<int>(column % D) : -1;
  };
  // Body b's local column j (0–11 its state, 12 + k its k-th own parameter) as a global column.
  auto column_of = [&](size_t b, int j) -> size_t {
    const auto u = static_cast<size_t>(j);
    if (j < 12) return coupled ? 12 * b + u : u;
    return state_columns + (coupled ? static_cast<size_t>(P) * b : 0) + (u - 12);
  };
  std::vector<Pass> pass(passes);
  for (size_t k = 0; k < passes; ++k) {
    if (adaptive) {
      pass[k].adaptive = make_adaptive_integrator(settings.integrator, settings.tolerances);
    } else {
      pass[k].integrator = make_integrator(settings.integrator);
      pass[k].integrator->check(model);
    }
    TangentCoordinates& x = pass[k].x;
    x.t = state.t;
    x.bodies.resize(B);
    x.m.resize(B);
    x.Lambda.resize(B);
    for (size_t b = 0; b < B; ++b) {
      seed_body(
          model.bodies[b], state.bodies[b], F, parameters, [&](int j) { return slot_of(k, column_of(b, j)); },
          x.bodies[b], x.m[b], x.Lambda[b]);
    }
    size_t column = state_columns;
    for (const std::vector<double>& values : force_values) {
      x.force_parameters.emplace_back();
      for (double v : values) {
        const int slot = shared ? slot_of(k, column++) : -1;
        x.force_parameters.back().push_back(slot >= 0 ? T::variable(v, slot) : T(v));
      }
    }
  }
  // Every integrator refuses here, before the first sample, if it does not differentiate its steps. An
  // adaptive one starts as AdaptiveSteps (steppers.hpp) starts it: the same first trial step.
  if (adaptive) {
    const SystemCoordinates x0 = to_coordinates(F, state);
    for (Pass& p : pass) {
      p.adaptive->start(model, F, x0,
                        std::min(settings.timestep, std::max(settings.duration, settings.timestep)));
      p.adaptive->start_tangent(model, F, p.x);
    }
  }
  // Bodies apart, every column in one pass: the steps between two samples go on SIMD packs when the
  // integrator and the forces have that path (Integrator::step_tangents_packed; the same numbers at a
  // fraction of the cost), else a step at a time. A system's first step_tangent refuses what cannot be
  // differentiated before the first sample; the packed path has nothing to refuse.
  const int slots = static_cast<int>(std::min<size_t>(columns, D));
  TangentCoordinates probe = pass[0].x;
  const bool packed = !adaptive && passes == 1 &&
                      pass[0].integrator->step_tangents_packed(model, F, probe, {}, slots);
  if (!adaptive && !packed && B > 0) pass[0].integrator->step_tangent(model, F, probe, settings.timestep);

  Sensitivities out;
  out.coupled = coupled;
  out.parameters_per_body = P;
  out.of = parameters;
  out.parameter_names = parameter_names(model, parameters);
  const Eigen::Index rows = static_cast<Eigen::Index>(12 * B);
  out.stm = Eigen::MatrixXd::Zero(rows, static_cast<Eigen::Index>(state_columns));
  out.parameters = Eigen::MatrixXd::Zero(rows, static_cast<Eigen::Index>(parameter_columns));
  SystemState sample;
  sample.bodies.resize(B);
  auto emit = [&]() {
    sample.t = pass[0].x.t;
    for (size_t b = 0; b < B; ++b) sample.bodies[b] = value_state(F, pass[0].x.bodies[b]);
    for (size_t k = 0; k < passes; ++k) {
      for (size_t b = 0; b < B; ++b) {
        const ReadBody read(model.bodies[b], F, pass[k].x.bodies[b]);
        const Eigen::Index row = static_cast<Eigen::Index>(12 * b);
        for (int s = 0; s < D; ++s) {
          const size_t g = k * D + static_cast<size_t>(s);
          if (g >= columns) break;
          const Tangent t = read.along(s);
          if (g < state_columns) {
            out.stm.block<12, 1>(row, static_cast<Eigen::Index>(g)) = t;
          } else {
            out.parameters.block<12, 1>(row, static_cast<Eigen::Index>(g - state_columns)) = t;
          }
        }
      }
    }
    return on_sample ? on_sample(sample, out) : true;
  };

  steppers::check_sample_times(settings, state.t);
  const steppers::SampleTimes sample_time(settings, state.t);
  const double h = settings.timestep, tiny = 1e-9 * h;
  // Sample 0 is the initial state as given, with the identity and zeros exactly (its dual numbers hold
  // them to the rounding of the seeding's frame conversions).
  out.stm.setZero();
  for (Eigen::Index i = 0; i < rows; ++i) out.stm(i, coupled ? i : i % 12) = 1.0;
  if (on_sample && !on_sample(state, out)) return state;
  double t_last_sample = state.t;
  long steps = 0, steps_since_sample = 0;
  auto check_finite = [&](const Pass& p, double step) {
    for (size_t b = 0; b < B; ++b) {
      if (!finite(p.x.bodies[b])) {
        throw Error(fmt::format(
            "sensitivities: the state of body '{}' or its derivatives became non-finite by t = {} "
            "s (step {}, h = {} s): take a smaller {}",
            model.bodies[b].name(), p.x.t, steps, step, adaptive ? "tolerance" : "timestep"));
      }
    }
  };
  std::vector<double> lengths;  // the packed path's steps to the next sample
  for (long k = 1; pass[0].x.t < sample_time.end() - tiny; ++k) {
    const double t_sample = sample_time(k);
    if (adaptive) {
      // AdaptiveSteps' way: accepted steps until one reaches the sample, which its dense output gives.
      for (Pass& p : pass) {
        AdaptiveIntegrator& a = *p.adaptive;
        while (a.current_time() < t_sample) {
          a.step();
          a.step_tangent();
        }
        p.x = a.interpolate_tangent(t_sample);
        steps = a.stats().steps;
        check_finite(p, a.current_time() - a.previous_time());
      }
    }
    // The clock of FixedSteps (steppers.hpp): steps of h, the last before a sample the remaining
    // interval, the time on the grid t_last_sample + n·h.
    lengths.clear();
    while (!adaptive && pass[0].x.t < t_sample - tiny) {
      const double remaining = t_sample - pass[0].x.t;
      const double step = remaining <= h + tiny ? remaining : h;
      ++steps;
      ++steps_since_sample;
      const double t_next = pass[0].x.t + step >= t_sample - tiny
                                ? t_sample
                                : t_last_sample + static_cast<double>(steps_since_sample) * h;
      for (Pass& p : pass) {
        if (packed) {
          lengths.push_back(step);
        } else {
          p.integrator->step_tangent(model, F, p.x, step);
          check_finite(p, step);
        }
        p.x.t = t_next;
      }
    }
    if (packed && !lengths.empty()) {
      pass[0].integrator->step_tangents_packed(model, F, pass[0].x, lengths, slots);
      check_finite(pass[0], h);
    }
    t_last_sample = pass[0].x.t;
    steps_since_sample = 0;
    if (!emit()) break;
  }
  return sample;
}

}  // namespace tumble
