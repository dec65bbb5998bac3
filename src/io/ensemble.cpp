// EnsembleStudy: run i of a study is the scene file with run i's draws, read by the scene reader and
// simulated alone; its row holds the draws and the outputs [ensemble.outputs] asks for.
#include "tumble/io/ensemble.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <atomic>
#include <bit>
#include <cmath>
#include <limits>
#include <map>
#include <mutex>
#include <thread>

#include "ensemble_impl.hpp"
#include "tumble/forces/stack.hpp"
#include "tumble/sim/drift_monitor.hpp"
#include "tumble/sim/event_specs.hpp"
#include "tumble/sim/output_fields.hpp"

namespace tumble {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
/// At most this many runs are stepped together by run_ensemble.
constexpr size_t kBatchRuns = 512;

struct EnsembleStudy::Impl {
  std::string text;
  std::filesystem::path path;
  toml::table root;
  ensemble::Study study;
  Scene base;
  std::vector<std::string> columns;
  size_t draw_columns = 0;
  std::vector<std::string> rows;  // the base scene's bodies and particles
  /// The draw columns (after "run") of variations that change a run's structure: anything but the
  /// values of a body (mass, shape, initial state) or of an event, which stay within the run's lane.
  std::vector<size_t> structural_columns;
};

namespace {

/// Sets the number (or the numbers of the array) at `path` in a scene's TOML.
void set_values(toml::table& root, const std::string& path, const std::vector<double>& values) {
  std::string error;
  toml::node* node = ensemble::resolve(root, path, error);
  if (node == nullptr) throw InvalidArgument(error);  // checked when the study was read
  if (values.size() > 1) {
    toml::array& a = *node->as_array();
    for (size_t k = 0; k < values.size(); ++k)
      a.replace(a.cbegin() + static_cast<std::ptrdiff_t>(k), values[k]);
    return;
  }
  if (auto* f = node->as_floating_point()) {
    f->get() = values[0];
    return;
  }
  // An integer in the file: replaced by a float through its parent (a node cannot change its type).
  if (path.back() == ']') {
    const size_t open = path.rfind('[');
    toml::array& a = *ensemble::resolve(root, path.substr(0, open), error)->as_array();
    const auto k = static_cast<std::ptrdiff_t>(std::stoul(path.substr(open + 1)));
    a.replace(a.cbegin() + k, values[0]);
    return;
  }
  const size_t dot = path.rfind('.');
  toml::table& parent =
      dot == std::string::npos ? root : *ensemble::resolve(root, path.substr(0, dot), error)->as_table();
  parent.insert_or_assign(dot == std::string::npos ? path : path.substr(dot + 1), values[0]);
}

std::uint64_t fnv1a(std::string_view text) {
  std::uint64_t h = 0xcbf29ce484222325ull;
  for (const char c : text) h = (h ^ static_cast<unsigned char>(c)) * 0x100000001b3ull;
  return h;
}

/// The output columns of a study whose base scene is `s` (after "run" and the draws).
std::vector<std::string> output_columns(const EnsembleOutputs& o, const Scene& s,
                                        const std::vector<std::string>& rows) {
  std::vector<std::string> c;
  if (o.events) {
    for (const EventSpec& e : s.events) {
      for (const char* what : {"count", "first_t", "mean_interval"})
        c.push_back(fmt::format("{}.{}", e.name, what));
    }
  }
  for (const std::string& row : rows) {
    for (const std::string& column : o.extrema) {
      c.push_back(fmt::format("{}.{}_min", row, column));
      c.push_back(fmt::format("{}.{}_max", row, column));
    }
  }
  const std::vector<const BodyField*> finals = o.final_fields.empty() ? std::vector<const BodyField*>{}
                                                                      : body_fields(o.final_fields);
  for (const std::string& row : rows) {
    for (const BodyField* f : finals) {
      for (int k = 0; k < f->width; ++k)
        c.push_back(fmt::format("{}.{}_final", row, f->columns[static_cast<size_t>(k)]));
    }
  }
  if (o.drift) {
    c.emplace_back("energy_drift_max");
    c.emplace_back("angular_momentum_drift_max");
  }
  return c;
}

}  // namespace

EnsembleStudy::EnsembleStudy(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
EnsembleStudy::EnsembleStudy(EnsembleStudy&&) noexcept = default;
EnsembleStudy& EnsembleStudy::operator=(EnsembleStudy&&) noexcept = default;
EnsembleStudy::~EnsembleStudy() = default;

EnsembleStudy EnsembleStudy::parse(const std::string& text, const std::filesystem::path& path) {
  auto impl = std::make_unique<Impl>();
  impl->text = text;
  impl->path = path;
  impl->root = scene::parse_toml(text, path.string());
  impl->study = ensemble::read_study(impl->root, path.string());
  impl->base = scene::read_scene(impl->root, text, path);
  impl->rows = row_names(impl->base.model);
  impl->columns = {"run"};
  for (const Variation& v : impl->study.variations) {
    const bool within_lane = v.path.starts_with("bodies.") || v.path.starts_with("events.");
    for (size_t k = 0; k < v.names.size(); ++k) {
      if (!within_lane) impl->structural_columns.push_back(impl->columns.size() - 1 + k);
    }
    impl->columns.insert(impl->columns.end(), v.names.begin(), v.names.end());
  }
  impl->draw_columns = impl->columns.size() - 1;
  const auto outputs = output_columns(impl->study.outputs, impl->base, impl->rows);
  impl->columns.insert(impl->columns.end(), outputs.begin(), outputs.end());
  const EnsembleOutputs& o = impl->study.outputs;
  if (o.worst > 0 &&
      std::find(impl->columns.begin(), impl->columns.end(), o.worst_by) == impl->columns.end()) {
    throw SceneError(
        fmt::format("{}: [ensemble.outputs] trajectories: by = \"{}\" is not a column of the table; "
                    "the columns are: {}",
                    path.string(), o.worst_by, fmt::join(impl->columns, ", ")));
  }
  return EnsembleStudy(std::move(impl));
}

EnsembleStudy EnsembleStudy::load(const std::filesystem::path& scene) {
  return parse(scene::read_file(scene), scene);
}

long EnsembleStudy::runs() const { return impl_->study.runs; }
std::uint64_t EnsembleStudy::seed() const { return impl_->study.seed; }
const std::vector<Variation>& EnsembleStudy::variations() const { return impl_->study.variations; }
const EnsembleOutputs& EnsembleStudy::outputs() const { return impl_->study.outputs; }
const Scene& EnsembleStudy::base() const { return impl_->base; }
std::uint64_t EnsembleStudy::fingerprint() const { return fnv1a(impl_->text); }
const std::vector<std::string>& EnsembleStudy::columns() const { return impl_->columns; }

std::vector<double> EnsembleStudy::draws(long i) const {
  std::vector<double> out;
  for (size_t v = 0; v < impl_->study.variations.size(); ++v) {
    const std::vector<double> d = ensemble::draw(impl_->study, v, i);
    out.insert(out.end(), d.begin(), d.end());
  }
  return out;
}

Scene EnsembleStudy::scene_of_run(long i) const {
  toml::table root = impl_->root;
  const std::vector<double> values = draws(i);
  size_t at = 0;
  std::vector<std::string> said;
  for (const Variation& v : impl_->study.variations) {
    const std::vector<double> x(values.begin() + static_cast<std::ptrdiff_t>(at),
                                values.begin() + static_cast<std::ptrdiff_t>(at) + v.width);
    at += static_cast<size_t>(v.width);
    set_values(root, v.path, x);
    said.push_back(fmt::format("{} = {}", v.path,
                               x.size() == 1 ? fmt::format("{:.17g}", x[0])
                                             : fmt::format("[{:.17g}]", fmt::join(x, ", "))));
  }
  try {
    return scene::read_scene(root, impl_->text, impl_->path);
  } catch (const SceneError& e) {
    throw SceneError(fmt::format("run {} ({}): {}", i, fmt::join(said, ", "), e.what()));
  }
}

namespace {

/// A run's row, gathered as the run goes from its samples (its variables, unconverted: VariableColumn,
/// DriftMonitor::observe of variables) and crossings: the same code for a run simulated alone and for a
/// lane of a batch, so their rows are the same numbers.
class RowReducer {
 public:
  RowReducer(const EnsembleOutputs& outputs, const Scene& s, long run, std::vector<double> draws)
      : o_(outputs), s_(s), F_(s.settings.formulation), n_(s.model.bodies.size()) {
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
    copy_bodies(x, first, n_, last_);
    last_.particles = x.particles;
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

}  // namespace

EnsembleRow EnsembleStudy::run(
    long i, const std::function<void(const Scene&, const SystemState&)>& trajectory) const {
  return run_alone(impl_->study.outputs, scene_of_run(i), i, draws(i), trajectory);
}

std::vector<EnsembleRow> EnsembleStudy::run_batch(std::span<const long> runs) const {
  // Runs whose structural draws (anything but a body's values or an event's) are equal, bit for bit,
  // share their settings, force models and bodies' count: a group, stepped as one stacked system.
  std::vector<Scene> scenes;
  scenes.reserve(runs.size());
  std::vector<std::vector<double>> drawn;
  for (const long i : runs) {
    scenes.push_back(scene_of_run(i));
    drawn.push_back(draws(i));
  }
  std::vector<std::vector<size_t>> groups;
  {
    std::map<std::vector<std::uint64_t>, size_t> group_of;
    for (size_t k = 0; k < runs.size(); ++k) {
      std::vector<std::uint64_t> key;
      for (const size_t c : impl_->structural_columns)
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
      for (const size_t k : group)
        rows[k] = run_alone(impl_->study.outputs, scenes[k], runs[k], std::move(drawn[k]));
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
      RowReducer& reducer = reducers.emplace_back(impl_->study.outputs, s, runs[k], std::move(drawn[k]));
      Lane& lane = hooks.lanes.emplace_back();
      lane.model = &s.model;
      lane.label = fmt::format("run {}", runs[k]);
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

std::vector<ColumnSummary> summarize(const std::vector<std::string>& columns,
                                     const std::vector<EnsembleRow>& rows) {
  std::vector<ColumnSummary> out;
  for (size_t c = 1; c < columns.size(); ++c) {
    ColumnSummary s;
    s.column = columns[c];
    std::vector<double> x;
    for (const EnsembleRow& r : rows) {
      if (std::isfinite(r.values[c - 1])) x.push_back(r.values[c - 1]);
    }
    s.count = static_cast<long>(x.size());
    s.histogram.assign(20, 0);
    if (x.empty()) {
      s.mean = s.std = s.min = s.max = s.q05 = s.q25 = s.q50 = s.q75 = s.q95 = kNaN;
      out.push_back(std::move(s));
      continue;
    }
    // Mean and standard deviation in two passes (the second on the deviations: no cancellation).
    double sum = 0;
    for (double v : x) sum += v;
    s.mean = sum / static_cast<double>(x.size());
    double squares = 0;
    for (double v : x) squares += (v - s.mean) * (v - s.mean);
    s.std = x.size() > 1 ? std::sqrt(squares / static_cast<double>(x.size() - 1)) : 0.0;
    std::sort(x.begin(), x.end());
    s.min = x.front();
    s.max = x.back();
    const auto quantile = [&x](double p) {  // linear between order statistics (R's type 7)
      const double h = (static_cast<double>(x.size()) - 1) * p;
      const auto k = static_cast<size_t>(std::floor(h));
      return k + 1 < x.size() ? x[k] + (h - static_cast<double>(k)) * (x[k + 1] - x[k]) : x[k];
    };
    s.q05 = quantile(0.05);
    s.q25 = quantile(0.25);
    s.q50 = quantile(0.5);
    s.q75 = quantile(0.75);
    s.q95 = quantile(0.95);
    const double width = (s.max - s.min) / 20;
    for (double v : x) {
      const auto bin = width > 0 ? std::min<long>(19, static_cast<long>((v - s.min) / width)) : 0;
      ++s.histogram[static_cast<size_t>(bin)];
    }
    out.push_back(std::move(s));
  }
  return out;
}

std::vector<long> every_run(const EnsembleStudy& study) {
  std::vector<long> runs(static_cast<size_t>(study.runs()));
  for (size_t i = 0; i < runs.size(); ++i) runs[i] = static_cast<long>(i);
  return runs;
}

std::vector<EnsembleRow> run_ensemble(const EnsembleStudy& study, const std::vector<long>& runs, int threads,
                                      const std::function<void(const EnsembleRow&)>& done,
                                      const std::function<bool()>& stop) {
  const unsigned n = threads > 0 ? static_cast<unsigned>(threads)
                                 : std::max(1u, std::thread::hardware_concurrency());
  // Batches of consecutive runs, stepped together (EnsembleStudy::run_batch): large enough to fill the
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
            study.run_batch(std::span<const long>(runs).subspan(begin, count));
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
