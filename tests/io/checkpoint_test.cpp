// Checkpoint files: every field back exactly; a damaged file refused with one line.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>

#include <unistd.h>

#include "../support/scene_files.hpp"
#include "tumble/error.hpp"
#include "tumble/io/checkpoint.hpp"

namespace tumble {
namespace {

Checkpoint sample_checkpoint() {
  Checkpoint c;
  c.tumble_version = "0.1.0";
  c.scene_path = "s.toml";
  c.scene_absolute = "/x/s.toml";
  c.scene_text = std::string("[simulation]\nduration = 1\n\0binary", 34);
  c.inputs = {{"/x/m.stl", 84, 0x0123456789abcdefULL}};
  c.settings.duration = 0.1;  // not a binary fraction: must come back bit for bit
  c.settings.integrator = "dopri45";
  c.settings.formulation = Formulation::body;
  c.settings.tolerances = {1e-11, 3e-13};
  c.settings.threads = 4;
  c.output = "/x/o.csv";
  c.fields = {"position", "kinetic_energy"};
  c.settings.drift_threshold = 1e-6;
  c.strict = true;
  c.writer_pid = 4242;
  c.writer_host = "node-17";
  c.writer_boot_id = "c0ffee00-0000-4000-8000-000000000000";
  c.output_bytes = 123456789;
  c.output_tail_hash = 0xfedcba9876543210ULL;
  c.largest_energy_drift = 2.5e-15;
  c.drift_warning = "energy drifted";
  c.crossings = {{3, 0.125}, {0, 0.0}, {1, -2.5e-300}};
  c.point.t0 = 0.0;
  c.point.x.t = 1.0 / 3.0;
  c.point.x.bodies.resize(3);
  for (size_t k = 0; k < BodyColumns::kCount; ++k)
    for (size_t i = 0; i < 3; ++i) c.point.x.bodies[k][i] = std::nextafter(0.1 * (k + i), 1.0);
  c.point.x.bodies[0][1] = -0.0;
  c.point.x.bodies[1][2] = std::numeric_limits<double>::denorm_min();
  c.point.x.particles = {ParticleState{Vec3(1, 2, 3), Vec3(4, 5, 6)}};
  c.point.next_sample = 17;
  c.point.t_last_sample = 0.32;
  c.point.steps_since_sample = 3;
  c.point.samples = 17;
  c.point.stats = {100, 2, 613};
  c.point.event_values = {-1e-300};
  c.point.integrator = {1.0, 2.0, 1.0 / 7.0};
  return c;
}

TEST(Checkpoint, EveryFieldComesBackExactly) {
  test::TempDir dir("checkpoint_roundtrip");
  const Checkpoint c = sample_checkpoint();
  write_checkpoint(dir / "c.ckpt", c);
  const Checkpoint r = read_checkpoint(dir / "c.ckpt");
  EXPECT_EQ(r.scene_text, c.scene_text);
  EXPECT_EQ(r.inputs[0].hash, c.inputs[0].hash);
  EXPECT_EQ(r.settings.duration, c.settings.duration);
  EXPECT_EQ(r.settings.formulation, Formulation::body);
  EXPECT_EQ(r.settings.tolerances.absolute, 3e-13);
  EXPECT_EQ(r.settings.threads, 4);
  EXPECT_EQ(r.fields, c.fields);
  EXPECT_TRUE(r.strict);
  EXPECT_EQ(r.writer_pid, 4242);
  EXPECT_EQ(r.writer_host, c.writer_host);
  EXPECT_EQ(r.writer_boot_id, c.writer_boot_id);
  EXPECT_EQ(r.output_bytes, c.output_bytes);
  EXPECT_EQ(r.output_tail_hash, c.output_tail_hash);
  EXPECT_EQ(r.largest_energy_drift, c.largest_energy_drift);
  EXPECT_FALSE(r.largest_angular_momentum_drift);
  EXPECT_EQ(r.drift_warning, c.drift_warning);
  EXPECT_EQ(r.crossings, c.crossings);
  EXPECT_EQ(r.point.x.t, c.point.x.t);
  for (size_t k = 0; k < BodyColumns::kCount; ++k)
    EXPECT_EQ(std::memcmp(r.point.x.bodies[k], c.point.x.bodies[k], 3 * sizeof(double)), 0) << k;
  EXPECT_EQ(r.point.x.particles[0].v, c.point.x.particles[0].v);
  EXPECT_EQ(r.point.next_sample, 17);
  EXPECT_EQ(r.point.steps_since_sample, 3);
  EXPECT_EQ(r.point.stats.evaluations, 613);
  EXPECT_EQ(r.point.event_values, c.point.event_values);
  EXPECT_EQ(r.point.integrator, c.point.integrator);
  EXPECT_FALSE(std::filesystem::exists(dir / ("c.ckpt.tmp-" + std::to_string(::getpid()))));
}

TEST(Checkpoint, EveryTruncationAndBitFlipIsRefused) {
  test::TempDir dir("checkpoint_damaged");
  write_checkpoint(dir / "c.ckpt", sample_checkpoint());
  const std::string good = test::read_text(dir / "c.ckpt");
  for (size_t cut = 0; cut < good.size(); cut += 7) {
    dir.write("cut.ckpt", good.substr(0, cut));
    EXPECT_THROW(read_checkpoint(dir / "cut.ckpt"), InvalidArgument) << cut;
  }
  for (size_t at = 0; at < good.size(); at += 5) {
    std::string bad = good;
    bad[at] = static_cast<char>(bad[at] ^ 0x04);
    dir.write("bad.ckpt", bad);
    EXPECT_THROW(read_checkpoint(dir / "bad.ckpt"), InvalidArgument) << at;
  }
}

}  // namespace
}  // namespace tumble
