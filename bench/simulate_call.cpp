// The C++ side of bench/python_overhead.py: the time of one simulate() call on a scene file, with
// every sample's output fields copied into growing arrays as tumble.simulate does in Python, so that
// the two differ only by what Python adds (argument conversion, the GIL, building the NumPy result).
//
//   simulate_call SCENE REPEATS  ->  one line per repeat: seconds of the call (scene loaded once)
#include <fmt/format.h>

#include <chrono>
#include <cstdlib>
#include <vector>

#include "tumble/io/scene.hpp"
#include "tumble/sim/output_fields.hpp"

int main(int argc, char** argv) try {
  if (argc != 3) {
    fmt::print(stderr, "usage: simulate_call SCENE REPEATS\n");
    return 2;
  }
  using namespace tumble;
  const Scene scene = load_scene(argv[1]);
  RunSettings settings = scene.settings;
  settings.threads = 1;  // as bench/python_overhead.py asks of tumble.simulate
  const std::vector<const BodyField*> fields = body_fields(scene.output_fields);
  const int repeats = std::atoi(argv[2]);
  const size_t rows = scene.model.bodies.size() + scene.model.particles.size();
  for (int r = 0; r < repeats; ++r) {
    const auto start = std::chrono::steady_clock::now();
    std::vector<double> t;
    std::vector<std::vector<double>> values(fields.size());
    simulate(scene.model, scene.initial, settings, [&](const SystemState& state) {
      t.push_back(state.t);
      for (size_t f = 0; f < fields.size(); ++f) {
        const auto w = static_cast<size_t>(fields[f]->width);
        for (size_t i = 0; i < rows; ++i) {
          values[f].resize(values[f].size() + w);
          field_of_row(*fields[f], scene.model, state, i, values[f].data() + values[f].size() - w);
        }
      }
      return true;
    });
    const std::chrono::duration<double> seconds = std::chrono::steady_clock::now() - start;
    fmt::print("{:.9g}\n", seconds.count());
  }
  return 0;
} catch (const std::exception& e) {
  fmt::print(stderr, "simulate_call: {}\n", e.what());
  return 1;
}
