#include "tumble/integrate/system_coordinates.hpp"

#include <cstring>

#include <fmt/format.h>

#include <cmath>

#include "tumble/math/huge_pages.hpp"
#include "tumble/math/simd.hpp"

namespace tumble {

SystemCoordinates to_coordinates(Formulation formulation, const SystemState& state) {
  SystemCoordinates x;
  x.t = state.t;
  x.bodies.resize(state.bodies.size());
  for (size_t i = 0; i < state.bodies.size(); ++i)
    x.bodies.store(i, to_coordinates(formulation, state.bodies[i]));
  x.particles = state.particles;
  return x;
}

void to_state(Formulation formulation, const SystemCoordinates& x, SystemState& s) {
  s.t = x.t;
  if (s.bodies.capacity() < x.bodies.size()) {
    s.bodies.reserve(x.bodies.size());
    prefer_huge_pages(s.bodies);
  }
  s.bodies.resize(x.bodies.size());
  for (size_t i = 0; i < x.bodies.size(); ++i) s.bodies[i] = to_state(formulation, x.bodies.load(i));
  s.particles = x.particles;
}

void to_state(Formulation formulation, const SystemCoordinates& x, size_t first, size_t n,
              SystemState& part) {
  part.t = x.t;
  part.bodies.resize(n);
  for (size_t i = 0; i < n; ++i) part.bodies[i] = to_state(formulation, x.bodies.load(first + i));
  part.particles.clear();
}

SystemState to_state(Formulation formulation, const SystemCoordinates& x) {
  SystemState s;
  to_state(formulation, x, s);
  return s;
}

size_t first_non_finite_body(const SystemCoordinates& x) {
  // x·0 is 0 for a finite x and NaN for ±∞ and NaN: one sum per column finds out whether to look closer.
  // Summed in packs over the padded columns (padding holds finite values): eight independent sums, not
  // one chain of dependent additions, which cost as much as an RK4 step.
  using Pack = xsimd::batch<double>;
  const size_t n = x.bodies.size();
  Pack sum(0.0);
  for (size_t k = 0; k < BodyColumns::kCount; ++k) {
    const double* c = x.bodies[k];
    for (size_t i = 0; i < x.bodies.stride(); i += Pack::size) sum += Pack::load_aligned(c + i) * Pack(0.0);
  }
  if (std::isfinite(xsimd::hadd(sum))) return n;
  for (size_t i = 0; i < n; ++i) {
    for (size_t k = 0; k < BodyColumns::kCount; ++k) {
      if (!std::isfinite(x.bodies[k][i])) return i;
    }
  }
  return n;
}

void copy_bodies(const SystemCoordinates& x, size_t first, size_t n, SystemCoordinates& part) {
  part.t = x.t;
  part.bodies.ensure(n);
  for (size_t k = 0; k < BodyColumns::kCount; ++k) {
    const double* from = x.bodies[k] + first;
    double* to = part.bodies[k];
    for (size_t i = 0; i < n; ++i) to[i] = from[i];  // a lane holds a body or a few: no call to memcpy
  }
  part.particles.clear();
}

std::string first_non_finite(const Model& model, const SystemCoordinates& x) {
  if (const size_t i = first_non_finite_body(x); i < x.bodies.size())
    return fmt::format("body '{}'", model.bodies[i].name());
  for (size_t i = 0; i < x.particles.size(); ++i) {
    if (!x.particles[i].x.allFinite() || !x.particles[i].v.allFinite()) {
      return fmt::format("particle '{}'", model.particles[i].name);
    }
  }
  return {};
}

}  // namespace tumble

namespace tumble {

bool same_variables(const SystemCoordinates& x, const BodyColumns& bodies,
                    const std::vector<ParticleState>& particles) {
  if (x.bodies.size() != bodies.size() || x.particles.size() != particles.size()) return false;
  for (size_t k = 0; k < BodyColumns::kCount; ++k) {
    if (std::memcmp(x.bodies[k], bodies[k], bodies.size() * sizeof(double)) != 0) return false;
  }
  for (size_t i = 0; i < particles.size(); ++i) {
    if (x.particles[i].x != particles[i].x || x.particles[i].v != particles[i].v) return false;
  }
  return true;
}

}  // namespace tumble
