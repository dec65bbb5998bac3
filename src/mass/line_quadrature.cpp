// Gauss–Legendre from Boost.Math's Legendre zeros (boost::math::quadrature::gauss fixes the point count
// at compile time and tabulates only some counts; the degree here is chosen at run time), and the
// periodic trapezoid rule.
#include "line_quadrature.hpp"

#include <boost/math/special_functions/legendre.hpp>
#include <cmath>
#include <numbers>

namespace tumble::detail {

LineRule gauss_legendre(int n, double a, double b) {
  // Nodes: the zeros of P_n (Boost returns the non-negative ones; the rest are their mirror images).
  // Weights: w = 2 / ((1 − x²) P_n'(x)²) on [−1, 1], scaled by (b − a)/2.
  LineRule rule;
  const double half = 0.5 * (b - a), mid = 0.5 * (a + b);
  for (const double x : boost::math::legendre_p_zeros<double>(n)) {
    const double dp = boost::math::legendre_p_prime(n, x);
    const double w = 2.0 / ((1.0 - x * x) * dp * dp);
    rule.nodes.push_back(mid + half * x);
    rule.weights.push_back(half * w);
    if (x != 0.0) {
      rule.nodes.push_back(mid - half * x);
      rule.weights.push_back(half * w);
    }
  }
  return rule;
}

LineRule periodic_trapezoid(int n) {
  LineRule rule;
  const double h = 2.0 * std::numbers::pi / n;
  for (int k = 0; k < n; ++k) {
    rule.nodes.push_back(k * h);
    rule.weights.push_back(h);
  }
  return rule;
}

}  // namespace tumble::detail
