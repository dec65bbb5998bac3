// The counts of a run, from its settings alone (sim/run_plan.hpp).
#include "tumble/sim/run_plan.hpp"

#include <algorithm>
#include <cmath>

#include "tumble/integrate/integrator.hpp"
#include "tumble/sim/output_fields.hpp"

namespace tumble {

RunPlan plan_run(const RunSettings& s, std::size_t bodies, std::size_t particles, std::size_t columns) {
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
  const auto values = static_cast<double>(columns);
  p.csv_bytes = p.rows * (kCsvLead + kCsvValue * values) + p.samples * kCsvValue * diagnostics;
  p.hdf5_bytes = p.rows * 8 * values + p.samples * 8 * diagnostics;
  return p;
}

}  // namespace tumble
