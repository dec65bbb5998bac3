// EulerPoinsot is a value that never touches the heap: the splitting integrator builds one per body per
// step. Proved by counting calls of the global allocation functions, replaced for the whole test binary
// (tests/support/allocation_counter.cpp). The counter is off except inside the measured region of a
// test, which holds no assertion (gtest allocates when it reports).
#include "tumble/integrate/euler_poinsot.hpp"

#include <gtest/gtest.h>

#include "../support/allocation_counter.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdlib>
#include <memory>
#include <new>
#include <vector>

namespace tumble {
namespace {

/// The number of allocations made by f() (the counter is on only while f runs).
template <class F>
long allocations_in(F&& f) {
  const test::CountAllocations counting;
  f();
  return counting.count();
}

using Regime = EulerPoinsot::Regime;

struct Case {
  Vec3 Lambda;
  Vec3 omega;
  Regime regime;
};

// Every regime, the triaxial ones in unsorted axes, and both kinds of separatrix (the elliptic one and
// steady spin about the intermediate axis).
const Case kCases[] = {
    {Vec3(1, 2, 3), Vec3::Zero(), Regime::rest},
    {Vec3(2.0, 2.0, 2.0), Vec3(1.0, -2.0, 0.5), Regime::sphere},
    {Vec3(0.6, 1.0, 0.6), Vec3(0.8, 5.0, -0.3), Regime::axisymmetric},
    {Vec3(4.0, 2.5, 1.5), Vec3(0.4, 0.5, 2.0), Regime::about_minor_axis},
    {Vec3(2.5, 4.0, 1.5), Vec3(5.0, 0.4, -0.3), Regime::about_major_axis},
    {Vec3(1.5, 2.5, 4.0), Vec3(0.002, 6.0, 0.0), Regime::about_minor_axis},  // k′² = 1e-7: reflected
    {Vec3(3.0, 5.0, 6.0), Vec3(1.0, 2.0, -1.0), Regime::separatrix},
    {Vec3(1.5, 4.0, 2.5), Vec3(0.0, 0.0, 3.0), Regime::separatrix},
};

Quat some_rotation() { return Quat(Eigen::AngleAxisd(0.7, Vec3(1, 2, 3).normalized())); }

TEST(EulerPoinsotAllocations, TheCounterSeesAHeapAllocation) {
  // The measurement is not vacuous: what EulerPoinsot did before (a shared_ptr to its flow) counts.
  std::shared_ptr<double> kept;
  EXPECT_GE(allocations_in([&] { kept = std::make_shared<double>(1.0); }), 1);
  std::vector<double> v;
  EXPECT_GE(allocations_in([&] { v.resize(1000); }), 1);
  EXPECT_EQ(v.size() + static_cast<std::size_t>(*kept), 1001u);
  // ... and only there: the allocations above were made with the counter on, these are not counted.
  const long before = test::allocations_counted();
  v.resize(5000);
  kept = std::make_shared<double>(2.0);
  EXPECT_EQ(test::allocations_counted(), before);
}

TEST(EulerPoinsotAllocations, ConstructionCopyAndEvaluationAllocateNothingInAnyRegime) {
  for (const Case& c : kCases) {
    // Outside the measured region: the case is what it claims to be.
    ASSERT_EQ(regime_name(EulerPoinsot(c.Lambda, some_rotation(), c.omega).regime()), regime_name(c.regime));

    Regime regime = Regime::rest;
    Vec3 sum_w = Vec3::Zero();
    Quat q = Quat::Identity();
    double periods = 0.0;
    const long n = allocations_in([&] {
      const EulerPoinsot ep(c.Lambda, some_rotation(), c.omega);
      const EulerPoinsot from_matrix(c.Lambda, some_rotation().toRotationMatrix(), c.omega);
      EulerPoinsot copy(ep);
      copy = from_matrix;
      copy = ep;
      regime = copy.regime();
      for (double t : {0.0, 0.37, -2.5, 13.0, 1e6}) {
        sum_w += ep.omega_b(t) + copy.omega_w(t);
        q = copy.q(t) * ep.q(t);
        sum_w += from_matrix.R(t) * c.omega;
      }
      periods = ep.period_omega() + ep.flip_interval() + ep.energy() + ep.angular_momentum_w().norm();
    });
    EXPECT_EQ(n, 0) << regime_name(c.regime);
    // The results were computed (and are used, so nothing above is optimised away).
    EXPECT_EQ(regime, c.regime);
    EXPECT_TRUE(sum_w.allFinite());
    EXPECT_NEAR(q.norm(), 1.0, 1e-15);
    EXPECT_FALSE(std::isnan(periods));
  }
}

}  // namespace
}  // namespace tumble
