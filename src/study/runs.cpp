// Running a study's runs into rows (study/runs.hpp): a run alone, or the runs of a batch that share a
// structure stepped together as lanes of one stacked system, each reduced into its row as it goes.
#include "tumble/study/runs.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <atomic>
#include <bit>
#include <cmath>
#include <limits>
#include <map>
#include <mutex>
#include <optional>
#include <thread>

#include "tumble/forces/stack.hpp"
#include "tumble/sim/drift_monitor.hpp"
#include "tumble/sim/event_specs.hpp"
#include "tumble/sim/output_fields.hpp"

namespace tumble {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
/// At most this many runs are stepped together by run_ensemble.
constexpr size_t kBatchRuns = 512;

}  // namespace

namespace {

/// A run's row, gathered as the run goes from its samples (its variables, unconverted: VariableColumn,
/// DriftMonitor::observe of variables) and crossings: the same code for a run simulated alone and for a
/// lane of a batch, so their rows are the same numbers.
class RowReducer {
 public:
  RowReducer(const EnsembleOutputs& outputs, const Scene& s, long run, std::vector<double> draws)
      : o_(outputs),
        s_(s),
        F_(s.settings.formulation),
        n_(s.model.bodies.size()),
        t_end_(s.initial.t + s.settings.duration) {
    row_.run = run;
    row_.values = std::move(draws);
    if (o_.drift) {
      SystemState scratch;
      const Invariants at_start = invariants(s.model, F_, to_coordinates(F_, s.initial), 0, scratch);
      monitor_.emplace(s.model, at_start, s.conserved, 0.0, s.settings);
    }
    for (const std::string& c : o_.extrema) {
      const auto [field, k] = *find_column(c);
      extrema_.emplace_back(*field, k);
    }
    const size_t rows = n_ + s.model.particles.size();
    lo_.assign(rows * extrema_.size(), kNaN);
    hi_.assign(rows * extrema_.size(), kNaN);
    tallies_.resize(s.events.size());
  }
  RowReducer(RowReducer&&) = default;

  void on_event(const EventHit& hit) {
    stopping_ = s_.events[hit.index].stop;  // its state comes next, as the run's last sample
    Tally& t = tallies_[hit.index];
    if (t.count++ == 0) t.first = hit.state.t;
    t.last = hit.state.t;
  }

  /// A sample: the run's bodies are rows first … first + n − 1 of x.
  bool on_variables(const SystemCoordinates& x, size_t first) {
    if (monitor_) {
      const DriftSample d = monitor_->observe(x, first);
      if (d.energy_drift) energy_drift_ = larger(energy_drift_, std::abs(*d.energy_drift));
      if (d.angular_momentum_drift)
        momentum_drift_ = larger(momentum_drift_, std::abs(*d.angular_momentum_drift));
    }
    const size_t E = extrema_.size();
    for (size_t r = 0; r < n_; ++r) {
      for (size_t k = 0; k < E; ++k)
        take(r * E + k, extrema_[k].column(s_.model.bodies[r], x.bodies, first + r, F_));
    }
    for (size_t p = 0; p < x.particles.size(); ++p) {  // a run alone may have particles
      for (size_t k = 0; k < E; ++k) {
        double v[4];
        extrema_[k].field->of_particle(x.particles[p], v);
        take((n_ + p) * E + k, v[extrema_[k].component]);
      }
    }
    // The last sample's variables, for the final values: the sample at the end time, or the state of a
    // stopping event (copied only then, not at every sample).
    if (x.t >= t_end_ || stopping_ || last_.bodies.size() == 0) {
      copy_bodies(x, first, n_, last_);
      last_.particles = x.particles;
    }
    return true;
  }

  EnsembleRow row() && {
    std::vector<double>& v = row_.values;
    if (o_.events) {
      for (const Tally& t : tallies_) {
        v.push_back(static_cast<double>(t.count));
        v.push_back(t.first);
        v.push_back(t.count > 1 ? (t.last - t.first) / static_cast<double>(t.count - 1) : kNaN);
      }
    }
    for (size_t i = 0; i < lo_.size(); ++i) {
      v.push_back(lo_[i]);
      v.push_back(hi_[i]);
    }
    const std::vector<const BodyField*> finals = o_.final_fields.empty() ? std::vector<const BodyField*>{}
                                                                         : body_fields(o_.final_fields);
    const SystemState last = to_state(F_, last_);
    for (size_t r = 0; r < n_ + s_.model.particles.size(); ++r) {
      for (const BodyField* f : finals) {
        double x[4];
        field_of_row(*f, s_.model, last, r, x);
        v.insert(v.end(), x, x + f->width);
      }
    }
    if (o_.drift) {
      v.push_back(energy_drift_);
      v.push_back(momentum_drift_);
    }
    return std::move(row_);
  }

