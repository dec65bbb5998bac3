// How many duplication steps carlson_rj (math/carlson.hpp) needs for the arguments of one exact flow,
// measured: carlson_rj is evaluated in long double (its rounding then ~ε/2048, far below the truncation
// being measured) and compared with Boost's ellint_rj in long double, over x = cn² ∈ [k′/(1 + k′), 1]
// (random, and the ends), y = x + m₁(1 − x), z = 1, and both p the flow forms (1 + N s², and the
// reflected 1 − n′ s²). For each m₁ the smallest M with truncation ≤ 0.05ε at every point is found for
// 40 characteristics N from 0 to 1e12, and base(m₁) = max over N of M − ⌈log₄(1 + N)⌉ is printed
// beside the count carlson_rj_steps gives (which must not be smaller than the need). About 40 s.
//
//   build/release/bin/carlson_rj_steps
#include <boost/math/special_functions/ellint_rj.hpp>
#include <cmath>
#include <cstdio>
#include <random>

namespace tumble {
// The number-type interface carlson_rj needs, for long double (declared before the template).
inline long double select(bool condition, long double a, long double b) { return condition ? a : b; }
}  // namespace tumble

#include "tumble/math/carlson.hpp"

namespace {

using L = long double;
constexpr double kEps = 2.220446049250313e-16;

int ceil_log4(double N) {
  int c = 0;
  for (double power = 1.0; power < 1.0 + N; power *= 4.0) ++c;
  return c;
}

/// Worst relative truncation error (in ε) of carlson_rj with M steps over the flow's arguments.
double worst_error(double m1, double N, int M, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  const L k1 = std::sqrt(static_cast<L>(m1)), x_min = k1 / (1 + k1);
  double worst = 0.0;
  for (int i = 0; i < 200; ++i) {
    L x = x_min * std::pow(1 / x_min, static_cast<L>(uniform(rng)));
    if (i == 0) x = x_min;
    if (i == 1) x = 1.0L - 1e-20L;
    if (i == 2) x = 1.0L;
    const L s2 = 1 - x, y = x + static_cast<L>(m1) * s2, n = static_cast<L>(N);
    for (const L p : {1 + n * s2, 1 - ((1 - static_cast<L>(m1)) + n) / (1 + n) * s2}) {
      const L reference = boost::math::ellint_rj(x, y, 1.0L, p);
      const L value = tumble::carlson_rj<L>(x, y, 1.0L, p, static_cast<L>(M), M);
      worst = std::max(worst, static_cast<double>(std::abs(value - reference) / reference) / kEps);
    }
  }
  return worst;
}

}  // namespace

int main() {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  std::printf("%10s %8s %22s %s\n", "m1", "base", "carlson_rj_steps base", "");
  bool short_anywhere = false;
  for (int im = 0; im <= 64; ++im) {
    const double m1 = std::pow(10.0, -16.0 + 0.25 * im);
    int base = 0;
    for (int iN = 0; iN < 40; ++iN) {
      const double N = iN == 0 ? 0.0 : std::pow(10.0, -3.0 + 15.0 * uniform(rng));
      int need = 64;
      for (int M = 2; M < 64; ++M) {
        if (worst_error(m1, N, M, rng) <= 0.05) {
          need = M;
          break;
        }
      }
      base = std::max(base, need - ceil_log4(N));
    }
    const int used = tumble::carlson_rj_steps(0.0, m1);  // its base, with the margin
    const bool enough = used >= base;
    short_anywhere = short_anywhere || !enough;
    std::printf("%10.3g %8d %22d %s\n", m1, base, used, enough ? "" : "TOO FEW");
  }
  return short_anywhere ? 1 : 0;
}
