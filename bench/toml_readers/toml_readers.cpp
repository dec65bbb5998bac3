// The C++ TOML readers Debian 12 packages, on the same scene files: toml++ 3.3 (what tumble reads scenes
// with), toml11 3.7 and cpptoml 0.1.1. Each file is parsed into the reader's document tree and the tree
// freed, REPEATS times, in one process; the time is the minimum. Each reader is also given the
// mistakes of a scene file that tests/apps/catalogue_test.cpp's messages name by line and column, to see
// whether its errors say where. Built and run by bench/toml_readers.sh.
//   toml_readers FILE.toml [REPEATS]
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>
#include <string>

#include "readers.hpp"

namespace {

using Clock = std::chrono::steady_clock;

double best_of(int repeats, const std::function<void()>& parse) {
  double best = 1e300;
  for (int r = 0; r < repeats; ++r) {
    const auto t0 = Clock::now();
    parse();
    best = std::min(best, std::chrono::duration<double>(Clock::now() - t0).count());
  }
  return best;
}

/// The first line of what a reader says about `text`, or "(accepted)".
std::string error_of(const std::string& text, const std::function<void(const std::string&)>& parse) {
  try {
    parse(text);
    return "(accepted)";
  } catch (const std::exception& e) {
    std::string m = e.what();
    for (char& c : m) c = c == '\n' ? ' ' : c;
    return m.substr(0, 160);
  }
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: toml_readers FILE.toml [REPEATS]\n");
    return 2;
  }
  const int repeats = argc > 2 ? std::atoi(argv[2]) : 3;
  std::ifstream in(argv[1], std::ios::binary);
  std::stringstream buffer;
  buffer << in.rdbuf();
  const std::string text = buffer.str();
  size_t tables = 0;
  for (size_t at = text.find("[[bodies]]"); at != std::string::npos; at = text.find("[[bodies]]", at + 1))
    ++tables;
  // The file's name, not its path: the output is kept in bench/results.
  const std::string file = std::filesystem::path(argv[1]).filename().string();
  std::printf("# %s: %zu bytes, %zu [[bodies]] tables; best of %d, parse and free the tree\n", file.c_str(),
              text.size(), tables, repeats);
  const auto per = [&](double s) { return tables ? 1e6 * s / static_cast<double>(tables) : 0.0; };

  const std::string name = argv[1];
  std::printf("%-12s %10s %14s\n", "reader", "s", "us per table");
  const auto time = [&](const char* reader, void (*parse)(const std::string&, const std::string&)) {
    try {
      const double s = best_of(repeats, [&] { parse(text, name); });
      std::printf("%-12s %10.3f %14.2f\n", reader, s, per(s));
    } catch (const std::exception& e) {  // a reader that refuses a valid file is out
      std::printf("%-12s refused the file: %s\n", reader, e.what());
    }
  };
  time("toml++", parse_tomlpp);
  time("toml11", parse_toml11);
  time("cpptoml", parse_cpptoml);

  // Do their errors say where? A value missing after '=', on line 3, column 12.
  const std::string bad = "[simulation]\nduration = 1\ntimestep = \n";
  std::printf("\nthe error for a value missing on line 3:\n");
  std::printf("  toml++:  %s\n",
              error_of(bad, [](const std::string& t) { parse_tomlpp(t, "s.toml"); }).c_str());
  std::printf("  toml11:  %s\n",
              error_of(bad, [](const std::string& t) { parse_toml11(t, "s.toml"); }).c_str());
  std::printf("  cpptoml: %s\n",
              error_of(bad, [](const std::string& t) { parse_cpptoml(t, "s.toml"); }).c_str());
  return 0;
}
