#pragma once
// Watching conserved quantities during a run. Each output sample gets its invariants and their
// relative drift from t = 0; the first time a quantity that the forces conserve drifts past the
// threshold, the monitor produces one warning saying which quantity, when, and what to change.
#include <optional>
#include <string>
#include <vector>

#include "tumble/forces/rotors.hpp"
#include "tumble/sim/diagnostics.hpp"
#include "tumble/sim/simulate.hpp"

namespace tumble {

/// Which invariants a model's forces conserve exactly (so that any drift is integration error).
struct Conservation {
  bool energy = true;            ///< kinetic + potential
  bool linear_momentum = true;   ///< Σ m v
  bool angular_momentum = true;  ///< about the world origin
};

/// The invariants at one sample and their drift relative to t = 0. A drift is nullopt where it is
/// undefined: energy without a potential for every force, or a quantity whose scale at t = 0 is zero.
struct DriftSample {
  Invariants invariants;
  std::optional<double> energy_drift;            ///< (E − E₀) / max(|E₀|, T₀), signed
  std::optional<double> linear_momentum_drift;   ///< |p − p₀| / |p₀|
  std::optional<double> angular_momentum_drift;  ///< |L − L₀| / |L₀|
  /// Each rotor's speed relative to its body Ω (rad/s) and motor torque u (N·m), in scene order
  /// (forces/rotors.hpp; empty without rotors). Taken here, with the sample, because a controller's
  /// torques change between samples and a writer may read the sample later, on a thread of its own.
  std::vector<double> rotor_speed, rotor_torque;
};

class DriftMonitor {
 public:
  /// `threshold` ≤ 0 disables the warning (the drifts are still computed). `settings` is quoted in
  /// the warning's advice (timestep, integrator).
  DriftMonitor(const Model& model, const SystemState& initial, Conservation conserved, double threshold,
               const RunSettings& settings);

  /// The same, relative to invariants at t = 0 given (e.g. from the initial variables, as the variables
  /// of later samples will give them).
  DriftMonitor(const Model& model, const Invariants& initial, Conservation conserved, double threshold,
               const RunSettings& settings);

  /// The invariants of `state` and their drifts.
  DriftSample observe(const SystemState& state);
  /// The same from the run's variables (settings.formulation; the run's bodies are first … of x):
  /// diagnostics::invariants on the variables, without converting the state (a study's samples).
  DriftSample observe(const SystemCoordinates& x, size_t first);

  /// The warning, once: set by the first observe() at which a conserved energy or angular momentum
  /// drifts by more than the threshold, and returned by the first call after that; nullopt otherwise.
  std::optional<std::string> take_warning();
  /// The warning of this run, if there was one (kept for the run's closing summary).
  const std::optional<std::string>& warning() const { return first_warning_; }
  /// A resumed run: the warning the first part of the run gave (it is not given again).
  void restore_warning(const std::string& warning) {
    warned_ = true;
    first_warning_ = warning;
  }

 private:
  DriftSample judge(const Invariants& at, double t);
  const Model& model_;
  const Rotors* rotors_;  ///< the model's rotors, or null
  Invariants initial_;
  double energy_scale_ = 0.0;
  std::optional<double> E0_;  ///< the initial energy, |p₀| and |L₀|
  double p0_ = 0.0, L0_ = 0.0;
  Conservation conserved_;
  double threshold_;
  RunSettings settings_;
  bool warned_ = false;
  std::optional<std::string> pending_;
  std::optional<std::string> first_warning_;
  SystemState scratch_;  // the bodies' states, for potentials, when observing variables
};

}  // namespace tumble
