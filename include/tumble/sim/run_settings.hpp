#pragma once
// The settings of a run, each described once: the scene reader's [simulation] keys, the options of
// tumble run and tumble check that override them, the keywords of tumble.simulate, their help, and
// the table of docs/scene-format.md (tests/sim/run_settings_test.cpp holds the docs and a checkpoint
// to it) are made from this one table. A new setting is a field of RunSettings and a row here.
#include <span>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "tumble/sim/simulate.hpp"

namespace tumble {

struct RunSetting {
  enum class Kind { number, count, name };  ///< a double; a whole number; a name among choices()
  enum class Range { finite, positive, non_negative };
  std::string_view key;   ///< the [simulation] key and the Python keyword, e.g. "output_interval"
  std::string_view flag;  ///< the command-line option, e.g. "--output-interval"
  Kind kind;
  Range range;            ///< for numbers and counts
  std::string_view unit;  ///< SI, e.g. "s"; "" for a pure number or a name
  /// The default as a scene file reads it ("required" where the scene must give it); runs built
  /// without a scene (RunSettings{}) start from the struct's defaults.
  std::string_view scene_default;
  bool in_scene;          ///< whether [simulation] has it (threads: the command line and Python only)
  std::string_view help;  ///< one line for --help, the docs and Python
  /// The setting's value in a RunSettings (a double, or a name), and setting it (from a value that
  /// set_run_setting checked).
  std::variant<double, std::string> (*get)(const RunSettings&);
  void (*set)(RunSettings&, const std::variant<double, std::string>&);
  std::vector<std::string> (*choices)() = nullptr;  ///< Kind::name: the valid names
};

/// Every setting, in the order the docs list them.
std::span<const RunSetting> run_settings();
/// The setting with this key or flag ("timestep", "--timestep"); nullptr if there is none.
const RunSetting* find_run_setting(std::string_view key_or_flag);

/// A value given for a setting: a number (numbers and counts) or a name.
using SettingValue = std::variant<double, std::string>;

/// Sets one setting of `s` from a value of its kind (a whole number for a count); InvalidArgument says
/// what `given_as` ("--timestep", "timestep=") was given and what it takes. The value itself is judged
/// by validate(), as for a scene's settings.
void set_run_setting(RunSettings& s, const RunSetting& setting, const SettingValue& value,
                     std::string_view given_as);

}  // namespace tumble
