#include <sstream>
#include <toml.hpp>

#include "readers.hpp"

void parse_toml11(const std::string& text, const std::string& name) {
  std::istringstream s(text);
  const auto v = toml::parse(s, name);
  (void)v;
}
