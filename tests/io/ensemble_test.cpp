// Ensembles: draws that depend on (seed, run) alone and follow their distributions, tables that do not
// depend on threads, per-run physics against the closed form, and clear errors for bad studies.
#include <gtest/gtest.h>

#include <boost/math/distributions/normal.hpp>
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <set>

#include "../support/racket_study.hpp"
#include "../support/scene_files.hpp"
#include "tumble/io/ensemble.hpp"

namespace tumble {
namespace {

EnsembleStudy study(const std::string& ensemble) { return test::racket_study(ensemble); }

/// The draws of every run, column k.
std::vector<double> column(const EnsembleStudy& s, size_t k) {
  std::vector<double> x;
  for (long i = 0; i < s.runs(); ++i) x.push_back(s.draws(i)[k]);
  return x;
}

double mean(const std::vector<double>& x) {
  double sum = 0;
  for (double v : x) sum += v;
  return sum / static_cast<double>(x.size());
}

double variance(const std::vector<double>& x) {
  const double m = mean(x);
  double sum = 0;
  for (double v : x) sum += (v - m) * (v - m);
  return sum / static_cast<double>(x.size() - 1);
}

// The tests of the sample moments below allow 5 standard errors: a correct generator fails one with
// probability below 1e-6; a wrong distribution (a wrong scale, shift or shape) misses by far more.
constexpr double kSigmas = 5.0;

TEST(Ensemble, DrawsFollowTheirDistributionsAndDependOnSeedAndRunAlone) {
  const EnsembleStudy s = study(R"([ensemble]
runs = 20000
seed = 7
[[ensemble.vary]]
path = "bodies.racket.angular_velocity[0]"
distribution = "uniform"
low = -1.0
high = 3.0
[[ensemble.vary]]
path = "bodies.racket.angular_velocity[1]"
distribution = "normal"
mean = 10.0
std = 0.5
[[ensemble.vary]]
path = "bodies.racket.mass"
distribution = "lognormal"
mu = 0.0
sigma = 0.25
[[ensemble.vary]]
path = "simulation.duration"
distribution = "truncated_normal"
mean = 1.0
std = 1.0
low = 0.5
high = 2.0
)");
  const double n = static_cast<double>(s.runs());
  // uniform(−1, 3): mean 1, variance 16/12.
  const auto u = column(s, 0);
  EXPECT_NEAR(mean(u), 1.0, kSigmas * std::sqrt(16.0 / 12 / n));
  EXPECT_NEAR(variance(u), 16.0 / 12, kSigmas * std::sqrt(16.0 * 16 / 180 / n));  // var of s²: (μ₄ − σ⁴)/n
  for (double v : u) EXPECT_TRUE(v > -1.0 && v < 3.0);
  // normal(10, 0.5).
  const auto g = column(s, 1);
  EXPECT_NEAR(mean(g), 10.0, kSigmas * 0.5 / std::sqrt(n));
  EXPECT_NEAR(std::sqrt(variance(g)), 0.5, kSigmas * 0.5 / std::sqrt(2 * n));
  // lognormal(0, 0.25): mean e^{σ²/2}, variance (e^{σ²} − 1) e^{σ²}.
  const auto l = column(s, 2);
  const double s2 = 0.25 * 0.25;
  EXPECT_NEAR(mean(l), std::exp(s2 / 2), kSigmas * std::sqrt((std::exp(s2) - 1) * std::exp(s2) / n));
  // truncated normal(1, 1) on [0.5, 2]: mean μ + σ (φ(α) − φ(β)) / (Φ(β) − Φ(α)), α = −0.5, β = 1.
  const auto t = column(s, 3);
  const auto phi = [](double x) { return std::exp(-x * x / 2) / std::sqrt(2 * std::numbers::pi); };
  const auto Phi = [](double x) { return 0.5 * std::erfc(-x / std::sqrt(2.0)); };
  const double tm = 1.0 + (phi(-0.5) - phi(1.0)) / (Phi(1.0) - Phi(-0.5));
  EXPECT_NEAR(mean(t), tm, kSigmas * std::sqrt(variance(t) / n));
  for (double v : t) EXPECT_TRUE(v >= 0.5 && v <= 2.0);
  // Run 123's draws are the same from another load of the study, and differ from run 124's.
  const EnsembleStudy again = study(R"([ensemble]
runs = 5
seed = 7
[[ensemble.vary]]
path = "bodies.racket.angular_velocity[0]"
distribution = "uniform"
low = -1.0
high = 3.0
)");
  EXPECT_EQ(again.draws(3)[0], s.draws(3)[0]) << "the same (seed, run, variation): the same value";
  EXPECT_NE(s.draws(123)[0], s.draws(124)[0]);
  // The drawn value is what the run's scene holds.
  EXPECT_EQ(s.scene_of_run(5).model.bodies[0].mass(), s.draws(5)[2]);
  EXPECT_EQ(s.scene_of_run(5).settings.duration, s.draws(5)[3]);
}

TEST(Ensemble, TruncatedNormalsFarInATailFollowTheExactDistribution) {
  // Φ(α) and Φ(β) round to 1 at α = 10 (mean 1000, std 1, [1010, 1020]), where an inverse CDF of Φ
  // drew `low` every time. The exact truncated distribution, by the upper tail Q = 1 − Φ in long double:
  //   F(x) = (Q(α) − Q(z))/(Q(α) − Q(β)),  z = (x − μ)/σ,  mean μ + σ (φ(α) − φ(β))/(Q(α) − Q(β)).
  // Checked by the mean (kSigmas standard errors) and by Kolmogorov–Smirnov: D ≤ 2.7/√n fails a correct
  // sampler with probability ~1e-6. A lower tail (mirrored) and a moderate one (α = 0.5) too.
  const EnsembleStudy s = study(R"([ensemble]
runs = 20000
seed = 3
[[ensemble.vary]]
path = "bodies.racket.mass"
distribution = "truncated_normal"
mean = 1000.0
std = 1.0
low = 1010.0
high = 1020.0
[[ensemble.vary]]
path = "bodies.racket.angular_velocity[0]"
distribution = "truncated_normal"
mean = 0.0
std = 2.0
low = -50.0
high = -40.0
[[ensemble.vary]]
path = "bodies.racket.angular_velocity[2]"
distribution = "truncated_normal"
mean = 0.0
std = 1.0
low = 0.5
high = 3.0
)");
  using L = long double;
  const boost::math::normal_distribution<L> unit;
  const auto Q = [&](L z) { return boost::math::cdf(boost::math::complement(unit, z)); };
  const auto phi = [](L z) { return std::exp(-z * z / 2) / std::sqrt(2 * std::numbers::pi_v<L>); };
  struct Case {
    size_t column;
    double mu, sigma, low, high;
  };
  for (const Case c :
       {Case{0, 1000.0, 1.0, 1010.0, 1020.0}, Case{1, 0.0, 2.0, -50.0, -40.0}, Case{2, 0.0, 1.0, 0.5, 3.0}}) {
    std::vector<double> x = column(s, c.column);
    const double n = static_cast<double>(x.size());
    // The lower tail is the upper one mirrored: z → −z maps [low, high] to [−high, −low].
    const bool upper = c.low > c.mu;
    const L alpha = static_cast<L>(upper ? (c.low - c.mu) / c.sigma : (c.mu - c.high) / c.sigma);
    const L beta = static_cast<L>(upper ? (c.high - c.mu) / c.sigma : (c.mu - c.low) / c.sigma);
    const L Z = Q(alpha) - Q(beta);
    const L mean_z = (phi(alpha) - phi(beta)) / Z;
    const double expected = c.mu + (upper ? 1.0 : -1.0) * c.sigma * static_cast<double>(mean_z);
    for (double v : x) ASSERT_TRUE(v >= c.low && v <= c.high) << v;
    EXPECT_NEAR(mean(x), expected, kSigmas * std::sqrt(variance(x) / n)) << c.column;
    EXPECT_GT(variance(x), 0.0) << "not one value drawn every time";
    std::sort(x.begin(), x.end());
    double D = 0.0;
    for (size_t i = 0; i < x.size(); ++i) {
      const L z = static_cast<L>(upper ? (x[i] - c.mu) / c.sigma : (c.mu - x[i]) / c.sigma);
      const double F = static_cast<double>((Q(alpha) - Q(z)) / Z);  // mirrored: 1 − F of the lower tail
      const double F_x = upper ? F : 1.0 - F;
      D = std::max(
          {D, std::abs(F_x - static_cast<double>(i) / n), std::abs(F_x - static_cast<double>(i + 1) / n)});
    }
    EXPECT_LE(D, 2.7 / std::sqrt(n)) << "column " << c.column;
  }
}

TEST(Ensemble, RandomRotationsAndDirectionsAreUniform) {
  const EnsembleStudy s = study(R"([ensemble]
runs = 20000
[[ensemble.vary]]
path = "bodies.racket.angular_velocity"
distribution = "direction"
magnitude = 2.0
[[ensemble.vary]]
path = "bodies.racket.orientation"
distribution = "rotation"
)");
  const double n = static_cast<double>(s.runs());
  // A uniform direction: |x| = magnitude, each component mean 0 and variance m²/3.
  for (int k = 0; k < 3; ++k) {
    const auto c = column(s, static_cast<size_t>(k));
    EXPECT_NEAR(mean(c), 0.0, kSigmas * std::sqrt(4.0 / 3 / n));
    EXPECT_NEAR(variance(c), 4.0 / 3, kSigmas * std::sqrt((16.0 / 5 - 16.0 / 9) / n));  // E x⁴ = m⁴/5
  }
  for (long i = 0; i < 100; ++i) {
    const auto d = s.draws(i);
    EXPECT_NEAR(std::hypot(d[0], d[1], d[2]), 2.0, 1e-15);
  }
  // A uniform rotation (Haar measure): each quaternion component squared has mean 1/4 (the unit
  // 3-sphere is symmetric), and the mean rotation matrix is 0: E[R_zz] = E[1 − 2(x² + y²)] = 0.
  std::vector<double> w2, Rzz;
  for (long i = 0; i < s.runs(); ++i) {
    const auto d = s.draws(i);
    const double w = d[3], x = d[4], y = d[5], z = d[6];
    EXPECT_NEAR(w * w + x * x + y * y + z * z, 1.0, 1e-15);
    w2.push_back(w * w);
    Rzz.push_back(1 - 2 * (x * x + y * y));
  }
  EXPECT_NEAR(mean(w2), 0.25, kSigmas * std::sqrt(variance(w2) / n));
  EXPECT_NEAR(mean(Rzz), 0.0, kSigmas * std::sqrt(1.0 / 3 / n));  // R_zz uniform on [−1, 1]
}

TEST(Ensemble, ListsCycleAndGridsCoverEveryPointOnce) {
  const EnsembleStudy s = study(R"([ensemble]
[[ensemble.vary]]
path = "bodies.racket.angular_velocity[1]"
distribution = "grid"
values = [8.0, 9.0, 10.0]
[[ensemble.vary]]
path = "bodies.racket.mass"
distribution = "grid"
values = [1.0, 2.0]
[[ensemble.vary]]
path = "simulation.timestep"
distribution = "list"
values = [1e-3, 2e-3]
)");
  ASSERT_EQ(s.runs(), 6) << "runs defaults to the grid's size";
  std::set<std::pair<double, double>> points;
  for (long i = 0; i < 6; ++i) {
    const auto d = s.draws(i);
    points.insert({d[0], d[1]});
    EXPECT_EQ(d[2], i % 2 == 0 ? 1e-3 : 2e-3);
  }
  EXPECT_EQ(points.size(), 6u);
}

TEST(Ensemble, MistakesAreNamed) {
  const auto error = [](const std::string& ensemble) {
    try {
      (void)study(ensemble);
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(error("[ensemble]\nruns = 3\n[[ensemble.vary]]\npath = \"bodies.rocket.mass\"\ndistribution = "
                  "\"uniform\"\nlow = 1\nhigh = 2\n")
                .find("no element of bodies is named \"rocket\""),
            std::string::npos);
  EXPECT_NE(error(
                "[ensemble]\nruns = 3\n[[ensemble.vary]]\npath = \"bodies.racket.velocity[0]\"\ndistribution "
                "= \"uniform\"\nlow = 1\nhigh = 2\n")
                .find("bodies.racket.velocity is not in the scene: write it in the file"),
            std::string::npos);
  EXPECT_NE(
      error("[ensemble]\nruns = 3\n[[ensemble.vary]]\npath = \"bodies.racket.angular_velocity[3]\"\n"
            "distribution = \"uniform\"\nlow = 1\nhigh = 2\n")
          .find("angular_velocity[3] is not in the scene (bodies.racket.angular_velocity has 3 elements)"),
      std::string::npos);
  EXPECT_NE(error("[ensemble]\nruns = 3\n[[ensemble.vary]]\npath = \"bodies.racket.mass\"\ndistribution = "
                  "\"gaussian\"\n")
                .find("unknown distribution \"gaussian\""),
            std::string::npos);
  EXPECT_NE(error("[ensemble]\nruns = 3\n[[ensemble.vary]]\npath = \"bodies.racket.mass\"\ndistribution = "
                  "\"rotation\"\n")
                .find("a rotation distribution sets 4 numbers"),
            std::string::npos);
  EXPECT_NE(error("[ensemble]\n[[ensemble.vary]]\npath = \"bodies.racket.mass\"\ndistribution = \"normal\"\n"
                  "mean = 1\nstd = 1\n")
                .find("missing 'runs'"),
            std::string::npos);
  // A draw that makes the scene invalid: the run and its values are named.
  const EnsembleStudy s = study(R"([ensemble]
runs = 50
[[ensemble.vary]]
path = "bodies.racket.mass"
distribution = "normal"
mean = 0.0
std = 1.0
)");
  long negative = 0;
  while (s.draws(negative)[0] > 0) ++negative;
  try {
    (void)s.scene_of_run(negative);
    FAIL() << "a negative mass was accepted";
  } catch (const SceneError& e) {
    EXPECT_NE(std::string(e.what()).find(fmt::format("run {} (bodies.racket.mass = -", negative)),
              std::string::npos)
        << e.what();
    EXPECT_NE(std::string(e.what()).find("it must be positive"), std::string::npos) << e.what();
  }
}

TEST(PartialRows, ATornOrDamagedRecordIsDroppedAndNewRowsFollowWholeOnes) {
  // What a kill (a record torn at any byte: stdio flushes buffers, not records) or a power loss (bytes
  // changed after the last good record) leaves in OUT.partial-RANK. Reading keeps the whole records
  // before the damage; opening the file again cuts it there, so rows added next are read back too and
  // nothing after the damage is ever taken for a row.
  const EnsembleStudy s = study("[ensemble]\nruns = 20\n[ensemble.outputs]\nextrema = [\"w2\"]\n");
  const test::TempDir dir("partial_rows");
  const std::filesystem::path out = dir / "t.csv", file = dir / "t.csv.partial-0";
  const size_t width = s.columns().size() - 1;
  const auto row = [&](long run) {
    EnsembleRow r;
    r.run = run;
    for (size_t k = 0; k < width; ++k)
      r.values.push_back(static_cast<double>(run) + 0.125 * static_cast<double>(k));
    return r;
  };
  const auto runs_read = [&] {
    std::vector<long> runs;
    for (const EnsembleRow& r : PartialRows::read_all(out, s)) {
      EXPECT_EQ(r.values, row(r.run).values) << "run " << r.run;
      runs.push_back(r.run);
    }
    return runs;
  };
  const auto add = [&](std::initializer_list<long> runs) {
    PartialRows partial(out, 0, s);
    for (long run : runs) partial.add(row(run));
  };
  add({0, 1, 2, 3, 4});
  ASSERT_EQ(runs_read(), (std::vector<long>{0, 1, 2, 3, 4}));
  const std::uintmax_t whole = std::filesystem::file_size(file), record = 8 * (width + 2);
  ASSERT_EQ((whole - 24) % record, 0u);

  // The last record torn at every byte: four rows read; reopened, the fifth place takes run 7.
  for (std::uintmax_t kept = 1; kept < record; ++kept) {
    std::filesystem::resize_file(file, whole - record + kept);
    EXPECT_EQ(runs_read(), (std::vector<long>{0, 1, 2, 3})) << kept << " bytes of the last record";
    add({7});
    EXPECT_EQ(runs_read(), (std::vector<long>{0, 1, 2, 3, 7})) << kept << " bytes of the last record";
    EXPECT_EQ(std::filesystem::file_size(file), whole);
  }

  // A byte of run 2's values changed: runs 0 and 1 stand, and rows added next follow them.
  {
    std::fstream f(file, std::ios::in | std::ios::out | std::ios::binary);
    f.seekp(static_cast<std::streamoff>(24 + 2 * record + 8 + 3));
    f.put('\x5a');
  }
  EXPECT_EQ(runs_read(), (std::vector<long>{0, 1}));
  add({9});
  EXPECT_EQ(runs_read(), (std::vector<long>{0, 1, 9}));

  // Zeros after the last record (a file extended, its data never written) are not a row of run 0.
  {
    std::ofstream f(file, std::ios::app | std::ios::binary);
    f << std::string(3 * record, '\0');
  }
  EXPECT_EQ(runs_read(), (std::vector<long>{0, 1, 9}));
}

}  // namespace
}  // namespace tumble
