#pragma once
// The command-line options that override a scene's run settings (--timestep, --integrator, …), made
// from the table of sim/run_settings.hpp: one option per setting, its help from the table.
#include <CLI/CLI.hpp>
#include <map>
#include <optional>
#include <string>
#include <string_view>

#include "tumble/sim/run_settings.hpp"

namespace tumble::cli {

class SettingOptions {
 public:
  /// Adds an option per setting to `command`; `only` limits them to these keys (all when empty).
  void add_to(CLI::App& command, std::initializer_list<std::string_view> only = {});
  /// The settings given on the command line, on top of `s` (unchecked: validate() judges them).
  void apply(RunSettings& s) const;

 private:
  std::map<std::string_view, std::optional<double>> numbers_;  // by key; stable addresses for CLI11
  std::map<std::string_view, std::optional<long>> counts_;
  std::map<std::string_view, std::optional<std::string>> names_;
};

}  // namespace tumble::cli
