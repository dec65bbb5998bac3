// The batched engine's promises (src/integrate/engine.hpp): a step allocates nothing; a body's result
// does not depend on the bodies around it, on the thread count, or on whether the step runs fused
// (block by block) or staged (stage by stage over the system) — bit for bit; forces written over
// columns equal the same forces written per body.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "../support/allocation_counter.hpp"
#include "../support/random.hpp"
#include "tumble/forces/forces.hpp"
#include "tumble/integrate/integrator.hpp"

namespace tumble {
namespace {

const std::vector<std::string> kFixedStep = {
    "euler", "semi_implicit_euler", "rk4", "lie_rk4", "implicit_gyro", "splitting", "splitting4", "midpoint"};
const Formulation kFormulations[] = {Formulation::world, Formulation::mixed, Formulation::body};

/// n different bodies (masses, moments, reference offsets) in random states, spinning at a few rad/s.
struct Bodies {
  std::vector<RigidBody> bodies;
  SystemState state;
};
Bodies random_bodies(size_t n, unsigned seed) {
  test::Random rng(seed);
  Bodies b;
  for (size_t i = 0; i < n; ++i) {
    std::string name = "b";
    name += std::to_string(i);  // (not "b" + …: GCC 12 warns falsely, -Wrestrict)
    b.bodies.push_back(RigidBody::from_mass_properties(rng.body(), name));
    b.state.bodies.push_back(BodyState{rng.vec(-1, 1), Quat(rng.rotation()), rng.vec(-1, 1), rng.vec(-5, 5)});
  }
  return b;
}

/// Gravity, and damping on every body (a model that reads velocities, so world v and ω are formed).
/// Without the damping no body feels a torque: splitting then continues each body's free flow from
/// step to step instead of setting up a new one (splitting.cpp), a path of its own to test.
void add_local_forces(Model& model, bool damped = true) {
  model.add_force<UniformGravity>(Vec3(0.3, -0.2, -9.81));
  if (damped) model.add_force<ViscousDamping>(all_bodies, 0.05, 0.002);
}

/// A system model (not local) that adds nothing: its presence alone makes steps staged.
class NoForce final : public ForceModel {
 public:
  void accumulate(const SystemView&, Loads&) const override {}
  std::string describe(std::span<const RigidBody>) const override { return "nothing"; }
};

SystemCoordinates run_steps(const Model& model, const SystemState& s0, const std::string& name, Formulation F,
                            int steps, int threads = 1) {
  SystemCoordinates x = to_coordinates(F, s0);
  auto integrator = make_integrator(name);
  integrator->set_threads(threads);
  for (int k = 0; k < steps; ++k) integrator->step(model, F, x, 2e-3);
  return x;
}

/// Body i of a equals body j of b in every variable, bit for bit.
bool same_body(const SystemCoordinates& a, size_t i, const SystemCoordinates& b, size_t j) {
  for (size_t k = 0; k < BodyColumns::kCount; ++k) {
    if (std::memcmp(&a.bodies[k][i], &b.bodies[k][j], sizeof(double)) != 0) return false;
  }
  return true;
}

TEST(Batch, AStepAllocatesNothingAfterTheFirst) {
  // 20 bodies: three packs of up to 8, with padding lanes. Local forces (fused steps), then a spring
  // between two bodies and a particle (staged steps, the system part).
  for (const auto& [staged, damped] :
       {std::pair{false, true}, std::pair{true, true}, std::pair{false, false}}) {
    Bodies b = random_bodies(20, 7);
    Model model;
    for (const RigidBody& body : b.bodies) model.add_body(body);
    add_local_forces(model, damped);
    if (staged) {
      model.add_particle(Particle{"p", 0.5});
      b.state.particles.push_back(ParticleState{Vec3(0, 0, 1), Vec3(0.1, 0, 0)});
      model.add_force<Spring>(Spring::End{0, Vec3::Zero()}, Spring::End{1, Vec3::Zero()}, 10.0, 0.5, 0.1);
      model.add_force<Spring>(Spring::End{2, Vec3::Zero()}, Spring::End{all_bodies, Vec3::Zero(), 0}, 5.0,
                              0.2, 0.0);
    }
    for (const std::string& name : kFixedStep) {
      SystemCoordinates x = to_coordinates(Formulation::mixed, b.state);
      auto integrator = make_integrator(name);
      integrator->step(model, Formulation::mixed, x, 1e-4);  // binds the integrator, sizes its workspace
      test::CountAllocations counting;
      for (int k = 0; k < 10000; ++k) integrator->step(model, Formulation::mixed, x, 1e-4);
      EXPECT_EQ(counting.count(), 0) << name << (staged ? " (staged)" : " (fused)")
                                     << (damped ? "" : ", no torque");
    }
  }
}

TEST(Batch, ABodyStepsTheSameAloneAsAmongOthersBitForBit) {
  // 37 bodies (padding in the last pack); each body is also stepped alone (N = 1, one lane of a pack
  // used). Every integrator, every formulation.
  const Bodies b = random_bodies(37, 11);
  for (const bool damped : {true, false}) {
    Model all;
    for (const RigidBody& body : b.bodies) all.add_body(body);
    add_local_forces(all, damped);
    for (const std::string& name : kFixedStep) {
      for (const Formulation F : kFormulations) {
        const SystemCoordinates together = run_steps(all, b.state, name, F, 5);
        for (const size_t i : {size_t{0}, size_t{9}, size_t{36}}) {
          Model one;
          one.add_body(b.bodies[i]);
          add_local_forces(one, damped);
          const SystemCoordinates alone =
              run_steps(one, SystemState{0.0, {b.state.bodies[i]}, {}}, name, F, 5);
          EXPECT_TRUE(same_body(together, i, alone, 0))
              << name << ", " << formulation_name(F) << ", body " << i << (damped ? "" : ", no torque");
        }
      }
    }
  }
}

TEST(Batch, ResultsAreBitIdenticalForAnyThreadCount) {
  // 1000 bodies: 16 blocks, split differently among 1, 2 and 3 threads.
  // Undamped, only the spring's two bodies can feel a torque: splitting keeps the others' free flows.
  const Bodies b = random_bodies(1000, 13);
  for (const bool damped : {true, false}) {
    Model model;
    for (const RigidBody& body : b.bodies) model.add_body(body);
    add_local_forces(model, damped);
    model.add_force<Spring>(Spring::End{3, Vec3::Zero()}, Spring::End{998, Vec3::Zero()}, 10.0, 0.5,
                            0.1);  // couples two blocks
    for (const std::string& name : kFixedStep) {
      const SystemCoordinates one = run_steps(model, b.state, name, Formulation::mixed, 3, 1);
      for (const int threads : {2, 3}) {
        const SystemCoordinates many = run_steps(model, b.state, name, Formulation::mixed, 3, threads);
        size_t differing = 0;
        for (size_t i = 0; i < 1000; ++i) differing += same_body(one, i, many, i) ? 0 : 1;
        EXPECT_EQ(differing, 0u) << name << " with " << threads << " threads"
                                 << (damped ? "" : ", no torque");
      }
    }
  }
}

TEST(Batch, FusedAndStagedStepsAreBitIdentical) {
  // The same system with and without a system model that adds nothing: fused steps without it, staged
  // steps with it. 300 bodies span several blocks.
  const Bodies b = random_bodies(300, 17);
  for (const bool damped : {true, false}) {
    Model fused, staged;
    for (const RigidBody& body : b.bodies) fused.add_body(body), staged.add_body(body);
    add_local_forces(fused, damped);
    add_local_forces(staged, damped);
    staged.add_force<NoForce>();
    for (const std::string& name : kFixedStep) {
      for (const Formulation F : kFormulations) {
        const SystemCoordinates a = run_steps(fused, b.state, name, F, 4),
                                c = run_steps(staged, b.state, name, F, 4);
        size_t differing = 0;
        for (size_t i = 0; i < 300; ++i) differing += same_body(a, i, c, i) ? 0 : 1;
        EXPECT_EQ(differing, 0u) << name << ", " << formulation_name(F) << (damped ? "" : ", no torque");
      }
    }
  }
}

TEST(Batch, AForceOverColumnsEqualsTheSameForcePerBody) {
  // A thrust along each body's own x axis plus a drag-like torque, written once as a BlockCallback
  // (columns, once per block) and once as BodyCallbacks (one body at a time): the same loads, the same
  // motion bit for bit.
  const Bodies b = random_bodies(50, 19);
  auto wrench = [](const BodyState& s) { return Wrench{s.q * Vec3(2.0, 0, 0), -0.01 * s.omega_w}; };
  Model columns, per_body;
  for (const RigidBody& body : b.bodies) columns.add_body(body), per_body.add_body(body);
  columns.add_force<BlockCallback>([&](const BodyBlock& block, BlockLoads& loads) {
    for (size_t j = 0; j < block.count; ++j) {
      const Wrench w = wrench(block.state(j));
      loads.add(j, w.force, w.torque);
    }
  });
  for (size_t i = 0; i < b.bodies.size(); ++i) {
    per_body.add_force<BodyCallback>(i,
                                     [&](double, const RigidBody&, const BodyState& s) { return wrench(s); });
  }
  for (const char* name : {"rk4", "splitting", "midpoint"}) {
    const SystemCoordinates a = run_steps(columns, b.state, name, Formulation::mixed, 5);
    const SystemCoordinates c = run_steps(per_body, b.state, name, Formulation::mixed, 5);
    for (size_t i = 0; i < b.bodies.size(); ++i) EXPECT_TRUE(same_body(a, i, c, i)) << name << ", body " << i;
  }
}

TEST(Batch, ABlockCallbackTrapOscillatesAtSqrtKOverM) {
  // The README's example: f = −k o on every body, written over columns. Bodies of different masses
  // released at rest oscillate as x₀ cos(√(k/m) t). RK4's phase error on an oscillator is
  // (ωh)⁴ ωt/120 to leading order (its amplification factor matches e^{iωh} to (ωh)⁴/24 and loses
  // (ωh)⁵/120 of phase a step); allowed twice that, plus rounding.
  const double k = 40.0;
  Model model;
  SystemState s0;
  for (int i = 0; i < 20; ++i) {
    model.add_body(RigidBody::from_principal_moments(0.5 + 0.25 * i, Vec3(0.1, 0.2, 0.25), "b"));
    s0.bodies.push_back(BodyState{Vec3(1.0 + i, -2.0, 0.5), Quat::Identity(), Vec3::Zero(), Vec3(0, 3, 0)});
  }
  model.add_force<BlockCallback>(
      [k](const BodyBlock& b, BlockLoads& loads) {
        for (size_t c = 0; c < 3; ++c)
          for (size_t j = 0; j < b.count; ++j) loads.f[c][j] -= k * b.o[c][j];
      },
      "harmonic trap", false);
  SystemCoordinates x = to_coordinates(Formulation::mixed, s0);
  auto integrator = make_integrator("rk4");
  for (int n = 0; n < 1000; ++n) integrator->step(model, Formulation::mixed, x, 1e-3);
  for (size_t i = 0; i < 20; ++i) {
    const double w = std::sqrt(k / model.bodies[i].mass());
    const Vec3 expected = s0.bodies[i].o * std::cos(w * x.t);
    const double phase_error = std::pow(w * 1e-3, 4) * w * x.t / 120;
    EXPECT_LT((x.bodies.vec3(BodyColumns::o, i) - expected).norm(),
              (2 * phase_error + 1e-14) * s0.bodies[i].o.norm())
        << "body " << i;
  }
}

TEST(Batch, ManyStepsAtOnceEqualStepByStepBitForBit) {
  // Integrator::steps(count) — fused integrators take each block through all the steps in cache —
  // must be count calls of step(), bit for bit, including the time every force sees: a force that
  // depends on t (a rotating thrust) on every body, fused (local forces only) and staged (plus a system
  // model), 130 bodies over three blocks, on 2 threads.
  const Bodies b = random_bodies(130, 29);
  Model fused, staged;
  for (const RigidBody& body : b.bodies) fused.add_body(body), staged.add_body(body);
  for (Model* m : {&fused, &staged}) {
    add_local_forces(*m);
    m->add_force<BlockCallback>(
        [](const BodyBlock& block, BlockLoads& loads) {
          const Vec3 thrust(std::cos(3 * block.t), std::sin(3 * block.t), 0.5);
          for (size_t j = 0; j < block.count; ++j) loads.add(j, thrust, 0.01 * thrust);
        },
        "rotating thrust", false);
  }
  staged.add_force<NoForce>();
  const double h = 1.7e-3;  // not a binary fraction: the accumulated times round
  for (const Model* model : {&fused, &staged}) {
    for (const std::string& name : kFixedStep) {
      for (const Formulation F : kFormulations) {
        SystemCoordinates one = to_coordinates(F, b.state), many = one;
        one.t = many.t = 0.3;
        auto a = make_integrator(name), c = make_integrator(name);
        a->set_threads(2);
        c->set_threads(2);
        for (int k = 0; k < 11; ++k) a->step(*model, F, one, h);
        c->steps(*model, F, many, h, 11);
        size_t differing = 0;
        for (size_t i = 0; i < b.bodies.size(); ++i) differing += same_body(one, i, many, i) ? 0 : 1;
        EXPECT_EQ(differing, 0u) << name << ", " << formulation_name(F)
                                 << (model == &staged ? ", staged" : "");
        EXPECT_EQ(one.t, many.t) << name;
      }
    }
  }
  EXPECT_TRUE(make_integrator("rk4")->fuses_steps(fused));
  EXPECT_FALSE(make_integrator("rk4")->fuses_steps(staged));
}

TEST(Batch, TheEngineNeedsAtMost400BytesPerBody) {
  // State and constants are the only whole-system arrays of a fused step (17 doubles, 136 bytes per
  // body); the stage variables live in per-thread block scratch, a fixed size. Everything the state and
  // the integrator allocate is counted, at 10⁵ bodies.
  const size_t n = 100000;
  const Bodies b = random_bodies(n, 23);
  Model model;
  for (const RigidBody& body : b.bodies) model.add_body(body);
  add_local_forces(model);
  for (const char* name : {"rk4", "lie_rk4", "semi_implicit_euler", "euler"}) {
    test::CountAllocations counting;
    SystemCoordinates x = to_coordinates(Formulation::mixed, b.state);
    auto integrator = make_integrator(name);
    integrator->step(model, Formulation::mixed, x, 1e-3);
    EXPECT_LE(static_cast<double>(counting.bytes()) / static_cast<double>(n), 400.0) << name;
  }
}

}  // namespace
}  // namespace tumble
