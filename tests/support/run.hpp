#pragma once
// Runs the tumble program as a user would and captures what it prints.
#include <array>
#include <cstdio>
#include <string>
#include <sys/wait.h>

namespace tumble::test {

struct CommandResult {
  int status;          // exit status
  std::string output;  // stdout and stderr together
};

/// Runs a shell command line as given and captures what it prints on stdout. The status is the exit
/// status, or 128 + N when signal N ended the shell (as shells report it).
inline CommandResult run_shell_command(const std::string& command) {
  FILE* pipe = popen(command.c_str(), "r");
  if (pipe == nullptr) return {-1, "popen failed"};
  std::string out;
  std::array<char, 4096> buffer;
  size_t n;
  while ((n = fread(buffer.data(), 1, buffer.size(), pipe)) > 0) out.append(buffer.data(), n);
  const int raw = pclose(pipe);
  return {WIFEXITED(raw) ? WEXITSTATUS(raw) : 128 + WTERMSIG(raw), out};
}

/// Runs `TUMBLE_CLI args` through the shell (stderr merged into stdout).
inline CommandResult run_tumble(const std::string& args) {
  return run_shell_command(std::string(TUMBLE_CLI) + " " + args + " 2>&1");
}

/// The numbers that follow `"key":` in JSON text, in order (flattening nested arrays).
inline std::vector<double> json_numbers(const std::string& json, const std::string& key) {
  std::vector<double> values;
  const auto at = json.find("\"" + key + "\":");
  if (at == std::string::npos) return values;
  size_t i = at + key.size() + 3;
  int depth = 0;
  while (i < json.size()) {
    const char c = json[i];
    if (c == '[') ++depth;
    if (c == ']' && --depth <= 0) break;
    if ((c == ',' || c == '\n') && depth == 0) break;
    if (c == '-' || (c >= '0' && c <= '9')) {
      size_t used = 0;
      values.push_back(std::stod(json.substr(i), &used));
      i += used;
      continue;
    }
    ++i;
  }
  return values;
}

}  // namespace tumble::test
