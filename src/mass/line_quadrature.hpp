#pragma once
// One-dimensional rules for the tensor-product quadrature of primitives (private to the mass layer).
#include <vector>

namespace tumble::detail {

/// ∫_a^b f(x) dx ≈ Σ_k w_k f(x_k).
struct LineRule {
  std::vector<double> nodes;
  std::vector<double> weights;
};

/// n-point Gauss–Legendre on [a, b]: exact for polynomials of degree ≤ 2n − 1.
LineRule gauss_legendre(int n, double a, double b);

/// n-point trapezoid rule over one period [0, 2π) of a periodic function: nodes 2πk/n, weights 2π/n.
/// Exact for trigonometric polynomials of degree ≤ n − 1; spectrally convergent for smooth periodic f.
LineRule periodic_trapezoid(int n);

}  // namespace tumble::detail
