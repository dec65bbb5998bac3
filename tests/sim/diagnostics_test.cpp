// The invariants from a run's variables (what a study observes at every sample) against those from its
// state (what tumble run's diagnostics hold), in every formulation.
#include <gtest/gtest.h>

#include "../support/random.hpp"
#include "tumble/forces/forces.hpp"
#include "tumble/integrate/integrator.hpp"
#include "tumble/sim/diagnostics.hpp"

namespace tumble {
namespace {

TEST(Diagnostics, InvariantsFromTheVariablesAreThoseOfTheState) {
  test::Random rng(21);
  Model model;
  for (int i = 0; i < 3; ++i) {
    model.add_body(
        RigidBody::from_principal_moments(rng.uniform(0.5, 2), Vec3(1, 2, 2.5) * rng.uniform(0.1, 1)));
  }
  model.add_particle(Particle{"p", 0.3});
  model.add_force<UniformGravity>(Vec3(0, 0, -9.81));
  SystemState s;
  for (int i = 0; i < 3; ++i) {
    s.bodies.push_back({rng.vec(-5, 5), Quat(rng.rotation()), rng.vec(-2, 2), rng.vec(-10, 10)});
  }
  s.particles.push_back({rng.vec(-1, 1), rng.vec(-1, 1)});
  const Invariants from_state = invariants(model, s);
  ASSERT_TRUE(from_state.potential_energy);
  for (const Formulation F : {Formulation::world, Formulation::mixed, Formulation::body}) {
    SCOPED_TRACE(formulation_name(F));
    SystemState scratch;
    const Invariants from_x = invariants(model, F, to_coordinates(F, s), 0, scratch);
    // The variables are the state's to one rotation's rounding (^bω = Rᵀω and back): a few ε relative.
    const double E = from_state.kinetic_energy;
    EXPECT_NEAR(from_x.kinetic_energy, E, 1e-14 * E);
    EXPECT_NEAR(*from_x.potential_energy, *from_state.potential_energy, 1e-14 * E);
    EXPECT_LT((from_x.linear_momentum - from_state.linear_momentum).norm(),
              1e-14 * from_state.linear_momentum.norm());
    EXPECT_LT((from_x.angular_momentum - from_state.angular_momentum).norm(),
              1e-14 * from_state.angular_momentum.norm());
    if (F == Formulation::mixed) {  // ^bω from the state is what the mixed variables hold: the same bits
      EXPECT_EQ(from_x.kinetic_energy, from_state.kinetic_energy);
      EXPECT_EQ(from_x.angular_momentum, from_state.angular_momentum);
    }
  }
  // A lane of a batch: the second body's run out of the three, with a model of its own.
  Model lane;
  lane.add_body(model.bodies[1]);
  SystemState alone{0.0, {s.bodies[1]}, {}};
  SystemState scratch;
  const Invariants of_lane =
      invariants(lane, Formulation::mixed, to_coordinates(Formulation::mixed, s), 1, scratch);
  const Invariants of_alone = invariants(lane, alone);
  EXPECT_EQ(of_lane.kinetic_energy, of_alone.kinetic_energy);
  EXPECT_EQ(of_lane.angular_momentum, of_alone.angular_momentum);
  EXPECT_EQ(*of_lane.potential_energy, 0.0);  // a model without forces has no potential
}

}  // namespace
}  // namespace tumble
