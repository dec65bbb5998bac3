#pragma once
// The time loop: fixed steps from t₀ to t₀ + duration, samples at every output interval and at the end.
#include <array>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "tumble/integrate/integrator.hpp"

namespace tumble {

struct RunSettings {
  double duration = 1.0;         ///< s
  double timestep = 1e-3;        ///< s; the last step before a sample time is what remains of the
                                 ///< interval (shorter, or longer by rounding only), to land on it.
                                 ///< The clock is t_last_sample + n·h (one rounding), not a running sum.
                                 ///< For adaptive integrators: the first trial step.
  double output_interval = 0.0;  ///< s between samples; 0 = every step. The final time is always sampled.
  Formulation formulation = Formulation::mixed;
  std::string integrator = "rk4";
  Tolerances tolerances;  ///< for adaptive integrators (dopri45)
  int threads = 1;        ///< threads for fixed-step integrators; 0: one per hardware thread.
                          ///< Results are bit-identical for any count.
  /// Relative drift of a conserved energy or angular momentum past which a run warns (0: never).
  double drift_threshold = 1e-6;
  /// Times to sample at (s, the clock's own, not from the start), instead of every output interval:
  /// ascending, after the start, and the run ends at the last, so duration must be that time minus the
  /// start (to rounding). The start is sampled as ever. Empty: every output_interval.
  std::vector<double> sample_times;
};

/// Throws InvalidArgument unless duration ≥ 0, timestep > 0, output_interval ≥ 0, drift_threshold ≥ 0,
/// all finite, threads in 0 … 4096, and the integrator and formulation exist (sim/run_settings.hpp
/// describes each setting).
void validate(const RunSettings& settings);
/// Throws InvalidArgument unless 0 ≤ threads ≤ 4096 (0: one per core), naming the range: a run's
/// settings and a study's --threads.
void require_thread_count(int threads);

/// Called with every sample (the initial state first); return false to stop the run early (Ctrl-C).
using SampleSink = std::function<bool(const SystemState&)>;
/// The same with the formulation's variables themselves, unconverted: the run's bodies are rows first …
/// of x (0 for a run alone, its row in the batch for a lane). For observers that read a few numbers
/// per sample (a study's extrema and drifts), where converting the whole state would cost more.
using VariablesSink = std::function<bool(const SystemCoordinates& x, size_t first)>;

/// A condition watched during a run: the moment g(state) crosses zero (a flip, an impact, an
/// attitude reached). Located within a step to 4 ulp of the time (the Illinois variant of regula falsi,
/// bracketing, with bisection where it stalls), on states the run's own method gives inside the step:
/// one step of the shorter length from the step's start by a second instance of the integrator, so
/// that locating a crossing never changes the run (fixed-step methods), or the dense output (adaptive
/// ones, accurate to their tolerance).
struct Event {
  std::string name;
  std::function<double(const SystemState&)> g;
  int direction = 0;  ///< +1: only rising crossings (g < 0 → g ≥ 0), −1: only falling, 0: both
  bool stop = false;  ///< end the run at the crossing (the state there is the last sample)
  /// Optional, in place of g: g from the variables of one body, `body`, in the run's formulation (row i
  /// of the columns x: i = `body` in a run alone, its row in the batch for a lane). It spares converting
  /// the whole state at every step, which cost several times the step itself when g reads one number
  /// (ω₂ about the intermediate axis is the mixed formulation's own ^bω₂). When set, simulate evaluates
  /// this one only.
  std::function<double(const BodyColumns& x, size_t i, Formulation formulation)> g_variables = {};
  size_t body = 0;
  /// Optional, beside g_variables, when g is one of the body's variables less a constant: g = x[c][i] −
  /// value with c = column[formulation], in the formulations that hold it as it is (c ≥ 0; the others
  /// call g_variables). simulate reads it inline: a study evaluates every run's events at every step.
  struct Variable {
    std::array<int, 3> column{-1, -1, -1};  ///< by Formulation (world, mixed, body)
    double value = 0.0;
  };
  std::optional<Variable> variable = {};
};

/// An event that happened: its name and the state just after the crossing.
struct EventHit {
  std::string name;
  size_t index = 0;  ///< of the event in RunHooks::events
  SystemState state;
};

/// Where a run stands at a sample, in full: what simulate needs to continue it exactly as if it had
/// never stopped (io/checkpoint.hpp stores it in a file). Taken only where nothing is pending: right after
/// a sample on the output grid (fixed-step integrators), or after an accepted step that held samples
/// (adaptive ones: their state is where the step ended).
struct RunPoint {
  double t0 = 0.0;       ///< the run's start time (the initial state's)
  SystemCoordinates x;   ///< the formulation's variables there
  long next_sample = 1;  ///< k of the next sample on the grid t₀ + k·Δ
  double t_last_sample = 0.0;
  long steps_since_sample = 0;  ///< fixed-step: steps since the last sample on the grid
  long samples = 0;             ///< samples handed to on_sample so far (the initial state's included)
  bool finished = false;        ///< the final time was sampled
  IntegratorStats stats;
  std::vector<double> event_values;  ///< g of each event there
  std::vector<double> integrator;    ///< Integrator::save_state(), AdaptiveIntegrator::save_state()
};

/// One of several independent runs stepped together as one system: a study's runs of one structure,
/// stacked by forces/stack.hpp (run r's n bodies are bodies r·n … r·n + n − 1 of the stacked model).
/// Each lane watches its own events, located by stepping its own model alone from the start of the
/// step, and sees only its own states. Since the engine steps a body alike in any company (any N, block
/// or thread), a lane's samples and crossings are those of the run simulated alone, bit for bit.
struct Lane {
  const Model* model = nullptr;  ///< the run's own model: its bodies (the stacked ones' values) and forces
  /// Names the run in errors, e.g. "run 17 (bodies.box.mass = 2.5)": called only then (a study's
  /// labels carry its draws, which take a while to format).
  std::function<std::string()> label;
  std::vector<Event> events;
  SampleSink on_sample;        ///< the run's own state at every sample; return false when it needs no more
  VariablesSink on_variables;  ///< its variables at every sample (after on_sample)
  std::function<void(const EventHit&)> on_event;
};

/// What a run reports back, all optional.
struct RunHooks {
  /// Called with every sample (the initial state first); return false to stop the run early.
  SampleSink on_sample;
  /// The same samples as the formulation's variables (after on_sample), first = 0: the whole system's,
  /// a batch's too (before its lanes', e.g. to reduce every lane's sample at once, a pack of lanes at a
  /// time; a stopping crossing's sample is only its lane's).
  VariablesSink on_variables;
  /// Conditions to watch.
  std::vector<Event> events;
  /// Called for every event crossing, in time order.
  std::function<void(const EventHit&)> on_event;
  /// Asked after every step — or after every chunk of up to 16 full steps, which simulate hands at once
  /// to integrators that gain from it (Integrator::steps) when no events are watched; when it answers
  /// true the state reached is handed to on_sample as a last, off-grid sample and the run ends (Ctrl-C).
  std::function<bool()> stop_requested;
  /// Receives the work done (steps, rejections, force evaluations).
  IntegratorStats* stats = nullptr;

