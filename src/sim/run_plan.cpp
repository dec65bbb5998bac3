// The counts of a run, from its settings alone (sim/run_plan.hpp).
#include "tumble/sim/run_plan.hpp"

#include <algorithm>
#include <cmath>

#include "tumble/integrate/integrator.hpp"
#include "tumble/sim/output_fields.hpp"

namespace tumble {

std::size_t hdf5_chunk_samples(std::size_t values, double samples) {
  const std::size_t block = std::max<std::size_t>(1, 65536 / std::max<std::size_t>(1, values));
  const double wanted = samples > 65536.0 ? 65536.0 : samples > 256.0 ? samples : 256.0;  // NaN: 256
  return std::min(block, static_cast<std::size_t>(wanted));
}

RunPlan plan_run(const RunSettings& s, std::size_t bodies, std::size_t particles,
                 std::span<const int> field_widths) {
  RunPlan p;
  // As simulate() steps: from each sample, steps of h, the last one shortened to land on the next
  // sample time (a remainder within 1e-9 h of it is the rounding of the grid, not a step).
  const double h = s.timestep, dt_out = s.output_interval > 0 ? s.output_interval : h;
  const double full = std::floor(s.duration / dt_out + 1e-9);  // whole intervals
  const double rest = s.duration - full * dt_out;              // a last, shorter one
  const bool partial = rest > 1e-9 * h;
  p.samples = full + 1 + (partial ? 1 : 0);
  if (!is_adaptive(s.integrator)) {
    auto steps_over = [&](double interval) { return std::max(1.0, std::ceil(interval / h - 1e-9)); };
    p.steps = full * steps_over(dt_out) + (partial ? steps_over(rest) : 0);
  }
  const auto rows_per_sample = static_cast<double>(bodies + particles);
  p.rows = p.samples * rows_per_sample;
  // CSV: t and the name (about 30 bytes), then each value as "-1.2345678901234567e-300," (at most 25).
  constexpr double kCsvValue = 25, kCsvLead = 30;
  double diagnostics = 1;  // t, then the energies, momenta and drifts
  for (const SystemField& f : system_fields()) diagnostics += f.width;
  double columns = 0;
  for (const int w : field_widths) columns += w;
  p.csv_bytes = p.rows * (kCsvLead + kCsvValue * columns) + p.samples * kCsvValue * diagnostics;
  // HDF5: each dataset in whole chunks of 8-byte values, and a record of its own (object header,
  // attributes, chunk index: about 2 kB a dataset), plus the file's own (superblock, groups, names:
  // 4 kB) and the records of the geometry group's ten datasets (their values, the display meshes,
  // come on top). Measured against written files in run_cli_test (CheckPlansTheHdf5File...).
  constexpr double kDatasetRecord = 2048, kFileRecord = 4096 + 10 * kDatasetRecord;
  const auto dataset = [&](double values) {
    const auto chunk = static_cast<double>(hdf5_chunk_samples(static_cast<std::size_t>(values), p.samples));
    return std::ceil(p.samples / chunk) * chunk * values * 8 + kDatasetRecord;
  };
  p.hdf5_bytes = kFileRecord + dataset(1);  // t
  for (const int w : field_widths) p.hdf5_bytes += dataset(rows_per_sample * w);
  for (const SystemField& f : system_fields()) p.hdf5_bytes += dataset(f.width);
  return p;
}

}  // namespace tumble
