#include "setting_options.hpp"

#include <fmt/format.h>

#include <algorithm>

namespace tumble::cli {

void SettingOptions::add_to(CLI::App& command, std::initializer_list<std::string_view> only) {
  for (const RunSetting& s : run_settings()) {
    if (only.size() > 0 && std::find(only.begin(), only.end(), s.key) == only.end()) continue;
    std::string help(s.help);
    if (s.kind == RunSetting::Kind::name) {
      help += fmt::format(" (one of: {})", fmt::join(s.choices(), ", "));
      command.add_option(std::string(s.flag), names_[s.key], help);
    } else if (s.kind == RunSetting::Kind::count) {  // CLI11 refuses a number that is not whole
      command.add_option(std::string(s.flag), counts_[s.key], help);
    } else {
      command.add_option(std::string(s.flag), numbers_[s.key], help);
    }
  }
}

void SettingOptions::apply(RunSettings& s) const {
  for (const RunSetting& setting : run_settings()) {
    if (const auto n = numbers_.find(setting.key); n != numbers_.end() && n->second) {
      set_run_setting(s, setting, *n->second, setting.flag);
    }
    if (const auto c = counts_.find(setting.key); c != counts_.end() && c->second) {
      set_run_setting(s, setting, static_cast<double>(*c->second), setting.flag);
    }
    if (const auto t = names_.find(setting.key); t != names_.end() && t->second) {
      set_run_setting(s, setting, *t->second, setting.flag);
    }
  }
}

}  // namespace tumble::cli
