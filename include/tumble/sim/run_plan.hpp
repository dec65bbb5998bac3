#pragma once
// What a run will do, known before it starts: how many steps and samples, and how many bytes its
// outputs will take. `tumble check` states it and `tumble run` refuses runs that would not end in a
// day or would fill a disk (unless --force), so that `duration = 1e300` or an output interval of
// 1e-300 s is a message, not a process that runs until it is killed.
#include <cstddef>
#include <optional>
#include <span>

#include "tumble/sim/simulate.hpp"

namespace tumble {

struct RunPlan {
  /// Steps of a fixed-step integrator: ⌈Δ/h⌉ per output interval Δ (the last step of each is
  /// shortened to land on the sample time), so ⌈duration/h⌉ when Δ is a multiple of h; nullopt for
  /// adaptive integrators, whose count depends on the tolerances.
  std::optional<double> steps;
  /// Samples written, the initial and the final state included: ⌈duration/Δ⌉ + 1 (Δ = h when the
  /// output interval is 0).
  double samples = 0;
  /// Rows of the trajectory: samples × (bodies + particles).
  double rows = 0;
  /// Bytes of the outputs: the trajectory and the diagnostics (one row per sample). CSV: an upper
  /// bound (the widest rows, 17 significant digits; a tumbling body writes about 0.7 of it, a body at
  /// rest less). HDF5: 8 bytes a value in whole chunks (hdf5_chunk_samples), every diagnostic and the
  /// datasets' own records; the geometry group and the scene's text come on top.
  double csv_bytes = 0, hdf5_bytes = 0;
};

/// The plan of a run of `settings` (validated) for `bodies` and `particles`, with per-body output
/// fields of the given widths (their columns, sim/output_fields.hpp).
RunPlan plan_run(const RunSettings& settings, std::size_t bodies, std::size_t particles,
                 std::span<const int> field_widths = {});

/// Samples in one chunk of an HDF5 dataset whose sample holds `values` numbers, for a run planned to
/// write `samples`: about 64 Ki values (512 KiB), large enough to write fast and small enough for
/// HDF5's chunk cache, but no more than the run writes (a chunk is stored whole, so six samples in
/// chunks of 21 845 made a 6 MB file), and not below 256 samples, so that a run that writes more
/// than planned (a resumed one) still writes in blocks.
std::size_t hdf5_chunk_samples(std::size_t values, double samples);

/// Runs whose counts no clock or file could hold: more steps or samples than a double counts exactly
/// (2⁵³), which is also where a step stops advancing the clock t₀ + n·h. validate(RunSettings)
/// refuses them.
inline constexpr double kMaxCount = 9007199254740992.0;  // 2⁵³

}  // namespace tumble
