#include "tumble/sim/finite_difference_stm.hpp"

#include <cmath>

#include <fmt/format.h>

#include "tumble/dynamics/tangent.hpp"
#include "tumble/error.hpp"

namespace tumble {

Eigen::MatrixXd stm_by_central_differences(const Model& model, const SystemState& initial,
                                           const RunSettings& settings, double epsilon) {
  if (!model.particles.empty()) {
    throw InvalidArgument("finite-difference sensitivities take rigid bodies only: the system has particles");
  }
  if (!(std::isfinite(epsilon) && epsilon > 0)) {
    throw InvalidArgument(
        fmt::format("finite-difference step {} is invalid: give a small positive number", epsilon));
  }
  const std::size_t B = model.bodies.size();
  // The bodies' states as their reference frames (the tangent space's), and back.
  const auto moved = [&](std::size_t body, const Tangent& delta) {
    SystemState s = initial;
    const RigidBody& rb = model.bodies[body];
    const ReferenceFrameState r = perturbed(reference_state(rb, initial.bodies[body]), delta);
    s.bodies[body] = state_from_reference(rb, r.position, r.orientation, r.velocity, r.omega_w, Frame::world);
    return s;
  };
  Eigen::MatrixXd stm(12 * B, 12 * B);
  for (std::size_t b = 0; b < B; ++b) {
    for (int j = 0; j < 12; ++j) {
      Tangent delta = Tangent::Zero();
      delta[j] = epsilon;
      const SystemState plus = simulate(model, moved(b, delta), settings);
      const SystemState minus = simulate(model, moved(b, -delta), settings);
      for (std::size_t row = 0; row < B; ++row) {
        const RigidBody& rb = model.bodies[row];
        stm.block<12, 1>(static_cast<Eigen::Index>(12 * row), static_cast<Eigen::Index>(12 * b + j)) =
            tangent_between(reference_state(rb, minus.bodies[row]), reference_state(rb, plus.bodies[row])) /
            (2 * epsilon);
      }
    }
  }
  return stm;
}

}  // namespace tumble
