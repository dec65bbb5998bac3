// EnsembleStudy: a study read from its scene file; run i's scene is the file with run i's draws, read by
// the scene reader. Running the runs into rows is the study layer's (study/runs.hpp).
#include "tumble/io/ensemble.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "ensemble_impl.hpp"
#include "tumble/sim/output_fields.hpp"

namespace tumble {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

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
  const scene::TomlFile file{path.string()};
  impl->root = scene::parse_toml(text, file);  // one tree, whose values each run's draws replace
  impl->study = ensemble::read_study(impl->root, file);
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
const std::vector<size_t>& EnsembleStudy::structural_columns() const { return impl_->structural_columns; }

std::vector<double> EnsembleStudy::draws(long i) const {
  std::vector<double> out;
  for (size_t v = 0; v < impl_->study.variations.size(); ++v) {
    const std::vector<double> d = ensemble::draw(impl_->study, v, i);
    out.insert(out.end(), d.begin(), d.end());
  }
  return out;
}

namespace {

/// Variation v's values among a run's draws (v.width of them, from `at`).
std::vector<double> values_of(const Variation& v, const std::vector<double>& values, size_t at) {
  return {values.begin() + static_cast<std::ptrdiff_t>(at),
          values.begin() + static_cast<std::ptrdiff_t>(at) + v.width};
}

}  // namespace

std::string EnsembleStudy::run_label(long i) const {
  const std::vector<double> values = draws(i);
  size_t at = 0;
  std::vector<std::string> said;
  for (const Variation& v : impl_->study.variations) {
    const std::vector<double> x = values_of(v, values, at);
    at += static_cast<size_t>(v.width);
    said.push_back(fmt::format("{} = {}", v.path,
                               x.size() == 1 ? fmt::format("{:.17g}", x[0])
                                             : fmt::format("[{:.17g}]", fmt::join(x, ", "))));
  }
  return fmt::format("run {} ({})", i, fmt::join(said, ", "));
}

Scene EnsembleStudy::scene_of_run(long i) const {
  const long runs[] = {i};
  const std::vector<double> values[] = {draws(i)};
  return std::move(scenes_of_runs(runs, values).front());
}

std::vector<Scene> EnsembleStudy::scenes_of_runs(std::span<const long> runs,
                                                 std::span<const std::vector<double>> values) const {
  toml::table root = impl_->root;
  std::vector<Scene> scenes;
  scenes.reserve(runs.size());
  for (size_t r = 0; r < runs.size(); ++r) {
    size_t at = 0;
    for (const Variation& v : impl_->study.variations) {
      set_values(root, v.path, values_of(v, values[r], at));
      at += static_cast<size_t>(v.width);
    }
    try {
      scenes.push_back(scene::read_scene(root, impl_->text, impl_->path));
    } catch (const SceneError& e) {
      // A drawn value is a node the draw made, which has no place in the file (toml++ gives it 0:0):
      // say so instead of a line 0.
      std::string what = e.what();
      const std::string nowhere = impl_->path.string() + ":0:0: ";
      if (what.rfind(nowhere, 0) == 0)
        what = impl_->path.string() + ", the drawn value: " + what.substr(nowhere.size());
      throw SceneError(fmt::format("{}: {}", run_label(runs[r]), what));
    }
  }
  return scenes;
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

}  // namespace tumble