  /// Exact resume. When set, kept up to date at every point a run can be resumed from (see RunPoint;
  /// the initial state is one): a copy of the state and of the integrator's state there each time.
  /// After a run that stopped early it holds the last such point, which may be a sample or two before
  /// the state the run stopped at.
  RunPoint* run_point = nullptr;
  /// Called right after each update of *run_point (e.g. to write a checkpoint now and then).
  std::function<void(const RunPoint&)> on_run_point;
  /// Continue a run from this point, taken by a run of the same model, initial state (passed as `state`),
  /// settings and events; the samples before it are not handed to on_sample again. The run from there
  /// is bit for bit the run that was not stopped.
  const RunPoint* resume_from = nullptr;

  /// A batch of independent runs (see Lane): when not empty, the system is these runs laid end to end,
  /// each watching its own events (`events` and `on_event` above must then be empty); on_sample still
  /// receives the whole system, and so does on_variables. A lane whose stopping event fires, or whose on_sample returns false, is
  /// done: it is stepped on with the others but reports nothing more; the run ends when all are done.
  /// Fixed-step integrators only (an adaptive step size would depend on every run's error), and no
  /// run points (a study resumes by whole runs).
  std::vector<Lane> lanes;
};

/// Runs the model from `state` and returns the final state. Throws tumble::Error naming the body,
/// time and step if a state becomes non-finite (a step too large, or a force that blows up).
SystemState simulate(const Model& model, SystemState state, const RunSettings& settings,
                     const RunHooks& hooks);

/// The same with only the commonly used hooks.
SystemState simulate(const Model& model, SystemState state, const RunSettings& settings,
                     const SampleSink& on_sample = {}, IntegratorStats* stats = nullptr,
                     const std::function<bool()>& stop_requested = {});

}  // namespace tumble
