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

#include "lane_samples.hpp"
#include "tumble/forces/stack.hpp"
#include "tumble/sim/event_specs.hpp"
#include "tumble/sim/output_fields.hpp"
#include "tumble/sim/simulate.hpp"

namespace tumble {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
/// At most this many runs are stepped together by run_ensemble: 32 packs of AVX-512 lanes, whose
/// variables, flows and samples stay in a core's L2 (512 ran the T-handle study ~5 % slower on one
/// thread), and small enough that the last batch leaves the other threads idle only briefly.
constexpr size_t kBatchRuns = 256;

}  // namespace

namespace {

/// A run's row, gathered as the run goes: its crossings, its last state (for the final values), and its
/// samples' extrema and drifts from lane `lane` of a LaneSamples (which the caller feeds the samples). The same code for a run simulated alone and for a lane of a batch, so their rows are
/// the same numbers.
class RowReducer {
 public:
  RowReducer(const EnsembleOutputs& outputs, const Scene& s, long run, std::vector<double> draws,
             const LaneSamples& samples, size_t lane)
      : o_(outputs), s_(s), n_(s.model.bodies.size()), samples_(samples), lane_(lane) {
    row_.run = run;
    row_.values = std::move(draws);
    tallies_.resize(s.events.size());
  }
  RowReducer(RowReducer&&) = default;

  /// Whether a stopping crossing has ended the run (its state is the run's last).
  bool stopped() const { return stopped_; }

  void on_event(const EventHit& hit) {
    Tally& t = tallies_[hit.index];
    if (t.count++ == 0) t.first = hit.state.t;
    t.last = hit.state.t;
    if (s_.events[hit.index].stop) {
      stopped_ = true;
      last_ = hit.state;
    }
  }

  /// The state the run ended in (what simulate returned; a lane's bodies of it), unless it stopped.
  void end(SystemState last) {
    if (!stopped_) last_ = std::move(last);
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
    samples_.append_extrema(lane_, v);
    const std::vector<const BodyField*> finals =
        o_.final_fields.empty() ? std::vector<const BodyField*>{} : body_fields(o_.final_fields, s_.model);
    for (size_t r = 0; r < n_ + s_.model.particles.size(); ++r) {
      for (const BodyField* f : finals) {
        double x[4];
        field_of_row(*f, s_.model, last_, r, x);
        v.insert(v.end(), x, x + f->width);
      }
    }
    if (o_.drift) {
      v.push_back(samples_.energy_drift_max(lane_));
      v.push_back(samples_.angular_momentum_drift_max(lane_));
    }
    return std::move(row_);
  }

