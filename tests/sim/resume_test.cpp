// Exact resume: a run stopped at a sample and continued from its RunPoint is the run that was not
// stopped, bit for bit, for every integrator.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cstring>

#include "../support/sim_helpers.hpp"
#include "tumble/error.hpp"
#include "tumble/forces/forces.hpp"

namespace tumble {
namespace {

/// Body 0 tumbles free under gravity (splitting keeps its flow across steps), body 1 is pushed off its
/// centre and damped (fresh flows, loads that depend on velocities); `particle` adds a damped particle
/// (no fused steps then).
Model model(bool particle, bool torques = true) {
  Model m;
  m.add_body(RigidBody::from_principal_moments(2.0, Vec3(1.0, 2.0, 3.0), "free"));
  m.add_body(RigidBody::from_principal_moments(1.5, Vec3(0.5, 0.9, 1.1), "pushed"));
  m.add_force<UniformGravity>(Vec3(0, 0, -9.81));
  if (torques) {
    m.add_force<PointForce>(1, Vec3(0.3, -0.2, 1.0), Frame::world, Vec3(0.1, 0.05, 0.0), Frame::principal);
    m.add_force<ViscousDamping>(1, 0.2, 0.05);
  }
  if (particle) m.add_particle(Particle{"p", 0.5});
  return m;
}

SystemState initial(const Model& m) {
  SystemState s;
  BodyState a, b;
  a.omega_w = Vec3(0.1, 3.0, 0.2);
  a.v = Vec3(1, 0, 4);
  b.o = Vec3(2, 0, 0);
  b.q = Quat(0.9, 0.1, 0.3, -0.2).normalized();
  b.omega_w = Vec3(-1.0, 0.4, 2.0);
  s.bodies = {a, b};
  if (!m.particles.empty()) s.particles = {ParticleState{Vec3(0, 1, 0), Vec3(0.5, 0, 2)}};
  return s;
}

void expect_same_bits(const SystemState& a, const SystemState& b, const std::string& what) {
  ASSERT_EQ(a.bodies.size(), b.bodies.size()) << what;
  EXPECT_EQ(std::memcmp(&a.t, &b.t, sizeof a.t), 0) << what << ": t " << a.t << " vs " << b.t;
  for (size_t i = 0; i < a.bodies.size(); ++i) {
    const BodyState &x = a.bodies[i], &y = b.bodies[i];
    EXPECT_EQ(std::memcmp(x.o.data(), y.o.data(), sizeof(double) * 3), 0) << what << " body " << i;
    EXPECT_EQ(std::memcmp(x.q.coeffs().data(), y.q.coeffs().data(), sizeof(double) * 4), 0) << what;
    EXPECT_EQ(std::memcmp(x.v.data(), y.v.data(), sizeof(double) * 3), 0) << what << " body " << i;
    EXPECT_EQ(std::memcmp(x.omega_w.data(), y.omega_w.data(), sizeof(double) * 3), 0) << what;
  }
  ASSERT_EQ(a.particles.size(), b.particles.size()) << what;
  for (size_t i = 0; i < a.particles.size(); ++i) {
    EXPECT_EQ(std::memcmp(a.particles[i].x.data(), b.particles[i].x.data(), sizeof(double) * 3), 0) << what;
    EXPECT_EQ(std::memcmp(a.particles[i].v.data(), b.particles[i].v.data(), sizeof(double) * 3), 0) << what;
  }
}

struct Case {
  bool particle;
  double output_interval;
  Formulation formulation;
  bool event;
};

/// The run uninterrupted, then stopped at sample `stop_at` (by on_sample) or after `stop_after_steps`
/// (by stop_requested, off the grid), resumed from its last run point, possibly twice.
void check_resume(const std::string& integrator, const Case& c) {
  const bool exact = integrator == "exact";
  const Model m = model(c.particle, !exact);
  const SystemState s0 = initial(m);
  RunSettings rs;
  rs.duration = 1.0;
  rs.timestep = 0.01;
  rs.output_interval = c.output_interval;
  rs.integrator = integrator;
  rs.formulation = c.formulation;
  rs.tolerances = {1e-8, 1e-10};
  const std::string what = fmt::format("{} particle={} interval={} formulation={} event={}", integrator,
                                       c.particle, c.output_interval, formulation_name(c.formulation),
                                       c.event);
  auto hooks_for = [&](std::vector<SystemState>& samples, int& hits) {
    RunHooks h;
    h.on_sample = [&samples](const SystemState& s) {
      samples.push_back(s);
      return true;
    };
    if (c.event) {
      h.events.push_back({"turn", [](const SystemState& s) { return s.bodies[1].omega_w.x(); }, 0, false});
      h.on_event = [&hits](const EventHit&) { ++hits; };
    }
    return h;
  };

  std::vector<SystemState> whole;
  int whole_hits = 0;
  const SystemState end = simulate(m, s0, rs, hooks_for(whole, whole_hits));
  ASSERT_GT(whole.size(), 10u) << what;

  for (const bool on_grid : {true, false}) {
    std::vector<SystemState> got;
    int hits = 0;
    RunHooks first = hooks_for(got, hits);
    RunPoint point;
    first.run_point = &point;
    int seen = 0;
    if (on_grid) {
      first.on_sample = [&](const SystemState& s) {
        got.push_back(s);
        return ++seen < 7;
      };
    } else {
      first.stop_requested = [&] { return ++seen >= 23; };
    }
    simulate(m, s0, rs, first);
    ASSERT_GE(point.samples, 2) << what;
    // What was written after the run point is dropped, as a resumed CSV file is cut there.
    got.resize(static_cast<size_t>(point.samples));
    const int hits_before = hits;  // crossings up to the stop; those after the point come again
    (void)hits_before;

    // Resume twice: at its third sample the first resumption stops again.
    RunPoint point2;
    {
      RunHooks second = hooks_for(got, hits);
      second.resume_from = &point;
      second.run_point = &point2;
      int n = 0;
      second.on_sample = [&](const SystemState& s) {
        got.push_back(s);
        return ++n < 3;
      };
      simulate(m, s0, rs, second);
      got.resize(static_cast<size_t>(point2.samples));
    }
    RunHooks third = hooks_for(got, hits);
    third.resume_from = &point2;
    const SystemState resumed_end = simulate(m, s0, rs, third);

    const std::string w = what + (on_grid ? " stopped at a sample" : " stopped between samples");
    expect_same_bits(end, resumed_end, w + ", final state");
    ASSERT_EQ(got.size(), whole.size()) << w;
    for (size_t k = 0; k < whole.size(); ++k)
      expect_same_bits(whole[k], got[k], w + fmt::format(", sample {}", k));
  }
}

TEST(Resume, EveryIntegratorContinuesBitForBit) {
  for (const std::string& name : integrator_names()) {
    check_resume(name, {false, 0.05, Formulation::mixed, false});
  }
}

TEST(Resume, OffGridIntervalsParticlesFormulationsAndEvents) {
  for (const std::string& name : integrator_names()) {
    check_resume(name, {true, 0.037, Formulation::world, false});
    check_resume(name, {false, 0.0, Formulation::body, false});
    if (name != "exact") check_resume(name, {false, 0.05, Formulation::mixed, true});
  }
}

TEST(Resume, APointOfAnotherRunIsRefused) {
  const Model m = model(false);
  RunSettings rs;
  rs.duration = 0.1;
  rs.output_interval = 0.05;
  rs.integrator = "splitting";
  RunPoint point;
  RunHooks h;
  h.run_point = &point;
  simulate(m, initial(m), rs, h);
  SystemState other = initial(m);
  other.t = 5.0;
  RunHooks again;
  again.resume_from = &point;
  EXPECT_THROW(simulate(m, other, rs, again), InvalidArgument);
  rs.integrator = "rk4";
  EXPECT_THROW(simulate(m, initial(m), rs, again), InvalidArgument);  // splitting's state, given to rk4
}

}  // namespace
}  // namespace tumble
