// One source of each equation: every template the batched engine instantiates on a SIMD pack is
// instantiated here on double (one body per call), on a reference pack (tests/support/ref_pack.hpp:
// lane-wise scalar operators) and on the engine's xsimd pack, and the lanes are compared bit for bit.
// Inputs mix magnitudes and signs lane by lane, and quat_exp gets small and large angles in the same
// pack, so a template that branched on one lane's value would show up as a wrong lane.
#include <gtest/gtest.h>

#include <bit>
#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include "../support/ref_pack.hpp"
#include "integrate/stages.hpp"
#include "tumble/dynamics/columns.hpp"
#include "tumble/math/simd.hpp"

namespace tumble {
namespace {

using SimdPack = xsimd::batch<double>;
constexpr std::size_t W = SimdPack::size;
using RefPackW = test::RefPack<W>;
constexpr std::size_t kBodies = 8 * W;  // several packs

template <class T>
void put(std::vector<T>& out, const Vec3T<T>& v) {
  for (int k = 0; k < 3; ++k) out.push_back(v(k));
}
template <class T>
void put(std::vector<T>& out, const QuatT<T>& q) {
  out.insert(out.end(), {q.w(), q.x(), q.y(), q.z()});
}
template <class T>
void put(std::vector<T>& out, const CoordinateRates<T>& r) {
  put(out, r.o_dot), put(out, r.q_dot), put(out, r.v_dot), put(out, r.omega_dot);
}
template <class T>
void put(std::vector<T>& out, const Coordinates<T>& c) {
  put(out, c.o), put(out, c.q), put(out, c.v), put(out, c.omega);
}

/// Columns of random inputs: the state of a body (13), m, Λ (3), f, τ (6), a step h and a rotation
/// vector φ (3) whose size ranges from 1e-6 (the Taylor branch of quat_exp) to 3 rad.
Columns random_inputs() {
  Columns in(kBodies, 27);
  std::mt19937_64 rng(2024);
  std::normal_distribution<double> normal;
  std::uniform_real_distribution<double> uniform(0.5, 2.0);
  for (std::size_t i = 0; i < kBodies; ++i) {
    const Quat q = Quat(normal(rng), normal(rng), normal(rng), normal(rng)).normalized();
    const double state[13] = {normal(rng),
                              normal(rng),
                              normal(rng),
                              q.w(),
                              q.x(),
                              q.y(),
                              q.z(),
                              normal(rng),
                              normal(rng),
                              normal(rng),
                              10 * normal(rng),
                              10 * normal(rng),
                              10 * normal(rng)};
    for (std::size_t k = 0; k < 13; ++k) in[k][i] = state[k];
    in[13][i] = uniform(rng);                                                           // m
    for (std::size_t k = 14; k < 17; ++k) in[k][i] = 0.1 * uniform(rng);                // Λ
    for (std::size_t k = 17; k < 23; ++k) in[k][i] = normal(rng);                       // f, τ
    in[23][i] = 1e-3 * uniform(rng);                                                    // h
    const double size = std::pow(10.0, -6.0 + 6.5 * static_cast<double>(i % 5) / 4.0);  // 1e-6 … 3
    const Vec3 phi = size * Vec3(normal(rng), normal(rng), normal(rng)).normalized();
    for (std::size_t k = 0; k < 3; ++k) in[24 + k][i] = phi(static_cast<Eigen::Index>(k));
  }
  return in;
}

/// f applied to every pack of T of the inputs; the outputs as columns.
template <class T, class F>
Columns evaluate(const Columns& in, F&& f) {
  Columns out;
  for (std::size_t i = 0; i < kBodies; i += Lanes<T>::width) {
    auto arg = [&](std::size_t k) { return Lanes<T>::load(in[k] + i); };
    const Coordinates<T> x{{arg(0), arg(1), arg(2)},
                           QuatT<T>(arg(3), arg(4), arg(5), arg(6)),
                           {arg(7), arg(8), arg(9)},
                           {arg(10), arg(11), arg(12)}};
    const Vec3T<T> Lambda(arg(14), arg(15), arg(16)), f_w(arg(17), arg(18), arg(19)),
        tau(arg(20), arg(21), arg(22));
    const Vec3T<T> phi(arg(24), arg(25), arg(26));
    std::vector<T> values;
    f(values, x, arg(13), Lambda, f_w, tau, arg(23), phi);
    if (out.count() == 0) out.resize(kBodies, values.size());
    for (std::size_t k = 0; k < values.size(); ++k) Lanes<T>::store(out[k] + i, values[k]);
  }
  return out;
}

/// Every lane of a equals the same lane of b, bit for bit.
void expect_identical(const Columns& a, const Columns& b, const char* what) {
  ASSERT_EQ(a.count(), b.count()) << what;
  for (std::size_t k = 0; k < a.count(); ++k) {
    for (std::size_t i = 0; i < kBodies; ++i) {
      EXPECT_EQ(std::bit_cast<std::uint64_t>(a[k][i]), std::bit_cast<std::uint64_t>(b[k][i]))
          << what << ": output " << k << ", body " << i << ": " << a[k][i] << " vs " << b[k][i];
    }
  }
}

/// The three instantiations of f, compared.
template <class F>
void check(const char* what, F&& f) {
  const Columns in = random_inputs();
  const Columns scalar = evaluate<double>(in, f);
  expect_identical(scalar, evaluate<RefPackW>(in, f), (std::string(what) + " (reference pack)").c_str());
  expect_identical(scalar, evaluate<SimdPack>(in, f), (std::string(what) + " (SIMD pack)").c_str());
}

TEST(GenericScalar, NewtonEulerInEveryFormulationIsTheSameOnDoublesAndPacks) {
  for (const Formulation F : {Formulation::world, Formulation::mixed, Formulation::body}) {
    check("newton_euler", [F](auto& out, const auto& x, auto m, const auto& Lambda, const auto& f,
                              const auto& tau, auto, const auto&) {
      using T = std::decay_t<decltype(m)>;
      put(out, newton_euler<T>(F, mass_constants<T>(m, Lambda), x, f, tau));
      const auto [o_dot, q_dot] = kinematics<T>(F, x);
      put(out, o_dot), put(out, q_dot);
    });
  }
  check("newton_euler_world", [](auto& out, const auto& x, auto m, const auto& Lambda, const auto& f,
                                 const auto& tau, auto, const auto&) {
    using T = std::decay_t<decltype(m)>;
    const MassConstants<T> c = mass_constants<T>(m, Lambda);
    put(out, newton_euler_world<T>(c, x, f, tau));
    put(out, newton_euler_mixed<T>(c, x, f, tau));
    put(out, newton_euler_body<T>(c, x, f, tau));
    put(out, euler_body<T>(c, x.omega, tau));
    put(out, rotate<T>(x.q, f)), put(out, rotate_inverse<T>(x.q, f));
  });
}

TEST(GenericScalar, StageUpdatesAndNormalisationAreTheSameOnDoublesAndPacks) {
  check("advanced, axpy, normalized", [](auto& out, const auto& x, auto m, const auto& Lambda, const auto& f,
                                         const auto& tau, auto h, const auto&) {
    using T = std::decay_t<decltype(m)>;
    const CoordinateRates<T> k = newton_euler<T>(Formulation::mixed, mass_constants<T>(m, Lambda), x, f, tau);
    put(out, advanced<T>(x, h, k));
    put(out, axpy<T>(k, T(2.0), k));
    put(out, normalized<T>(QuatT<T>(x.q.coeffs() * T(1.5))));
  });
}

TEST(GenericScalar, QuatExpIsTheSameOnDoublesAndTheReferencePackInBothBranches) {
  // Lanes of one pack take different branches (|φ| from 1e-6 to 3 rad). The reference pack uses the
  // same <cmath> functions as double: bit for bit.
  const Columns in = random_inputs();
  auto f = [](auto& out, const auto&, auto, const auto&, const auto&, const auto&, auto, const auto& phi) {
    using T = std::decay_t<decltype(phi.x())>;
    put(out, quat_exp<T>(phi));
  };
  const Columns scalar = evaluate<double>(in, f);
  expect_identical(scalar, evaluate<RefPackW>(in, f), "quat_exp");
  // xsimd's sin and cos are its own polynomial approximations, not glibc's: they may round the last
  // bit differently. Every body of a batched run goes through the pack (whatever N, block or thread),
  // so runs stay bit-identical among themselves; against double the lanes agree to 2 ulp, and no lane
  // takes the other lanes' branch (which would be off by ~1e-7, test "branch" below).
  const Columns simd = evaluate<SimdPack>(in, f);
  for (std::size_t k = 0; k < 4; ++k) {
    for (std::size_t i = 0; i < kBodies; ++i) {
      EXPECT_NEAR(simd[k][i], scalar[k][i], 2 * 2.220446049250313e-16) << "component " << k << ", body " << i;
    }
  }
}

}  // namespace
}  // namespace tumble
