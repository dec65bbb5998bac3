#include <toml++/toml.h>

#include "readers.hpp"

void parse_tomlpp(const std::string& text, const std::string& name) {
  const toml::table t = toml::parse(text, name);
  (void)t;
}
