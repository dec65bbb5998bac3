// The exact triaxial free flow on packs (src/integrate/euler_poinsot_flows.hpp, triaxial_state): the
// template splitting's batched drift evaluates, one body per lane. Instantiated on double (what
// EulerPoinsot evaluates), on the reference pack (each operation lane by lane with <cmath>: branch-free
// and equal to double bit for bit, or the template is wrong) and on the SIMD pack (xsimd's own sin,
// cos, asin, atan and hypot: equal to double up to their last bits, bounded below), and on a pair of
// SIMD packs (how the drift evaluates two packs at once: equal to one pack, bit for bit).
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <stdexcept>
#include <vector>

#include "../support/ref_pack.hpp"
#include "integrate/euler_poinsot_flows.hpp"
#include "tumble/integrate/euler_poinsot.hpp"
#include "tumble/math/pack_pair.hpp"
#include "tumble/math/simd.hpp"

namespace tumble {
namespace {

constexpr double kEps = std::numeric_limits<double>::epsilon();
using SimdPack = xsimd::batch<double>;
constexpr std::size_t W = SimdPack::size;
using RefPackW = test::RefPack<W>;

/// The triaxial flow inside an EulerPoinsot (the cases below are all triaxial).
const detail::TriaxialRotation& triaxial_of(const EulerPoinsot& flow) {
  const detail::TriaxialRotation* t = flow.free_rotation().triaxial();
  if (!t) throw std::logic_error("not a triaxial flow");
  return *t;
}

/// Triaxial flows off the separatrix in both regimes, with moments from nearly equal pairs to far
/// apart (N from ~1e-3 to ~1e3) and states near the separatrix (k′² down to ~1e-9), and the
/// times to evaluate them at (up to 1e3 s, many periods).
struct Case {
  EulerPoinsot flow;
  double t;
};
std::vector<Case> cases() {
  std::mt19937_64 rng(20261127);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<Case> out;
  while (out.size() < 64 * W) {
    const double I1 = 1.0, I2 = 1.0 + std::pow(10.0, -3.0 + 4.0 * unit(rng)),
                 I3 = I2 + std::pow(10.0, -3.0 + 4.0 * unit(rng));
    Vec3 w(unit(rng) - 0.5, unit(rng) - 0.5, unit(rng) - 0.5);
    if (out.size() % 4 == 0)
      w(1) = 10.0 * std::copysign(1.0, w(1));  // about the intermediate axis: near the separatrix
    const Quat q0 =
        Quat(Eigen::AngleAxisd(6.0 * unit(rng), Vec3(unit(rng), unit(rng), unit(rng)).normalized()));
    EulerPoinsot flow(Vec3(I2, I3, I1), q0, 5.0 * w);  // the axes in another order: P is a signed permutation
    const auto* tri = flow.free_rotation().triaxial();
    if (!tri || tri->separatrix()) continue;
    out.push_back({flow, std::pow(10.0, -3.0 + 6.0 * unit(rng)) * (unit(rng) < 0.2 ? -1.0 : 1.0)});
  }
  return out;
}

/// Lanes first … first + W − 1 of `cs` as one pack of flows and times.
template <class T>
std::pair<detail::TriaxialConstants<T>, T> pack_of(const std::vector<Case>& cs, std::size_t first) {
  constexpr std::size_t width = Lanes<T>::width;
  std::vector<std::array<double, width>> columns;
  int steps = 0, rj_steps = 0;
  for (std::size_t l = 0; l < width; ++l) {
    detail::TriaxialConstants<double> k = triaxial_of(cs[first + l].flow).constants();
    steps = std::max(steps, k.jacobi.steps);
    rj_steps = std::max(rj_steps, k.pi.rj_max_steps);
    for (int r = k.jacobi.steps; r < kMaxLandenSteps; ++r) k.jacobi.ratio[r] = 0.0;
    std::size_t c = 0;
    detail::visit_constants(k, kMaxLandenSteps, [&](double& v) {
      if (columns.size() <= c) columns.emplace_back();
      columns[c++][l] = v;
    });
  }
  detail::TriaxialConstants<T> k;
  alignas(64) std::array<double, width> buffer;
  std::size_t c = 0;
  detail::visit_constants(k, kMaxLandenSteps, [&](T& v) {
    buffer = columns[c++];
    v = Lanes<T>::load(buffer.data());
  });
  k.jacobi.steps = steps;
  k.pi.rj_max_steps = rj_steps;
  for (std::size_t l = 0; l < width; ++l) buffer[l] = cs[first + l].t;
  return {k, Lanes<T>::load(buffer.data())};
}

/// q (w, x, y, z) and ω_b of every case, by the template on T.
template <class T>
std::vector<std::array<double, 7>> evaluate(const std::vector<Case>& cs) {
  constexpr std::size_t width = Lanes<T>::width;
  std::vector<std::array<double, 7>> out(cs.size());
  for (std::size_t first = 0; first < cs.size(); first += width) {
    const auto [k, t] = pack_of<T>(cs, first);
    const detail::FlowState<T> s = detail::triaxial_state<T>(k, t);
    const T parts[7] = {s.q.w(), s.q.x(), s.q.y(), s.q.z(), s.omega_b(0), s.omega_b(1), s.omega_b(2)};
    alignas(64) std::array<double, width> buffer;
    for (std::size_t j = 0; j < 7; ++j) {
      Lanes<T>::store(buffer.data(), parts[j]);
      for (std::size_t l = 0; l < width; ++l) out[first + l][j] = buffer[l];
    }
  }
  return out;
}

TEST(EulerPoinsotPack, DoubleIsTheFlowEulerPoinsotEvaluates) {
  // A lane padded with zero ratios beyond its own AGM steps computes the bits of its own count.
  const std::vector<Case> cs = cases();
  const auto by_double = evaluate<double>(cs);
  for (std::size_t i = 0; i < cs.size(); ++i) {
    const EulerPoinsot::State s = cs[i].flow.state(cs[i].t);
    const double expected[7] = {s.q.w(), s.q.x(), s.q.y(), s.q.z(), s.omega_b(0), s.omega_b(1), s.omega_b(2)};
    EXPECT_EQ(std::memcmp(expected, by_double[i].data(), sizeof expected), 0) << "case " << i;
  }
}

TEST(EulerPoinsotPack, TheReferencePackEqualsDoubleBitForBit) {
  const std::vector<Case> cs = cases();
  const auto a = evaluate<double>(cs), b = evaluate<RefPackW>(cs);
  for (std::size_t i = 0; i < cs.size(); ++i) {
    EXPECT_EQ(std::memcmp(a[i].data(), b[i].data(), sizeof(double) * 7), 0) << "case " << i;
  }
}

TEST(EulerPoinsotPack, TheSimdPackAgreesWithDoubleToItsFunctionsRounding) {
  // The SIMD lanes differ from double only where xsimd's sin, cos, asin, atan and hypot round their last
  // bit otherwise than glibc's. Those differences enter the phase u (through am: absolute ~ε·K) and
  // φ = rate·t + κ(Π − Π₀), whose rounding is relative to |φ| (and so grows with t, as the double
  // flow's own rounding does: euler_poinsot_test.cpp); ω_b moves with the phase u = λt + u₀. Bound, with
  // |phase| = |rate·t| + |λt|: 32ε(1 + |phase|) rad in attitude and 4ε(1 + |phase|)|ω| in ω_b: the
  // measured maxima (printed; 10.6ε and 0.8ε on AVX-512) with a margin of 3.
  const std::vector<Case> cs = cases();
  const auto a = evaluate<double>(cs), b = evaluate<SimdPack>(cs);
  double worst_angle = 0.0, worst_omega = 0.0;
  for (std::size_t i = 0; i < cs.size(); ++i) {
    const Quat qa(a[i][0], a[i][1], a[i][2], a[i][3]), qb(b[i][0], b[i][1], b[i][2], b[i][3]);
    const Vec3 wa(a[i][4], a[i][5], a[i][6]), wb(b[i][4], b[i][5], b[i][6]);
    const detail::TriaxialRotation* tri = &triaxial_of(cs[i].flow);
    const double phi = std::abs(tri->constants().rate * cs[i].t) +
                       std::abs(tri->constants().lambda * cs[i].t);
    const double angle = 2.0 * std::asin(std::min(1.0, (qa.conjugate() * qb).vec().norm()));
    EXPECT_LE(angle, 32 * kEps * (1.0 + phi)) << "case " << i << ", t = " << cs[i].t;
    EXPECT_LE((wa - wb).norm(), 4 * kEps * (1.0 + phi) * wa.norm()) << "case " << i;
    worst_angle = std::max(worst_angle, angle / (kEps * (1.0 + phi)));
    worst_omega = std::max(worst_omega, (wa - wb).norm() / (kEps * (1.0 + phi) * wa.norm()));
  }
  std::printf(
      "[ measured ] SIMD lanes against double: attitude %.2f eps (1 + |phase|), omega_b %.2f eps (1 + "
      "|phase|) |omega|\n",
      worst_angle, worst_omega);
}

}  // namespace
}  // namespace tumble

namespace tumble {
namespace {

TEST(EulerPoinsotPack, APairOfPacksEqualsOnePackBitForBit) {
  const std::vector<Case> cs = cases();
  const auto a = evaluate<SimdPack>(cs), b = evaluate<PackPair>(cs);
  for (std::size_t i = 0; i < cs.size(); ++i) {
    EXPECT_EQ(std::memcmp(a[i].data(), b[i].data(), sizeof(double) * 7), 0) << "case " << i;
  }
}

}  // namespace
}  // namespace tumble
