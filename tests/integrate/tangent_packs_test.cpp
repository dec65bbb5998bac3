// Tangents on packs (integrate/tangent_packs.hpp): Integrator::step_tangents_packed regroups the dual
// numbers into lanes of (body, four slots) and steps them by the same templates as step_tangent. The
// operations on each derivative are the same, in the same order, so the two must agree bit for bit,
// values and every slot, for each method, formulation and number of slots (padding lanes included).
#include <gtest/gtest.h>

#include <fmt/format.h>

#include <random>
#include <string>
#include <vector>

#include "tumble/forces/forces.hpp"
#include "tumble/integrate/integrator.hpp"

namespace tumble {
namespace {

using T = TangentScalar;

/// A number with value v and random derivatives in its first `slots` slots (zeros in the others).
T seeded(double v, int slots, std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  T x(v);
  for (int j = 0; j < slots; ++j) x.d[static_cast<size_t>(j)] = u(rng);
  return x;
}

/// The bodies' numbers, every one seeded, and the uniform fields' g's seeded.
TangentCoordinates seeded_system(const Model& model, int slots, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  TangentCoordinates x;
  x.t = 0.25;
  for (size_t b = 0; b < model.bodies.size(); ++b) {
    const Quat q = Quat(Eigen::AngleAxisd(0.4 + b, Vec3(1.0, -0.5 + b, 0.3).normalized()));
    Coordinates<T> c;
    for (int k = 0; k < 3; ++k) {
      c.o(k) = seeded(u(rng), slots, rng);
      c.v(k) = seeded(u(rng), slots, rng);
      c.omega(k) = seeded(3.0 * u(rng), slots, rng);
    }
    for (int k = 0; k < 4; ++k) c.q.coeffs()(k) = seeded(q.coeffs()(k), slots, rng);
    x.bodies.push_back(c);
    x.m.push_back(seeded(model.bodies[b].mass(), slots, rng));
    Vec3T<T> Lambda;
    for (int k = 0; k < 3; ++k) Lambda(k) = seeded(model.bodies[b].Lambda()(k), slots, rng);
    x.Lambda.push_back(Lambda);
  }
  for (const auto& f : model.forces) {
    x.force_parameters.emplace_back();
    for (const ForceParameter& p : f->parameters())
      x.force_parameters.back().push_back(seeded(p.value, slots, rng));
  }
  return x;
}

Model bodies(int n, bool gravity) {
  Model model;
  for (int b = 0; b < n; ++b) {
    model.add_body(RigidBody::from_principal_moments(1.0 + 0.5 * b, Vec3(1.0, 2.0 + 0.1 * b, 2.5 + 0.2 * b)));
  }
  if (gravity) {
    model.add_force<UniformGravity>(Vec3(0.0, 0.0, -9.81));
    model.add_force<UniformGravity>(Vec3(0.1, 0.2, 0.0));  // two fields: summed in model order
  }
  return model;
}

void expect_same_bits(const TangentCoordinates& a, const TangentCoordinates& b, const std::string& what) {
  auto same = [&](const T& x, const T& y, const char* name, size_t body) {
    ASSERT_EQ(x.v, y.v) << what << ", body " << body << ", " << name << " value";
    for (size_t j = 0; j < x.d.size(); ++j)
      ASSERT_EQ(x.d[j], y.d[j]) << what << ", body " << body << ", " << name << " slot " << j;
  };
  for (size_t i = 0; i < a.bodies.size(); ++i) {
    for (int k = 0; k < 3; ++k) {
      same(a.bodies[i].o(k), b.bodies[i].o(k), "o", i);
      same(a.bodies[i].v(k), b.bodies[i].v(k), "v", i);
      same(a.bodies[i].omega(k), b.bodies[i].omega(k), "omega", i);
    }
    for (int k = 0; k < 4; ++k) same(a.bodies[i].q.coeffs()(k), b.bodies[i].q.coeffs()(k), "q", i);
  }
}

TEST(TangentPacks, StepThePackedLanesExactlyAsStepTangentStepsEachBody) {
  const std::vector<double> lengths = {1e-2, 1e-2, 1e-2, 3.7e-3};  // a sample's steps: h, h, h, the rest
  // One body takes lanes of 2 slots (8 lanes, one pack on AVX-512); five take lanes of 4 (the last pack
  // padded) except with 5 slots: both layouts are checked.
  for (const int n : {1, 5})
    for (const bool gravity : {false, true}) {
      const Model model = bodies(n, gravity);
      for (const char* method : {"euler", "semi_implicit_euler", "rk4"}) {
        for (const Formulation F : {Formulation::world, Formulation::mixed, Formulation::body}) {
          // 15: a body's 12 tangents and 3 moments (four lanes of four); 13: mass (the last lane one slot
          // short); 5: two lanes, the second short; 16: all.
          for (const int slots : {15, 13, 5, 16}) {
            const std::string what = fmt::format("{} bodies, {} in the {} formulation, {} slots{}", n, method,
                                                 formulation_name(F), slots, gravity ? ", gravity" : "");
            const TangentCoordinates x0 = seeded_system(model, slots, 7u + static_cast<unsigned>(slots));
            TangentCoordinates by_body = x0, packed = x0;
            const auto integrator = make_integrator(method);
            for (double h : lengths) integrator->step_tangent(model, F, by_body, h);
            ASSERT_TRUE(integrator->step_tangents_packed(model, F, packed, lengths, slots)) << what;
            expect_same_bits(by_body, packed, what);
          }
        }
      }
    }
}

TEST(TangentPacks, AreRefusedWhereTheyDoNotApplyAndLeaveTheStateAlone) {
  Model drag = bodies(5, true);
  drag.add_force<QuadraticDrag>(all_bodies, 0.05, 1e-3);  // a load that depends on the state
  const TangentCoordinates x0 = seeded_system(drag, 15, 3u);
  TangentCoordinates x = x0;
  const std::vector<double> lengths = {1e-2};
  EXPECT_FALSE(make_integrator("rk4")->step_tangents_packed(drag, Formulation::mixed, x, lengths, 15));
  expect_same_bits(x0, x, "rk4 under drag, refused");
  // Methods without a packed path (their maps are not an explicit stage loop on the rates).
  const Model free = bodies(5, false);
  for (const char* method : {"splitting", "lie_rk4", "midpoint"}) {
    EXPECT_FALSE(make_integrator(method)->step_tangents_packed(free, Formulation::mixed, x, lengths, 15))
        << method;
  }
}

}  // namespace
}  // namespace tumble
