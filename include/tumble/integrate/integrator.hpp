#pragma once
// Time integrators, selected by name. Two kinds:
//  - fixed-step (`Integrator`): advance by a given h; the time loop shortens the last step before a
//    sample so samples land on the output grid;
//  - adaptive (`AdaptiveIntegrator`): choose their own steps to meet tolerances and answer at any
//    requested time by dense output.
//
// | name                | kind     | order | keeps                                  |
// | euler               | fixed    | 1     | nothing (gains energy on a free rotor)  |
// | semi_implicit_euler | fixed    | 1     | nothing                                 |
// | rk4                 | fixed    | 4     | |q| = 1 by projection                   |
// | lie_rk4             | fixed    | 4     | R ∈ SO(3) to rounding, no projection    |
// | implicit_gyro       | fixed    | 1     | stable at large steps; dissipates E, |L| |
// | splitting           | fixed    | 2     | L_w, E of the free flow exactly         |
// | splitting4          | fixed    | 4     | same                                    |
// | midpoint            | fixed    | 2     | E, |L|, L_w exactly without torque (implicit) |
// | dopri45             | adaptive | 5(4)  | the tolerances                          |
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "tumble/integrate/system_coordinates.hpp"
#include "tumble/integrate/tangent_system.hpp"

namespace tumble {

class Integrator {
 public:
  virtual ~Integrator() = default;
  virtual std::string name() const = 0;
  /// Order of accuracy of the method (global error ∝ hᵒʳᵈᵉʳ).
  virtual int order() const = 0;
  /// Right-hand-side (force) evaluations per step, for work–precision comparisons.
  virtual int evaluations_per_step() const = 0;
  /// For methods whose work varies per step (implicit ones): the evaluations made since the object was
  /// created; nullopt when evaluations_per_step() is exact.
  virtual std::optional<long> evaluations_counted() const { return std::nullopt; }
  /// Advance the formulation's variables `x` from x.t to x.t + h, in place. Integrators work on the
  /// formulation's own variables from step to step: converting to world quantities and back every step
  /// would rotate ω and v forth and back by a quaternion whose norm is 1 only to rounding, a bias of
  /// ~1e-16 per step that accumulates (measured: 2e-11 energy drift in 40 000 steps of a free body).
  /// The first step binds the integrator to `model` and sizes its workspace; from then on a step
  /// allocates nothing. An instance serves one model at a time (a model that changes size re-binds it)
  /// and one caller at a time; it spreads its own work over threads() threads.
  virtual void step(const Model& model, Formulation formulation, SystemCoordinates& x, double h) = 0;
  /// `count` steps of h: the same result, bit for bit, as `count` calls of step(). Integrators whose
  /// steps are fused (rk4, lie_rk4: every force model local, no particles) take each block of bodies
  /// through all of them while it is in cache, so the state crosses memory once per call, not once per
  /// step: what keeps the rate flat up to millions of bodies. simulate() uses it between samples.
  virtual void steps(const Model& model, Formulation formulation, SystemCoordinates& x, double h,
                     long count) {
    for (long k = 0; k < count; ++k) step(model, formulation, x, h);
  }
  /// Whether steps() takes blocks through several steps at once for this model (and so gains from
  /// being handed many). simulate() chunks steps only then: the state is checked between chunks.
  virtual bool fuses_steps(const Model& /*model*/) const { return false; }

  /// One step of h of the same method on dual numbers (tangent_system.hpp, issue 25): the values of x
  /// advance as step() advances the variables, by the same templated stage updates, rates and force
  /// laws, and their derivatives are those of that discrete step. Throws InvalidArgument for the
  /// integrators that do not differentiate their steps (differentiating_integrators() names the others).
  virtual void step_tangent(const Model& model, Formulation formulation, TangentCoordinates& x, double h);
  /// Steps of x's tangents of the given lengths with every body on SIMD packs (src/integrate/
  /// tangent_packs.hpp): the numbers step_tangent gives step by step, bit for bit, at a fraction of the
  /// cost, with the derivatives in x's first `slots` slots. False, and x untouched, when this integrator
  /// or the model's forces have no such path (euler, semi_implicit_euler and rk4 have it, under uniform
  /// fields): step_tangent then. x.t is the caller's.
  virtual bool step_tangents_packed(const Model& /*model*/, Formulation /*formulation*/,
                                    TangentCoordinates& /*x*/, std::span<const double> /*lengths*/,
                                    int /*slots*/) {
    return false;
  }

  /// Throws InvalidArgument, naming what is in the way, if this integrator cannot run `model` (only
  /// `exact` refuses some: it solves torque-free motion under a uniform field). simulate() asks first.
  virtual void check(const Model& /*model*/) const {}

