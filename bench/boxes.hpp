#pragma once
// The benchmarks' standard load: n boxes 0.1 × 0.2 × 0.3 m of density 1000 (m = 6 kg), |ω| = 10 rad/s
// in random directions, random attitudes, under g = 9.81 m/s² (batch_throughput, sensitivity_bench).
#include <random>

#include "tumble/forces/forces.hpp"
#include "tumble/forces/model.hpp"

namespace tumble::bench {

inline SystemState boxes(long n, Model& model) {
  const Vec3 Lambda(0.025, 0.05, 0.065);
  std::mt19937_64 rng(12345);
  std::normal_distribution<double> normal;
  SystemState s;
  for (long i = 0; i < n; ++i) {
    model.add_body(RigidBody::from_principal_moments(6.0, Lambda, "box"));
    const Quat q = Quat(normal(rng), normal(rng), normal(rng), normal(rng)).normalized();
    const Vec3 w = 10.0 * Vec3(normal(rng), normal(rng), normal(rng)).normalized();
    s.bodies.push_back(BodyState{Vec3(0, 0, 10), q, Vec3(1, 0, 2), w});
  }
  model.add_force<UniformGravity>(Vec3(0, 0, -9.81));
  return s;
}

}  // namespace tumble::bench
