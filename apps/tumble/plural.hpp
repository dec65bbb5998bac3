#pragma once
// "1 body", "2 bodies": counts for messages.
#include <fmt/format.h>

#include <string>

namespace tumble::cli {

inline std::string count(size_t n, const char* one, const char* many) {
  return fmt::format("{} {}", n, n == 1 ? one : many);
}

}  // namespace tumble::cli