  /// What the integrator carries from one step to the next besides x (splitting's kept flows and end
  /// loads, exact's anchor, counters), as doubles (counts and flags are exact in a double): a checkpoint
  /// stores it, and an integrator given it by load_state() and then the same x continues bit for bit as
  /// this one would. Empty for the integrators that carry nothing.
  virtual std::vector<double> save_state() const { return {}; }
  /// Restores what save_state() returned, for `model` in `formulation`. Throws InvalidArgument if it
  /// does not fit (another integrator's state, another model's size).
  virtual void load_state(const Model& model, Formulation formulation, const std::vector<double>& state);

  /// Threads a step uses (≤ 0: one per hardware thread). Results do not depend on it, bit for bit.
  void set_threads(int threads) { threads_ = threads; }
  int threads() const { return threads_; }

 protected:
  int threads_ = 1;
};

/// Error tolerances of adaptive integrators: each component y of the state keeps its local error below
/// absolute + relative·|y|.
struct Tolerances {
  double relative = 1e-9;
  double absolute = 1e-12;
};

/// Work done by an integrator in a run.
struct IntegratorStats {
  long steps = 0;        ///< accepted steps
  long rejected = 0;     ///< rejected step attempts (adaptive only)
  long evaluations = 0;  ///< right-hand-side (force model) evaluations
};

class AdaptiveIntegrator {
 public:
  virtual ~AdaptiveIntegrator() = default;
  virtual std::string name() const = 0;
  /// Begin at x0 with a first trial step; `model` must outlive the integrator's use.
  virtual void start(const Model& model, Formulation formulation, const SystemCoordinates& x0,
                     double initial_step) = 0;
  /// Take one accepted step (rejected attempts are retried inside); returns the new current time.
  virtual double step() = 0;
  /// Time at the start and the end of the last accepted step (both the start time before any step).
  virtual double previous_time() const = 0;
  virtual double current_time() const = 0;
  /// The variables at t ∈ [previous_time(), current_time()], by dense output.
  virtual SystemCoordinates interpolate(double t) const = 0;
  virtual IntegratorStats stats() const = 0;

  /// Everything the integrator carries between accepted steps (its state, time and next trial step, the
  /// work counted), as doubles, for a checkpoint. load_state() after start() (same model, formulation and
  /// shape of x) continues the run bit for bit: the next step is the step this integrator would take.
  virtual std::vector<double> save_state() const = 0;
  /// Throws InvalidArgument if `state` does not fit.
  virtual void load_state(const std::vector<double>& state) = 0;

  /// Sensitivities (issue 25): the accepted steps replayed on dual numbers. start_tangent(), after
  /// start(), takes x(0) on dual numbers (its values those given to start()); after each step(),
  /// step_tangent() takes the step just accepted — previous_time() to current_time() — by the same
  /// stages, and interpolate_tangent(t) is the dense output inside it. The lengths the error control
  /// chose are constants of this map: their own derivatives are not taken (docs/sensitivities.md).
  /// The defaults throw InvalidArgument (differentiating_integrators() names those that override them).
  virtual void start_tangent(const Model& model, Formulation formulation, const TangentCoordinates& x0);
  virtual void step_tangent();
  virtual TangentCoordinates interpolate_tangent(double t) const;

  /// The variables at time t (non-decreasing between calls), stepping as far as needed and
  /// interpolating inside the last step.
  SystemCoordinates at(double t) {
    while (current_time() < t) step();
    return interpolate(t);
  }
};

/// The integrators whose steps are differentiated (Integrator::step_tangent).
std::vector<std::string> differentiating_integrators();

/// Every registered integrator name, fixed-step and adaptive.
std::vector<std::string> integrator_names();
/// True for the adaptive ones (dopri45).
bool is_adaptive(const std::string& name);
/// The fixed-step integrator registered under `name`; throws InvalidArgument listing the names there
/// are (and saying so for an adaptive name).
[[nodiscard]] std::unique_ptr<Integrator> make_integrator(const std::string& name);
/// The adaptive integrator registered under `name`; throws InvalidArgument for other names and for
/// tolerances that are not positive and finite.
std::unique_ptr<AdaptiveIntegrator> make_adaptive_integrator(const std::string& name,
                                                             const Tolerances& tolerances);

/// What the batched engine was built for: the SIMD instruction set of its packs (e.g. "sse2", "avx2",
/// "avx512bw") and the bodies per pack.
struct EngineInfo {
  std::string instruction_set;
  int lanes = 1;
};
EngineInfo engine_info();

/// "world", "mixed" or "body" ↔ Formulation; throws InvalidArgument for anything else.
Formulation parse_formulation(const std::string& name);
std::string formulation_name(Formulation formulation);

}  // namespace tumble
