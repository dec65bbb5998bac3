#pragma once
// Point masses (tutorial, section I): p = m v, τ = x × f, l = x × p, f = ṗ, τ = l̇.
#include <string>

#include "tumble/math/types.hpp"

namespace tumble {

struct Particle {
  std::string name = "particle";
  double mass = 1.0;  ///< m (kg)
};

struct ParticleState {
  Vec3 x = Vec3::Zero();  ///< position, world (m)
  Vec3 v = Vec3::Zero();  ///< velocity, world (m/s)
};

/// p = m v.
inline Vec3 momentum(const Particle& p, const ParticleState& s) { return p.mass * s.v; }
/// l = x × p, about the world origin (or about x₀: (x − x₀) × p).
inline Vec3 angular_momentum(const Particle& p, const ParticleState& s, const Vec3& x0 = Vec3::Zero()) {
  return (s.x - x0).cross(momentum(p, s));
}
/// τ = x × f, about the world origin (or about x₀).
inline Vec3 moment_of_force(const Vec3& x, const Vec3& f, const Vec3& x0 = Vec3::Zero()) {
  return (x - x0).cross(f);
}

}  // namespace tumble
