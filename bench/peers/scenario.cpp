#include "scenario.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace peers {
namespace {

/// splitmix64 (Steele, Lea & Flood 2014): a tiny generator whose output is fixed by its definition.
class SplitMix64 {
 public:
  explicit SplitMix64(std::uint64_t seed) : state_(seed) {}
  std::uint64_t next() {
    std::uint64_t z = (state_ += 0x9E3779B97F4A7C15ULL);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
    return z ^ (z >> 31);
  }
  /// Uniform in [0, 1), 53 random bits.
  double uniform() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }

 private:
  std::uint64_t state_;
};

}  // namespace

std::vector<BoxState> initial_boxes(std::size_t n, std::uint64_t seed) {
  constexpr double two_pi = 2 * std::numbers::pi;
  SplitMix64 rng(seed);
  // Centres on a cubic grid of spacing 1 m, side ⌈∛n⌉.
  std::size_t side = 1;
  while (side * side * side < n) ++side;
  std::vector<BoxState> boxes(n);
  for (std::size_t i = 0; i < n; ++i) {
    BoxState& b = boxes[i];
    b.position = {static_cast<double>(i % side), static_cast<double>((i / side) % side),
                  static_cast<double>(i / (side * side))};
    // Uniform random rotation (Shoemake 1992): from three uniforms, a point uniform on S³.
    const double u1 = rng.uniform(), u2 = rng.uniform(), u3 = rng.uniform();
    const double a = std::sqrt(1 - u1), c = std::sqrt(u1);
    const double x = a * std::sin(two_pi * u2), y = a * std::cos(two_pi * u2);
    const double z = c * std::sin(two_pi * u3), w = c * std::cos(two_pi * u3);
    b.q = {w, x, y, z};
    // A direction uniform on S²: cos θ uniform in [−1, 1], φ uniform.
    const double cz = 2 * rng.uniform() - 1, phi = two_pi * rng.uniform();
    const double sz = std::sqrt(std::max(0.0, 1 - cz * cz));
    b.omega = {kOmegaNorm * sz * std::cos(phi), kOmegaNorm * sz * std::sin(phi), kOmegaNorm * cz};
    b.velocity = {0.0, 0.0, 0.0};
  }
  return boxes;
}

double rotational_energy(const BoxState& box) {
  const auto& [w, x, y, z] = box.q;
  // Rows of R(q) for a unit quaternion: ω_b = Rᵀ ω has components (column j of R) · ω.
  const double R[3][3] = {{1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)},
                          {2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)},
                          {2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)}};
  double e = 0;
  for (int j = 0; j < 3; ++j) {
    const double wb = R[0][j] * box.omega[0] + R[1][j] * box.omega[1] + R[2][j] * box.omega[2];
    e += 0.5 * kMoments[static_cast<std::size_t>(j)] * wb * wb;
  }
  return e;
}

void Runner::run_sampled(long steps, long every, const SampleSink& sink) {
  std::vector<BoxState> boxes;
  for (long done = 0; done < steps;) {
    const long n = std::min(every, steps - done);
    advance(n);
    done += n;
    read(boxes);
    sink(done, boxes);
  }
}

}  // namespace peers