 private:
  static double larger(double current, double x) { return std::isnan(current) || x > current ? x : current; }
  void take(size_t at, double v) {
    double& l = lo_[at];
    double& h = hi_[at];
    l = std::isnan(l) || v < l ? v : l;
    h = larger(h, v);
  }
  struct Tally {
    long count = 0;
    double first = kNaN, last = kNaN;
  };
  struct Extremum {
    Extremum(const BodyField& f, int k) : field(&f), component(k), column(f, k) {}
    const BodyField* field;
    int component;
    VariableColumn column;
  };
  const EnsembleOutputs& o_;
  const Scene& s_;
  Formulation F_;
  size_t n_;
  std::optional<DriftMonitor> monitor_;
  EnsembleRow row_;
  std::vector<Extremum> extrema_;  // per (row, column): min and max
  std::vector<double> lo_, hi_;
  std::vector<Tally> tallies_;
  double energy_drift_ = kNaN, momentum_drift_ = kNaN;
  double t_end_;
  bool stopping_ = false;   // the last crossing ends the run: its state is the last sample
  SystemCoordinates last_;  // the variables at the last sample
};

/// The settings a run of a study is simulated with: the runs are spread over the threads, not the
/// bodies of one run.
RunSettings study_settings(const Scene& s) {
  RunSettings settings = s.settings;
  settings.threads = 1;
  return settings;
}

/// Run i of a study simulated alone, from its scene: its row.
EnsembleRow run_alone(const EnsembleOutputs& outputs, const Scene& s, long i, std::vector<double> draws,
                      const std::function<void(const Scene&, const SystemState&)>& trajectory = {}) {
  RowReducer reducer(outputs, s, i, std::move(draws));
  RunHooks hooks;
  hooks.events = make_events(s.model, s.events);
  hooks.on_event = [&](const EventHit& hit) { reducer.on_event(hit); };
  if (trajectory) {
    hooks.on_sample = [&](const SystemState& state) {
      trajectory(s, state);
      return true;
    };
  }
  hooks.on_variables = [&](const SystemCoordinates& x, size_t first) {
    return reducer.on_variables(x, first);
  };
  simulate(s.model, s.initial, study_settings(s), hooks);
  return std::move(reducer).row();
}

/// f(), with run i and its draws named in an error of its run (a blow-up, an event that is not finite).
template <class F>
EnsembleRow naming_run(const EnsembleStudy& study, long i, const F& f) {
  try {
    return f();
  } catch (const InvalidArgument& e) {
    throw InvalidArgument(fmt::format("{}: {}", study.run_label(i), e.what()));
  } catch (const Error& e) {
    throw Error(fmt::format("{}: {}", study.run_label(i), e.what()));
  }
}

}  // namespace

EnsembleRow run_alone(const EnsembleStudy& study, long i,
                      const std::function<void(const Scene&, const SystemState&)>& trajectory) {
  const Scene s = study.scene_of_run(i);
  return naming_run(study, i, [&] { return run_alone(study.outputs(), s, i, study.draws(i), trajectory); });
}

