// Grundmann–Möller simplex rules in three dimensions (A. Grundmann, H. M. Möller, "Invariant
// integration formulas for the n-simplex by combinatorial methods", SIAM J. Numer. Anal. 15 (1978)
// 282–290, Theorem 4). For the n-simplex, s ≥ 0, degree d = 2s + 1:
//
//   ∫_{T_n} f ≈ n!|T_n| Σ_{i=0}^{s} (−1)^i 2^{−2s} (d + n − 2i)^d / (i! (d + n − i)!)
//                        Σ_{|β| = s−i, β ∈ ℕ^{n+1}} f(λ),   λ_j = (2β_j + 1) / (d + n − 2i),
//
// with λ the barycentric coordinates of the point. The weights in closed form make the rule cheap to
// build at any degree; they alternate in sign between the levels i, which amplifies rounding by
// Σ|w| (2.6 at degree 3, 545 at degree 17) — the reason tumble caps the degree.
//
// Written here because no packaged library provides simplex rules: Boost.Math has 1-D rules only,
// Eigen none; the Python quadpy is not a C++ dependency.
#include "tet_quadrature.hpp"

#include <cmath>
#include <fmt/format.h>

#include "tumble/error.hpp"

namespace tumble::detail {
namespace {

double factorial(int k) {
  double f = 1.0;  // exact in double up to 18!, correctly rounded products beyond
  for (int j = 2; j <= k; ++j) f *= j;
  return f;
}

}  // namespace

TetRule grundmann_moller_tet(int degree) {
  if (degree < 1 || degree % 2 == 0) {
    throw InvalidArgument(fmt::format(
        "Grundmann-Moller rules have odd degree 2s+1 >= 1, not {}: ask for an odd degree", degree));
  }
  constexpr int n = 3;
  const int s = (degree - 1) / 2;
  const int d = degree;
  TetRule rule;
  rule.degree = d;
  for (int i = 0; i <= s; ++i) {
    const double denom = d + n - 2 * i;
    // n! · (−1)^i 2^{−2s} (d+n−2i)^d / (i! (d+n−i)!): the n! turns the weights into volume fractions.
    const double sign = i % 2 == 0 ? 1.0 : -1.0;
    const double w = factorial(n) * sign * std::ldexp(1.0, -2 * s) * std::pow(denom, d) /
                     (factorial(i) * factorial(d + n - i));
    // Every β = (β0, β1, β2, β3) ∈ ℕ⁴ with |β| = s − i.
    const int total = s - i;
    for (int b0 = 0; b0 <= total; ++b0) {
      for (int b1 = 0; b0 + b1 <= total; ++b1) {
        for (int b2 = 0; b0 + b1 + b2 <= total; ++b2) {
          const int b3 = total - b0 - b1 - b2;
          rule.barycentric.emplace_back((2 * b0 + 1) / denom, (2 * b1 + 1) / denom, (2 * b2 + 1) / denom,
                                        (2 * b3 + 1) / denom);
          rule.weights.push_back(w);
        }
      }
    }
  }
  return rule;
}

}  // namespace tumble::detail
