#pragma once
// What a study keeps of its runs' samples, reduced as they come, over all the runs of a batch at once:
// each run's extrema and its largest energy and angular momentum drifts. A study samples every run at
// every output time; taken one run at a time (a DriftMonitor and a loop over its columns each), this
// cost more than stepping the T-handle's flow. Private to tumble_study.
#include <cstddef>
#include <optional>
#include <vector>

#include "tumble/dynamics/columns.hpp"
#include "tumble/io/ensemble.hpp"
#include "tumble/io/scene.hpp"
#include "tumble/sim/drift_monitor.hpp"
#include "tumble/sim/output_fields.hpp"

namespace tumble {

/// The samples of L runs ("lanes") of n bodies each: run l's bodies are rows l·n … l·n + n − 1 of the
/// system's variables (a run alone, L = 1, may have particles too). Per lane and output column, the
/// smallest and largest value; per lane, max |E − E₀| / max(|E₀|, T₀) and max |L − L₀| / |L₀|.
///
/// Where the drifts are the bodies' sums alone (no force model, so no potential, and no particles) they
/// are reduced a pack of lanes at a time from sim/diagnostics.hpp's add_body_sums; a lane of a pack gives
/// the bits of the same run observed alone, on doubles (the same operations in the same order). Other
/// runs' drifts are a DriftMonitor's each. Extrema of the columns the formulation holds as variables
/// (VariableColumn::variable) are taken a pack of lanes at a time too, the others lane by lane.
class LaneSamples {
 public:
  LaneSamples(const EnsembleOutputs& outputs, Formulation F, size_t lanes, size_t bodies_per_lane,
              size_t particles_per_lane = 0);

  /// Run l: its scene (its bodies' constants, kept by pointer: the scene must outlive this) and its
  /// invariants at t = 0.
  void add(size_t l, const Scene& s);
  /// A sample of every lane not stopped.
  void observe(const SystemCoordinates& x);
  /// Lane l's last sample (a stopping crossing), its bodies rows first … of x: the lane stops there.
  void observe_last(size_t l, const SystemCoordinates& x, size_t first);

  /// Lane l's extrema as the row has them: for each of its bodies (then particles) and each column,
  /// min and max (NaN before any sample).
  void append_extrema(size_t l, std::vector<double>& row) const;
  /// NaN while undefined: no sample yet, or a quantity zero at t = 0 (a body at rest has no T₀).
  double energy_drift_max(size_t l) const;
  double angular_momentum_drift_max(size_t l) const;

 private:
  /// Per lane, for the drifts on packs: E₀, the energy's scale, L₀ and |L₀|, then each body's m and Λ.
  enum : size_t { kE0 = 0, kScale, kL0, kL0Norm = kL0 + 3, kPerLane };
  static size_t mass_of(size_t j) { return kPerLane + 4 * j; }
  /// Per lane: the drifts' maxima and whether it still runs (1) or stopped (0).
  enum : size_t { kEnergy = 0, kMomentum, kRunning, kState };

  /// Lanes l … l + W − 1 (W = 1 for double), whose body j is row row0 + j + w·stride: the extrema of
  /// the columns held as variables, and the drifts where they are packed.
  template <class T>
  void observe_packed(const BodyColumns& x, size_t l, size_t row0, size_t stride);
  template <class T, class Mask>
  void observe_drifts(const BodyColumns& x, size_t l, size_t row0, size_t stride, const Mask& running);
  /// Lane l's other extrema (columns computed from a body's state, and particles) at a sample, its
  /// bodies rows first … of x.
  void observe_extrema(size_t l, const SystemCoordinates& x, size_t first);
  /// Lane l's extrema and, when a DriftMonitor watches it, its drifts.
  void observe_unpacked(size_t l, const SystemCoordinates& x, size_t first);

  const EnsembleOutputs& o_;
  Formulation F_;
  size_t lanes_, n_;
  bool packed_drifts_ = false;           ///< the lanes' drifts are reduced on packs (else monitors_)
  std::vector<VariableColumn> columns_;  ///< the extrema's columns
  std::vector<std::pair<const BodyField*, int>> fields_;  ///< the same, for particles
  bool converted_ = false;  ///< some column is computed from a body's state (not a variable as it is)
  std::vector<const RigidBody*> bodies_;  ///< lane l's body j is bodies_[l·n + j]
  std::vector<std::optional<DriftMonitor>> monitors_;
  Columns constants_, state_;
  Columns lo_, hi_;  ///< column r·E + k: row r's (body, then particle) extremum k, one value per lane
  size_t rows_;      ///< bodies and particles of a lane
};

}  // namespace tumble
