#include <cpptoml.h>

#include <sstream>

#include "readers.hpp"

void parse_cpptoml(const std::string& text, const std::string&) {
  std::istringstream s(text);
  cpptoml::parser p(s);
  const auto t = p.parse();
  (void)t;
}