 private:
  struct Tally {
    long count = 0;
    double first = kNaN, last = kNaN;
  };
  const EnsembleOutputs& o_;
  const Scene& s_;
  size_t n_;
  const LaneSamples& samples_;
  size_t lane_;
  EnsembleRow row_;
  std::vector<Tally> tallies_;
  bool stopped_ = false;
  SystemState last_;
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
                      const RunTrajectory& trajectory = {}) {
  LaneSamples samples(outputs, s.settings.formulation, 1, s.model.bodies.size(), s.model.particles.size());
  samples.add(0, s);
  RowReducer reducer(outputs, s, i, std::move(draws), samples, 0);
  RunHooks hooks;
  hooks.events = make_events(s.model, s.events);
  hooks.on_event = [&](const EventHit& hit) {
    reducer.on_event(hit);
    if (trajectory.event) trajectory.event(s, hit);
  };
  if (trajectory.sample) {
    hooks.on_sample = [&](const SystemState& state) {
      trajectory.sample(s, state);
      return true;
    };
  }
  hooks.on_variables = [&](const SystemCoordinates& x, size_t) {
    samples.observe(x);
    return true;
  };
  reducer.end(simulate(s.model, s.initial, study_settings(s), hooks));
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

EnsembleRow run_alone(const EnsembleStudy& study, long i, const RunTrajectory& trajectory) {
  const Scene s = study.scene_of_run(i);
  return naming_run(study, i, [&] { return run_alone(study.outputs(), s, i, study.draws(i), trajectory); });
}

std::vector<EnsembleRow> run_batch(const EnsembleStudy& study, std::span<const long> runs) {
  // Runs whose structural draws (anything but a body's values or an event's) are equal, bit for bit,
  // share their settings, force models and bodies' count: a group, stepped as one stacked system.
  std::vector<std::vector<double>> drawn;
  for (const long i : runs) drawn.push_back(study.draws(i));
  std::vector<Scene> scenes = study.scenes_of_runs(runs, drawn);
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
    // Every lane's sample at once (a stopping crossing's is its lane's alone, below).
    LaneSamples samples(study.outputs(), first.settings.formulation, group.size(), first.model.bodies.size());
    hooks.on_variables = [&samples](const SystemCoordinates& x, size_t) {
      samples.observe(x);
      return true;
    };
    for (size_t j = 0; j < group.size(); ++j) {
      const size_t k = group[j];
      const Scene& s = scenes[k];
      initial.bodies.insert(initial.bodies.end(), s.initial.bodies.begin(), s.initial.bodies.end());
      samples.add(j, s);
      RowReducer& reducer =
          reducers.emplace_back(study.outputs(), s, runs[k], std::move(drawn[k]), samples, j);
      Lane& lane = hooks.lanes.emplace_back();
      lane.model = &s.model;
      lane.label = [&study, run = runs[k]] { return study.run_label(run); };
      lane.events = make_events(s.model, s.events);
      // A stopping crossing's sample is the lane's alone: simulate hands it to the lane only, after
      // the crossing (on_event) and as its last.
      if (std::any_of(s.events.begin(), s.events.end(), [](const EventSpec& e) { return e.stop; })) {
        lane.on_variables = [&samples, &reducer, j](const SystemCoordinates& x, size_t row) {
          if (reducer.stopped()) samples.observe_last(j, x, row);
          return true;
        };
      }
      lane.on_event = [&reducer](const EventHit& hit) { reducer.on_event(hit); };
    }
    const SystemState end = simulate(*stacked, std::move(initial), study_settings(first), hooks);
    for (size_t j = 0; j < group.size(); ++j) {
      const size_t n = end.bodies.size() / group.size();
      SystemState last;
      last.t = end.t;
      last.bodies.assign(end.bodies.begin() + static_cast<std::ptrdiff_t>(j * n),
                         end.bodies.begin() + static_cast<std::ptrdiff_t>((j + 1) * n));
      reducers[j].end(std::move(last));
      rows[group[j]] = std::move(reducers[j]).row();
    }
  }
  return rows;
}

std::vector<EnsembleRow> run_ensemble(const EnsembleStudy& study, const std::vector<long>& runs, int threads,
                                      const std::function<void(const EnsembleRow&)>& done,
                                      const std::function<bool()>& stop) {
  require_thread_count(threads);
  const unsigned n = threads > 0 ? static_cast<unsigned>(threads)
                                 : std::max(1u, std::thread::hardware_concurrency());
  // Batches of consecutive runs, stepped together (run_batch): large enough to fill the
  // engine's packs and blocks many times over, small enough that every thread gets eight or more (a row
  // does not depend on the batch it is in) and that Ctrl-C, asked between batches, is answered soon.
  const size_t batch = std::clamp<size_t>(runs.size() / (8 * n), 1, kBatchRuns);
  const size_t batches = (runs.size() + batch - 1) / batch;
  std::vector<std::optional<EnsembleRow>> rows(runs.size());
  std::atomic<size_t> next{0};
  std::atomic<bool> halt{false};
  std::mutex lock;
  // The failure reported is the first run's, whatever thread meets it first: a batch before the one
  // that failed was claimed before it and still runs to its end.
  std::exception_ptr failure;
  size_t failed_batch = batches;
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
        if (b < failed_batch) failure = std::current_exception(), failed_batch = b;
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
