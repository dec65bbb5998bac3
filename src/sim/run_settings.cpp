#include "tumble/sim/run_settings.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "tumble/error.hpp"

namespace tumble {
namespace {

using Value = std::variant<double, std::string>;
using K = RunSetting::Kind;
using R = RunSetting::Range;

double number(const Value& v) { return std::get<double>(v); }
const std::string& text(const Value& v) { return std::get<std::string>(v); }

std::vector<std::string> formulations() { return {"world", "mixed", "body"}; }

// clang-format off
const RunSetting kSettings[] = {
    {"duration", "--duration", K::number, R::non_negative, "s", "required", true,
     "simulated time (s)",
     [](const RunSettings& s) -> Value { return s.duration; },
     [](RunSettings& s, const Value& v) { s.duration = number(v); }},
    {"timestep", "--timestep", K::number, R::positive, "s", "1e-3", true,
     "step h (s); for adaptive integrators the first trial step",
     [](const RunSettings& s) -> Value { return s.timestep; },
     [](RunSettings& s, const Value& v) { s.timestep = number(v); }},
    {"integrator", "--integrator", K::name, R::finite, "", "\"rk4\"", true,
     "time integrator",
     [](const RunSettings& s) -> Value { return s.integrator; },
     [](RunSettings& s, const Value& v) { s.integrator = text(v); },
     integrator_names},
    {"formulation", "--formulation", K::name, R::finite, "", "\"mixed\"", true,
     "frame of the integrated velocities (tutorial §VII)",
     [](const RunSettings& s) -> Value { return formulation_name(s.formulation); },
     [](RunSettings& s, const Value& v) { s.formulation = parse_formulation(text(v)); },
     formulations},
    {"output_interval", "--output-interval", K::number, R::non_negative, "s", "0.01", true,
     "time between samples (s); 0 = every step",
     [](const RunSettings& s) -> Value { return s.output_interval; },
     [](RunSettings& s, const Value& v) { s.output_interval = number(v); }},
    {"rtol", "--rtol", K::number, R::positive, "", "1e-9", true,
     "relative tolerance of adaptive integrators",
     [](const RunSettings& s) -> Value { return s.tolerances.relative; },
     [](RunSettings& s, const Value& v) { s.tolerances.relative = number(v); }},
    {"atol", "--atol", K::number, R::positive, "", "1e-12", true,
     "absolute tolerance of adaptive integrators",
     [](const RunSettings& s) -> Value { return s.tolerances.absolute; },
     [](RunSettings& s, const Value& v) { s.tolerances.absolute = number(v); }},
    {"drift_threshold", "--drift-threshold", K::number, R::non_negative, "", "1e-6", true,
     "warn when a conserved energy or angular momentum drifts by more than this, relative to t = 0 "
     "(0 = never)",
     [](const RunSettings& s) -> Value { return s.drift_threshold; },
     [](RunSettings& s, const Value& v) { s.drift_threshold = number(v); }},
    {"threads", "--threads", K::count, R::non_negative, "", "1", false,
     "threads for fixed-step integrators (default 1; 0 = one per core); worth it from a few thousand "
     "bodies; results are bit-identical for any count",
     [](const RunSettings& s) -> Value { return static_cast<double>(s.threads); },
     [](RunSettings& s, const Value& v) { s.threads = static_cast<int>(number(v)); }},
};
// clang-format on

}  // namespace

std::span<const RunSetting> run_settings() { return kSettings; }

const RunSetting* find_run_setting(std::string_view key_or_flag) {
  for (const RunSetting& s : kSettings) {
    if (s.key == key_or_flag || s.flag == key_or_flag) return &s;
  }
  return nullptr;
}

void set_run_setting(RunSettings& s, const RunSetting& setting, const SettingValue& value,
                     std::string_view given_as) {
  // Only the kind is checked here: validate() judges the values (its messages say how to fix them), and
  // setting an unknown formulation throws parse_formulation's message.
  if (setting.kind == RunSetting::Kind::name) {
    if (!std::holds_alternative<std::string>(value))
      throw InvalidArgument(
          fmt::format("{} takes a name, one of: {}", given_as, fmt::join(setting.choices(), ", ")));
    setting.set(s, value);
    return;
  }
  const double* x = std::get_if<double>(&value);
  if (x == nullptr) throw InvalidArgument(fmt::format("{} takes a number, not a name", given_as));
  if (setting.kind == RunSetting::Kind::count &&
      !(std::isfinite(*x) && *x == std::floor(*x) && std::abs(*x) < 1e9)) {
    throw InvalidArgument(fmt::format("{} {} is invalid: give a whole number", given_as, *x));
  }
  setting.set(s, value);
}

}  // namespace tumble