std::vector<EnsembleRow> run_batch(const EnsembleStudy& study, std::span<const long> runs) {
  // Runs whose structural draws (anything but a body's values or an event's) are equal, bit for bit,
  // share their settings, force models and bodies' count: a group, stepped as one stacked system.
  std::vector<Scene> scenes;
  scenes.reserve(runs.size());
  std::vector<std::vector<double>> drawn;
  for (const long i : runs) {
    scenes.push_back(study.scene_of_run(i));
    drawn.push_back(study.draws(i));
  }
  std::vector<std::vector<size_t>> groups;
  {
    std::map<std::vector<std::uint64_t>, size_t> group_of;
    for (size_t k = 0; k < runs.size(); ++k) {
      std::vector<std::uint64_t> key;
      for (const size_t c : study.structural_columns())
        key.push_back(std::bit_cast<std::uint64_t>(drawn[k][c]));
      const auto [it, fresh] = group_of.try_emplace(std::move(key), groups.size());
      if (fresh) groups.emplace_back();
      groups[it->second].push_back(k);
    }
  }
  std::vector<EnsembleRow> rows(runs.size());
  for (const std::vector<size_t>& group : groups) {
    const Scene& first = scenes[group.front()];
    std::vector<const Model*> models;
    for (const size_t k : group) models.push_back(&scenes[k].model);
    std::optional<Model> stacked;
    if (group.size() > 1 && !is_adaptive(first.settings.integrator)) stacked = stack_runs(models);
    if (!stacked) {  // each run alone
      for (const size_t k : group) {
        rows[k] = naming_run(study, runs[k], [&] {
          return run_alone(study.outputs(), scenes[k], runs[k], std::move(drawn[k]));
        });
      }
      continue;
    }
    SystemState initial;
    initial.t = first.initial.t;
    std::vector<RowReducer> reducers;
    reducers.reserve(group.size());
    RunHooks hooks;
    for (const size_t k : group) {
      const Scene& s = scenes[k];
      initial.bodies.insert(initial.bodies.end(), s.initial.bodies.begin(), s.initial.bodies.end());
      RowReducer& reducer = reducers.emplace_back(study.outputs(), s, runs[k], std::move(drawn[k]));
      Lane& lane = hooks.lanes.emplace_back();
      lane.model = &s.model;
      lane.label = study.run_label(runs[k]);
      lane.events = make_events(s.model, s.events);
      lane.on_variables = [&reducer](const SystemCoordinates& x, size_t row) {
        return reducer.on_variables(x, row);
      };
      lane.on_event = [&reducer](const EventHit& hit) { reducer.on_event(hit); };
    }
    simulate(*stacked, std::move(initial), study_settings(first), hooks);
    for (size_t j = 0; j < group.size(); ++j) rows[group[j]] = std::move(reducers[j]).row();
  }
  return rows;
}

std::vector<EnsembleRow> run_ensemble(const EnsembleStudy& study, const std::vector<long>& runs, int threads,
                                      const std::function<void(const EnsembleRow&)>& done,
                                      const std::function<bool()>& stop) {
  const unsigned n = threads > 0 ? static_cast<unsigned>(threads)
                                 : std::max(1u, std::thread::hardware_concurrency());
  // Batches of consecutive runs, stepped together (run_batch): large enough to fill the
  // engine's packs and blocks many times over, small enough that every thread gets several (a row
  // does not depend on the batch it is in) and that Ctrl-C, asked between batches, is answered soon.
  const size_t batch = std::clamp<size_t>(runs.size() / (4 * n), 1, kBatchRuns);
  const size_t batches = (runs.size() + batch - 1) / batch;
  std::vector<std::optional<EnsembleRow>> rows(runs.size());
  std::atomic<size_t> next{0};
  std::atomic<bool> halt{false};
  std::mutex lock;
  std::exception_ptr failure;
  const auto work = [&] {
    for (;;) {
      const size_t b = next.fetch_add(1);
      if (b >= batches || halt.load()) return;
      const size_t begin = b * batch, count = std::min(batch, runs.size() - begin);
      try {
        std::vector<EnsembleRow> computed =
            run_batch(study, std::span<const long>(runs).subspan(begin, count));
        const std::lock_guard<std::mutex> guard(lock);
        for (size_t k = 0; k < count; ++k) {
          if (done) done(computed[k]);
          rows[begin + k] = std::move(computed[k]);
        }
        if (stop && stop()) halt = true;
      } catch (...) {
        const std::lock_guard<std::mutex> guard(lock);
        if (!failure) failure = std::current_exception();
        halt = true;
        return;
      }
    }
  };
  {
    std::vector<std::jthread> pool;
    for (unsigned t = 1; t < std::min<size_t>(n, batches); ++t) pool.emplace_back(work);
    work();
  }
  if (failure) std::rethrow_exception(failure);
  std::vector<EnsembleRow> out;
  for (auto& r : rows) {
    if (r) out.push_back(std::move(*r));
  }
  return out;
}

}  // namespace tumble
